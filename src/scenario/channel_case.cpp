// SPDX-License-Identifier: MIT
#include "scenario/channel_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "core/error.h"

namespace sabo::scenario {

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Uniform double in [0,1) from the raw 64-bit engine: portable across standard libraries.
double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

void build_walls(ChannelCase& c) {
    using dem::Wall;
    c.walls.push_back(Wall::plane("bed", {0, 0, 0}, {0, 0, 1}));
    c.walls.push_back(Wall::plane("ceiling", {0, 0, c.height}, {0, 0, -1}));
    c.walls.push_back(Wall::plane("side_y0", {0, 0, 0}, {0, 1, 0}));
    c.walls.push_back(Wall::plane("side_y1", {0, c.width, 0}, {0, -1, 0}));
    c.walls.push_back(Wall::plane("upstream_end", {0, 0, 0}, {1, 0, 0}));
    c.walls.push_back(Wall::plane("downstream_end", {c.length, 0, 0}, {-1, 0, 0}));
}

void build_release(const Config& cfg, ChannelCase& c) {
    ReleaseInfo& info = c.release;
    const double r_mean = cfg.real_or("release.radius_mean_m", 0.05, Range::positive());
    info.r_mean = r_mean;
    const double spread = cfg.real_or("release.radius_spread", 0.05, Range::closed(0.0, 0.5));
    info.density = cfg.real_or("release.density_kg_m3", 2500.0, Range::positive());
    const double target = cfg.real_or("release.solid_volume_m3", 4.03, Range::positive());
    const double block_l = cfg.real_or("release.length_m", 4.60, Range::positive());
    const double block_w = cfg.real_or("release.width_m", 1.90, Range::positive());
    const double front = cfg.real_or("release.front_x_m", 4.725, Range::positive());
    const auto seed = static_cast<std::uint64_t>(cfg.integer_or("release.seed", 12345, 0, INT64_MAX));
    info.r_min = r_mean * (1.0 - spread);
    info.r_max = r_mean * (1.0 + spread);

    // Lattice rule: simple cubic, spacing = largest diameter (no overlap whatever the draw),
    // nx × ny columns = round(length/s) × round(width/s), filled layer by layer from the bed until
    // the solid volume reaches the target. The front grain surface touches X = front_x_m.
    const double s = 2.0 * info.r_max;
    const int nx = std::max(1, static_cast<int>(std::lround(block_l / s)));
    const int ny = std::max(1, static_cast<int>(std::lround(block_w / s)));
    if (ny * s > c.width)
        cfg.fail("release.width_m", fmt::format("block wider than the channel ({} m)", c.width));
    const double x0 = front - 0.5 * s - (nx - 1) * s;
    if (x0 - 0.5 * s < 0.0)
        cfg.fail("release.front_x_m", "the block would start upstream of the channel end X = 0");
    const double y0 = 0.5 * (c.width - ny * s) + 0.5 * s;
    const double z0 = 0.5 * s + 0.001;  // 1 mm above the bed
    std::mt19937_64 rng(seed);
    double volume = 0.0;
    int layer = 0;
    while (volume < target) {
        const double z = z0 + layer * s;
        if (z + 0.5 * s > c.height) {
            cfg.fail(
                "release.solid_volume_m3",
                fmt::format("a {:.2f} x {:.2f} m block of this volume does not fit under the {} m ceiling",
                            nx * s, ny * s, c.height));
        }
        for (int j = 0; j < ny && volume < target; ++j) {
            for (int i = 0; i < nx && volume < target; ++i) {
                const double r = r_mean * (1.0 + spread * (2.0 * uniform01(rng) - 1.0));
                c.particles.add_mobile({x0 + i * s, y0 + j * s, z}, r, info.density);
                volume += 4.0 / 3.0 * std::numbers::pi * r * r * r;
            }
        }
        ++layer;
    }
    info.count = c.particles.n_mobile;
    info.solid_volume = volume;
    info.lo = {x0 - 0.5 * s, y0 - 0.5 * s, z0 - 0.5 * s};
    info.hi = {x0 + (nx - 0.5) * s, y0 + (ny - 0.5) * s, z0 + (layer - 0.5) * s};
    info.lattice_rule = fmt::format(
        "simple cubic, spacing {:.4f} m (largest diameter), {} x {} columns, {} layers "
        "(last one partly filled), filled bottom-up until V_s >= {:.3f} m3",
        s, nx, ny, layer, target);
}

}  // namespace

ChannelCase build_channel_case(const Config& cfg) {
    ChannelCase c;
    c.name = cfg.text_or("case.name", "channel");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    c.slope_deg = cfg.real("channel.slope_deg", Range::closed(0.0, 60.0));
    c.length = cfg.real_or("channel.length_m", 20.0, Range::positive());
    c.width = cfg.real_or("channel.width_m", 2.10, Range::positive());
    c.height = cfg.real_or("channel.height_m", 1.35, Range::positive());
    const double g = cfg.real_or("channel.gravity_m_s2", 9.81, Range::non_negative());
    c.gravity = {g * std::sin(c.slope_deg * deg), 0.0, -g * std::cos(c.slope_deg * deg)};
    build_walls(c);
    build_release(cfg, c);
    c.barrier = build_barrier(cfg, {c.length, c.width, c.height, c.slope_deg}, c.release.r_mean, c.walls,
                              c.particles);
    // Velocity scale: frictionless slide of the block front to the barrier (or the channel end)
    // plus the fall of the block height — the impact speed used for contact-time and overlap
    // estimates (docs/dem.md).
    const double stop_x = c.barrier.present() ? c.barrier.face_x : c.length;
    const double drop = std::max(0.0, stop_x - c.release.hi.x) * std::sin(c.slope_deg * deg) + c.release.hi.z;
    c.velocity_scale = cfg.real_or("dem.velocity_scale_m_s", std::sqrt(2.0 * g * drop), Range::positive());
    return c;
}

}  // namespace sabo::scenario
