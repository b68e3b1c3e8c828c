// SPDX-License-Identifier: MIT
// A box full of fluid with grains at given places (case.type = "fluid_box"): settling, sedimentation, drag
// and buoyancy experiments as case files. The box spans [0, length] × [0, width] × [0, height] (X, Y, Z),
// gravity along −Z; its faces are walls for the fluid (bounce-back) and for the grains (frictional planes),
// or, along an axis made periodic, the fluid wraps (a periodic box holds its grains in place: they do not
// cross its faces). A body force on the fluid along X (`drive`, standing for a mean pressure gradient)
// drives a flow past held grains. The grains come from a CSV file: one per row, `x_m, y_m, z_m, radius_m`
// and optionally `vx_m_s, vy_m_s, vz_m_s` (their velocity at the start), header first.
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"

namespace sabo::scenario {

struct FluidBoxCase {
    std::string name;
    double end_time = 0.0;                          // s
    Vec3 size{};                                    // m
    double gravity = 9.81;                          // m/s², along −Z
    std::filesystem::path grains_file;              // absolute
    double density = 0.0;                           // kg/m³, the grains'
    dem::Particles particles;                       // the grains (all mobile)
    double r_min = 0.0, r_max = 0.0, r_mean = 0.0;  // m
    std::vector<dem::Wall> walls;
    std::array<bool, 3> periodic{};  // X, Y, Z: the fluid wraps, no walls there
    double drive = 0.0;              // m/s², the fluid's body force per unit mass along +X
    bool held = false;               // the grains stay where the file puts them, at rest
    double velocity_scale = 0.0;     // m/s
};

// Reads [case], [box] and [grains] and the grains' file (relative to the case file's folder). Refuses (with
// the key, or the file and line) a grain outside the box or overlapping another, a file without grains, a
// periodic box with grains not held, a box periodic along gravity, a drive without a periodic X.
// `fluid_density` (kg/m³) and `fluid_viscosity` (Pa·s): the fluid's, for the default velocity scale.
[[nodiscard]] FluidBoxCase read_fluid_box_case(const Config& cfg, double fluid_density,
                                               double fluid_viscosity);

}  // namespace sabo::scenario
