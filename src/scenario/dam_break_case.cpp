// SPDX-License-Identifier: MIT
#include "scenario/dam_break_case.h"

#include <fmt/format.h>

#include <cmath>

namespace sabo::scenario {

double DamBreakCase::velocity_scale() const {
    return 2.0 * std::sqrt(gravity * column_height);
}

DamBreakCase read_dam_break_case(const Config& cfg) {
    DamBreakCase c;
    c.name = cfg.text_or("case.name", "dam_break");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    c.column_width = cfg.real("dam_break.column_width_m", Range::positive());
    c.column_height = cfg.real("dam_break.column_height_m", Range::positive());
    c.tank_length = cfg.real("dam_break.tank_length_m", Range::positive());
    c.tank_height = cfg.real_or("dam_break.tank_height_m", 1.2 * c.column_height, Range::positive());
    c.width_cells = static_cast<int>(cfg.integer_or("dam_break.width_cells", 4, 1, 100000));
    c.gravity = cfg.real_or("dam_break.gravity_m_s2", 9.81, Range::positive());
    if (c.column_width >= c.tank_length)
        cfg.fail("dam_break.column_width_m",
                 fmt::format("must be shorter than the tank ({} m)", c.tank_length));
    if (c.column_height > c.tank_height)
        cfg.fail("dam_break.column_height_m", fmt::format("must fit the tank height ({} m)", c.tank_height));
    return c;
}

}  // namespace sabo::scenario
