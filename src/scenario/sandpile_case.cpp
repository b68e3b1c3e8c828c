// SPDX-License-Identifier: MIT
#include "scenario/sandpile_case.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <unordered_map>

#include "core/error.h"
#include "dem/grain_budget.h"

namespace sabo::scenario {

namespace {

// Random sequential addition of equal spheres in a box, with a cell hash of edge d so each trial
// checks 27 cells. Reaches solid fractions up to ~0.35 quickly; refuses (false) after
// `max_trials` consecutive misses.
bool place_random(dem::Particles& p, std::size_t count, double r, double density, const Vec3& lo,
                  const Vec3& hi, std::uint64_t seed) {
    const double d = 2.0 * r;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
    auto key = [&](const Vec3& x) {
        const auto i = static_cast<std::int64_t>(std::floor((x.x - lo.x) / d));
        const auto j = static_cast<std::int64_t>(std::floor((x.y - lo.y) / d));
        const auto k = static_cast<std::int64_t>(std::floor((x.z - lo.z) / d));
        return (i * 1048576 + j) * 1048576 + k;
    };
    std::unordered_multimap<std::int64_t, Vec3> cells;
    cells.reserve(count * 2);
    constexpr int max_trials = 100000;
    for (std::size_t n = 0; n < count; ++n) {
        int trials = 0;
        while (true) {
            if (++trials > max_trials) return false;
            const Vec3 x{ux(rng), uy(rng), uz(rng)};
            bool free = true;
            for (int a = -1; a <= 1 && free; ++a) {
                for (int b = -1; b <= 1 && free; ++b) {
                    for (int c = -1; c <= 1 && free; ++c) {
                        const auto range = cells.equal_range(key(x + Vec3{a * d, b * d, c * d}));
                        for (auto it = range.first; it != range.second; ++it) {
                            if (norm2(it->second - x) < d * d) {
                                free = false;
                                break;
                            }
                        }
                    }
                }
            }
            if (!free) continue;
            cells.emplace(key(x), x);
            p.add_mobile(x, r, density);
            break;
        }
    }
    return true;
}

}  // namespace

SandpileCase build_sandpile_case(const Config& cfg, bool place_grains) {
    SandpileCase c;
    c.name = cfg.text_or("case.name", "sandpile");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    const double d = cfg.real("sandpile.diameter_m", Range::positive());
    c.diameter = d;
    c.density = cfg.real_or("sandpile.density_kg_m3", 2500.0, Range::positive());
    c.count = static_cast<std::size_t>(cfg.integer_or("sandpile.particles", 10000, 1, 100000000));
    const double width = cfg.real_or("sandpile.width_over_d", 20.0, Range::closed(2.0, 1e4)) * d;
    const double plate = cfg.real_or("sandpile.plate_length_over_d", 40.0, Range::closed(4.0, 1e5)) * d;
    const double outlet = cfg.real_or("sandpile.outlet_length_over_d", 5.0, Range::closed(1.5, 1e4)) * d;
    const double below = cfg.real_or("sandpile.plate_height_over_d", 20.0, Range::closed(2.0, 1e5)) * d;
    const double thick = cfg.real_or("sandpile.plate_thickness_over_d", 1.0, Range::closed(0.1, 100.0)) * d;
    c.parts_per_side = static_cast<int>(cfg.integer_or("sandpile.parts_per_side", 10, 3, 1000));
    c.settle_max_time = cfg.real_or("sandpile.settle_max_time_s", 0.25 * c.end_time, Range::positive());
    if (c.settle_max_time >= c.end_time)
        cfg.fail("sandpile.settle_max_time_s", fmt::format("must be below case.end_time_s = {}", c.end_time));
    const auto seed = static_cast<std::uint64_t>(cfg.integer_or("sandpile.seed", 12345, 0, INT64_MAX));
    const double g = cfg.real_or("sandpile.gravity_m_s2", 9.81, Range::positive());
    c.gravity = {0.0, 0.0, -g};
    c.length = plate + 2.0 * outlet;
    c.width = width;
    c.plate_x_lo = outlet;
    c.plate_x_hi = outlet + plate;
    c.plate_z = below;
    c.plate_thickness = thick;
    // Fill region: the whole box section above the plate and the closed gates. Default height: the
    // grains at a solid fraction of 0.3 (random sequential addition jams near 0.38).
    const double solid = static_cast<double>(c.count) * dem::sphere_volume(0.5 * d);
    const double auto_fill = solid / (0.3 * c.length * width) + d;
    c.fill_height = cfg.real_or("sandpile.fill_height_over_d", auto_fill / d, Range::closed(1.0, 1e6)) * d;
    const double above = cfg.real_or("sandpile.box_height_above_plate_over_d", c.fill_height / d + 2.0,
                                     Range::closed(1.0, 1e6)) *
                         d;
    if (above < c.fill_height)
        cfg.fail("sandpile.box_height_above_plate_over_d",
                 fmt::format("must be at least the fill height ({:.1f} d)", c.fill_height / d));
    c.height = below + above;
    c.fill_fraction = solid / (c.length * width * (c.fill_height - d));
    // refused before placing: random sequential addition slows to a crawl before it jams near 0.38
    constexpr double densest_fill = 0.35;
    if (c.fill_fraction > densest_fill)
        cfg.fail(
            "sandpile.fill_height_over_d",
            fmt::format("{} spheres of d = {} m do not fit without overlap in a fill region {:.1f} d high: "
                        "a solid fraction of {:.3f}, above the {} random placement reaches; raise the "
                        "fill height to at least {:.1f} d",
                        c.count, d, c.fill_height / d, c.fill_fraction, densest_fill,
                        solid / (densest_fill * c.length * width) / d + 1.0));

    using dem::Wall;
    c.walls.push_back(Wall::plane("floor", {0, 0, 0}, {0, 0, 1}));
    c.walls.push_back(Wall::plane("ceiling", {0, 0, c.height}, {0, 0, -1}));
    c.walls.push_back(Wall::plane("end_x0", {0, 0, 0}, {1, 0, 0}));
    c.walls.push_back(Wall::plane("end_x1", {c.length, 0, 0}, {-1, 0, 0}));
    c.walls.push_back(Wall::plane("side_y0", {0, 0, 0}, {0, 1, 0}));
    c.walls.push_back(Wall::plane("side_y1", {0, width, 0}, {0, -1, 0}));
    const std::array<Vec3, 3> axes{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
    const double zc = below - 0.5 * thick;
    c.walls.push_back(
        Wall::box("plate", {0.5 * c.length, 0.5 * width, zc}, axes, {0.5 * plate, 0.5 * width, 0.5 * thick}));
    // gates fill the outlets flush with the plate
    c.gates = {c.walls.size(), c.walls.size() + 1};
    c.walls.push_back(Wall::box("gate_x0", {0.5 * outlet, 0.5 * width, zc}, axes,
                                {0.5 * outlet, 0.5 * width, 0.5 * thick}));
    c.walls.push_back(Wall::box("gate_x1", {c.length - 0.5 * outlet, 0.5 * width, zc}, axes,
                                {0.5 * outlet, 0.5 * width, 0.5 * thick}));

    dem::check_sphere_budget(cfg, "sandpile.particles", static_cast<double>(c.count), "grains");
    const double r = 0.5 * d;
    const Vec3 lo{r, r, below + r}, hi{c.length - r, width - r, below + c.fill_height - r};
    if (place_grains && !place_random(c.particles, c.count, r, c.density, lo, hi, seed)) {
        cfg.fail(
            "sandpile.fill_height_over_d",
            fmt::format("{} spheres of d = {} m do not fit without overlap in a fill region {:.1f} d high "
                        "(placed {} at random; raise the fill height)",
                        c.count, d, c.fill_height / d, c.particles.n_mobile));
    }
    c.velocity_scale = cfg.real_or("dem.velocity_scale_m_s", std::sqrt(2.0 * g * (below + c.fill_height)),
                                   Range::positive());
    return c;
}

}  // namespace sabo::scenario
