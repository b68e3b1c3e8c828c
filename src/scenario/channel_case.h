// SPDX-License-Identifier: MIT
// Inclined-channel scenario of CASES C2: six frictional walls, a released block of spheres on a
// cubic lattice, and an optional barrier (scenario/barrier.h). Frame: X down-slope, Y across, Z
// normal to the bed; gravity 9.81 (sin θ, 0, −cos θ).
#pragma once
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "scenario/barrier.h"

namespace sabo::scenario {

struct ReleaseInfo {
    std::string lattice_rule;
    std::size_t count = 0;
    double solid_volume = 0.0;  // m³
    Vec3 lo{}, hi{};            // extents of the grains (surfaces), m
    double r_mean = 0.0, r_min = 0.0, r_max = 0.0, density = 0.0;
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
