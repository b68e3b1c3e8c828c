// SPDX-License-Identifier: MIT
// Inclined-channel scenario of CASES C2: six frictional walls, a released block of spheres on a
// cubic lattice, and an optional barrier (closed or slit, orthogonal "OB" or vertical "VB",
// modelled by fixed overlapping spheres or by exact boxes). Frame: X down-slope, Y across, Z
// normal to the bed; gravity 9.81 (sin θ, 0, −cos θ).
#pragma once
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"

namespace sabo::scenario {

struct ReleaseInfo {
    std::string lattice_rule;
    std::size_t count = 0;
    double solid_volume = 0.0;  // m³
    Vec3 lo{}, hi{};            // extents of the grains (surfaces), m
    double r_mean = 0.0, r_min = 0.0, r_max = 0.0, density = 0.0;
};

struct BarrierInfo {
    std::string type;         // none | closed | slit
    std::string orientation;  // OB | VB
    std::string model;        // spheres | boxes
    double face_x = 0.0;      // upstream face at Z = 0, m
    double thickness = 0.0;   // m, along the face normal
    double outlet_width = 0.0;
    Vec3 face_normal{1, 0, 0};  // unit normal of the face, pointing downstream
    // downstream face plane: points x with dot(x − downstream_point, face_normal) > 0 are downstream
    Vec3 downstream_point{};
    std::size_t first_wall = 0, wall_count = 0;  // barrier walls in the wall list
    std::size_t sphere_count = 0;                // fixed spheres (model = spheres)
};

struct ChannelCase {
    std::string name;
    dem::Particles particles;
    std::vector<dem::Wall> walls;
    Vec3 gravity{};
    double slope_deg = 0.0;
    double length = 0.0, width = 0.0, height = 0.0;
    double end_time = 0.0;
    double velocity_scale = 0.0;  // m/s, free-fall speed over the drop from the block to the barrier
    ReleaseInfo release;
    BarrierInfo barrier;
};

[[nodiscard]] ChannelCase build_channel_case(const Config& cfg);

}  // namespace sabo::scenario
