// SPDX-License-Identifier: MIT
#include "scenario/grain_inflow.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "dem/grain_budget.h"
#include "geometry/mesh_queries.h"
#include "scenario/csv_table.h"
#include "scenario/overlap_grid.h"

namespace sabo::scenario {

namespace {

double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Whether a grain at x of radius r stays clear of the channel mesh's triangles near the zone (touching is
// clear) and outside its side walls there.
bool clear_of_mesh(const InflowSettings& s, const Vec3& x, double r) {
    if (!s.mesh) return true;
    const geometry::TriangleMesh& mesh = *s.mesh;
    for (const std::uint32_t t : s.mesh_near)
        if (norm2(geometry::closest_point(mesh, t, x) - x) < r * r) return false;
    for (const auto& [p, b] : s.walls_near) {
        const bool within = x.x >= b.lo.x && x.x <= b.hi.x && x.y >= b.lo.y && x.y <= b.hi.y &&
                            x.z >= b.lo.z && x.z <= b.hi.z;
        if (within && geometry::contains(mesh, p, x)) return false;
    }
    return true;
}

}  // namespace

double InflowSettings::r_min() const {
    const double mean = hydrograph.graded() ? hydrograph.smallest_radius() : radius;
    return mean * (1.0 - spread);
}
double InflowSettings::r_max() const {
    const double mean = hydrograph.graded() ? hydrograph.largest_radius() : radius;
    return mean * (1.0 + spread);
}

double InflowSettings::depth(double solid, double solid_fraction) const {
    const double c = std::clamp(solid_fraction, 1e-6, inflow_placement_fraction);
    // at least two largest diameters: in a layer one grain thick the placement is a 2-D one, which jams at
    // an areal coverage a solid fraction of 0.3 already asks for
    // (+ one diameter: no centre lies within a radius of the zone's faces)
    return std::clamp(solid / (c * length * width) + 2.0 * r_max(), 4.0 * r_max(),
                      std::max(height - base, 4.0 * r_max()));
}

double InflowSettings::deepest() const {
    return hydrograph.largest_discharge() / (velocity * width) *
               std::max(1.0, hydrograph.largest_solid_fraction() / inflow_placement_fraction) +
           2.0 * r_max();
}

std::optional<InflowSettings> read_inflow(const Config& cfg, double width, double height, double barrier_x) {
    if (!cfg.has("inflow.hydrograph_file")) {
        for (const char* key :
             {"inflow.velocity_m_s", "inflow.x_m", "inflow.length_m", "inflow.radius_mean_m",
              "inflow.radius_spread", "inflow.density_kg_m3", "inflow.seed"})
            if (cfg.has(key)) cfg.fail(key, "an inflow needs inflow.hydrograph_file");
        return std::nullopt;
    }
    InflowSettings s;
    const std::filesystem::path file = beside_case(cfg.source(), cfg.text("inflow.hydrograph_file"));
    try {
        s.hydrograph = Hydrograph::read(file);
    } catch (const InputError& e) {
        cfg.fail("inflow.hydrograph_file", e.what());
    }
    s.velocity = cfg.real("inflow.velocity_m_s", Range::open_closed(0.0, 100.0));
    s.radius = cfg.real_or("inflow.radius_mean_m",
                           cfg.real_or("release.radius_mean_m", 0.05, Range::positive()), Range::positive());
    s.spread = cfg.real_or("inflow.radius_spread", 0.05, Range::closed(0.0, 0.5));
    s.density =
        cfg.real_or("inflow.density_kg_m3", cfg.real_or("release.density_kg_m3", 2500.0, Range::positive()),
                    Range::positive());
    s.seed = static_cast<std::uint64_t>(cfg.integer_or("inflow.seed", 1, 0, INT64_MAX));
    s.width = width;
    s.height = height;
    // ten mean diameters: several grains deep along the channel in every batch
    s.length = cfg.real_or("inflow.length_m", 20.0 * s.r_max() / (1.0 + s.spread), Range::positive());
    s.x0 = cfg.real_or("inflow.x_m", 0.0, Range::closed(0.0, 1e6));
    if (s.x0 + s.length > barrier_x - 2.0 * s.r_max())
        cfg.fail("inflow.length_m",
                 fmt::format(
                     "the inflow zone X [{:.3f}, {:.3f}] m must end before the barrier (X = {:.3f} m) by a "
                     "grain diameter",
                     s.x0, s.x0 + s.length, barrier_x));
    if (2.0 * s.r_max() > width) cfg.fail("inflow.radius_mean_m", "grains wider than the channel");
    const double deepest = s.deepest();
    if (deepest > height)
        cfg.fail(
            "inflow.velocity_m_s",
            fmt::format(
                "the inflow at the hydrograph's largest discharge ({:.4g} m3/s) would be {:.3f} m deep "
                "at {:.3g} m/s (Q / (u W) + a diameter, placed at a solid fraction of at most {}), above the "
                "side "
                "walls ({:.3f} m): raise the velocity or widen the channel",
                s.hydrograph.largest_discharge(), deepest, s.velocity, inflow_placement_fraction, height));
    dem::check_sphere_budget(
        cfg, "inflow.hydrograph_file",
        s.hydrograph.solid_volume(s.hydrograph.start(), s.hydrograph.end()) / dem::sphere_volume(s.r_min()),
        "inflow grains");
    return s;
}

std::string inflow_bed_note(const InflowSettings& s) {
    std::string note;
    if (s.base > 0.0) note += fmt::format(", from Z {:.3f} m (the bed's relief)", s.base);
    if (!s.mesh_near.empty())
        note += fmt::format(", clear of the {} triangles of the channel mesh there", s.mesh_near.size());
    return note;
}

std::vector<dem::GrainRecord> inflow_batch(const InflowSettings& s, double t, double solid,
                                           std::uint64_t batch, const dem::Particles& present,
                                           double& placed) {
    placed = 0.0;
    std::vector<dem::GrainRecord> out;
    if (!(solid > 0.0)) return out;
    const double r_max = s.r_max();
    t = std::clamp(t, s.hydrograph.start(), s.hydrograph.end());
    const double depth = s.depth(solid, s.hydrograph.solid_fraction(t));
    const Vec3 lo{s.x0, 0.0, s.base}, hi{s.x0 + s.length, s.width, s.base + depth};
    // the grains already near the zone, then those placed here, in one store the grid searches
    dem::Particles near;
    const double reach = 2.0 * r_max;
    for (std::size_t i = 0; i < present.n_mobile; ++i) {
        const Vec3& x = present.x[i];
        if (x.x > lo.x - reach && x.x < hi.x + reach && x.z < hi.z + reach)
            near.add_mobile(x, present.r[i], 1.0);
    }
    OverlapGrid grid(lo - Vec3{reach, reach, reach}, hi + Vec3{reach, reach, reach}, reach, false);
    for (std::size_t q = 0; q < near.n_mobile; ++q) grid.add(static_cast<std::uint32_t>(q), near.x[q]);
    // one stream per batch: no generator state to carry in a checkpoint
    std::seed_seq seq{s.seed, batch};
    std::mt19937_64 rng(seq);
    const double mean = s.hydrograph.radius(t, s.radius);
    constexpr int attempts = 200;  // a grain that finds no room in this many draws ends the batch
    while (placed < solid) {
        const double r = mean * (1.0 + s.spread * (2.0 * uniform01(rng) - 1.0));
        bool found = false;
        Vec3 x{};
        for (int a = 0; a < attempts && !found; ++a) {
            x = {lo.x + r + (s.length - 2.0 * r) * uniform01(rng), r + (s.width - 2.0 * r) * uniform01(rng),
                 s.base + r + std::max(0.0, depth - 2.0 * r) * uniform01(rng)};
            found = !grid.overlap(x, r, near) && clear_of_mesh(s, x, r);
        }
        if (!found) break;
        grid.add(static_cast<std::uint32_t>(near.n_mobile), x);
        near.add_mobile(x, r, 1.0);
        const double m = s.density * dem::sphere_volume(r);
        dem::GrainRecord g;
        g.x = x;
        g.vh = {s.velocity, 0.0, 0.0};
        g.r = r;
        g.m = m;
        g.inv_m = 1.0 / m;
        g.inv_j = 1.0 / (0.4 * m * r * r);
        out.push_back(g);
        placed += dem::sphere_volume(r);
    }
    return out;
}

}  // namespace sabo::scenario
