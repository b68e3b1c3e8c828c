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

// Martin & Moyce (1952), column height 2a (n² = 2): front Z = x/a at T = t sqrt(2g/a).
struct FrontPoint {
    double t_scaled, front_over_a;
};
inline constexpr FrontPoint martin_moyce_front[] = {{0.41, 1.11}, {0.84, 1.22}, {1.19, 1.44}, {1.43, 1.67},
                                                    {1.63, 1.89}, {1.83, 2.11}, {1.98, 2.33}, {2.20, 2.56},
                                                    {2.32, 2.78}, {2.51, 3.00}, {2.65, 3.22}, {2.83, 3.44},
                                                    {2.97, 3.67}, {3.11, 3.89}, {3.33, 4.11}};

}  // namespace sabo::scenario
