// SPDX-License-Identifier: MIT
#include "cases/dam_break/dam_break_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "core/memory.h"

namespace sabo::cases {

PreparedDamBreak prepare_dam_break(const sim::RunRequest& req, const Config& cfg) {
    PreparedDamBreak pc;
    pc.scene = scenario::read_dam_break_case(cfg);
    const auto& s = pc.scene;
    pc.fluid = lbm::read_fluid_settings(cfg);
    const double dx = pc.fluid.units.dx();
    const auto cells = [&](double length) { return static_cast<int>(std::lround(length / dx)); };
    pc.shape = {cells(s.tank_length), s.width_cells, cells(s.tank_height), {false, true, false}};
    pc.column_cells = cells(s.column_width);
    pc.height_cells = cells(s.column_height);
    if (pc.column_cells < 4 || pc.height_cells < 4)
        cfg.fail("lattice.dx_m",
                 fmt::format("the column must span at least 4 cells each way (a = {} cells, h = {} "
                             "cells): refine dx",
                             pc.column_cells, pc.height_cells));
    lbm::check_fluid_settings(cfg, pc.fluid, {s.velocity_scale(), s.gravity, s.column_height, pc.shape},
                              memory_of_all_machines_bytes());
    pc.output = sim::read_output_settings(cfg, req, s.name, s.end_time / 20.0, s.end_time / 500.0);
    cfg.record("derived.column_width_cells", static_cast<std::int64_t>(pc.column_cells));
    cfg.record("derived.column_height_cells", static_cast<std::int64_t>(pc.height_cells));
    cfg.finish();
    return pc;
}

void print_derived(const PreparedDamBreak& pc) {
    const auto& s = pc.scene;
    const double dx = pc.fluid.units.dx();
    spdlog::info(
        "case '{}': dam break, column a = {:.4f} m x h = {:.4f} m ({} x {} cells) in a tank {:.4f} x {:.4f} "
        "m, "
        "{} cells across (periodic)",
        s.name, pc.column_cells * dx, pc.height_cells * dx, pc.column_cells, pc.height_cells, s.tank_length,
        s.tank_height, s.width_cells);
    for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
    for (const auto& w : lbm::warnings(pc.fluid)) spdlog::warn("{}", w);
    spdlog::info("velocity scale 2 sqrt(g h) = {:.3f} m/s; {} steps to t = {} s", s.velocity_scale(),
                 static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time);
}

}  // namespace sabo::cases
