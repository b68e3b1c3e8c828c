// SPDX-License-Identifier: MIT
// Sandpile of reference case C1 (Zhou et al. 2002 set-up): a box 20 d wide (Y) with a fixed middle plate of
// length L_p and an outlet of 5 d on each side of it, closed by gates while the grains, generated at
// random without overlap above the plate, settle; then the gates vanish and the grains drain to the
// floor below. What stays on the plate is the heap. Frame: X along the plate, Y across, Z up; the
// floor is Z = 0 and the box spans X in [0, L_p + 2 outlets]. docs/case_files.md lists the keys.
#pragma once
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"

namespace sabo::scenario {

struct SandpileCase {
    std::string name;
    dem::Particles particles;
    std::vector<dem::Wall> walls;
    std::vector<std::size_t> gates;  // indices into walls: the two outlet gates
    Vec3 gravity{};
    double diameter = 0.0, density = 0.0;
    std::size_t count = 0;
    double length = 0.0, width = 0.0, height = 0.0;  // m, the box
    double plate_x_lo = 0.0, plate_x_hi = 0.0;       // m, plate ends
    double plate_z = 0.0;                            // m, plate surface
    double plate_thickness = 0.0;                    // m
    double fill_height = 0.0;                        // m, generation region above the plate
    double fill_fraction = 0.0;                      // solid fraction of the generated mass
    int parts_per_side = 10;
    double settle_max_time = 0.0;  // s, longest settling with the gates closed
    double end_time = 0.0;         // s, longest run (settling + draining)
    double velocity_scale = 0.0;   // m/s, fall from the top of the generated mass to the floor
};

// Throws InputError (file, key, range) on bad input or when the grains do not fit the fill region.
// `place_grains` false: everything but the grains themselves (`sabo check`: the count is the case's).
[[nodiscard]] SandpileCase build_sandpile_case(const Config& cfg, bool place_grains = true);

}  // namespace sabo::scenario
