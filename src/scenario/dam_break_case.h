// SPDX-License-Identifier: MIT
// The dam break (issue 5): a fluid column of width a and height h at the left end of a closed tank
// collapses under gravity; its front along the floor is compared with Martin & Moyce (1952). A slab
// a few cells thick, periodic across, makes the flow two-dimensional like the experiment's.
#pragma once
#include <string>

#include "core/config.h"

namespace sabo::scenario {

struct DamBreakCase {
    std::string name;
    double end_time = 0.0;                        // s
    double column_width = 0.0;                    // m, a
    double column_height = 0.0;                   // m, h
    double tank_length = 0.0, tank_height = 0.0;  // m
    int width_cells = 4;                          // cells across (periodic)
    double gravity = 9.81;                        // m/s², along −Z
    // Ritter's front speed 2 sqrt(g h): no point of the flow moves faster
    [[nodiscard]] double velocity_scale() const;
};

// Reads [case] and [dam_break]; throws InputError (file, key, range).
[[nodiscard]] DamBreakCase read_dam_break_case(const Config& cfg);

}  // namespace sabo::scenario
