// SPDX-License-Identifier: MIT
#include "scenario/debris_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include "dem/grain_budget.h"
#include "geometry/mesh_queries.h"
#include "scenario/mesh_barrier.h"
#include "scenario/overlap_grid.h"

namespace sabo::scenario {

namespace {

// Uniform double in [0,1) from the raw 64-bit engine: portable across standard libraries.
double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Random sequential addition: radii r (1 ± spread) drawn until their volume reaches the target, each
// centre drawn uniformly where the grain lies inside the block, kept if it is farther than r_i + r_j from
// every grain kept before (a grid of cells of the largest diameter finds them), at most `tries` draws per
// grain. Not placed (`sabo check`): the expected count and the target volume.
void random_grains(const Config& cfg, DebrisCase& c, double target, bool place) {
    ReleaseInfo& g = c.grains;
    const double spread = cfg.real_or("release.radius_spread", 0.05, Range::closed(0.0, 0.5));
    g.r_mean = cfg.real_or("release.radius_mean_m", 0.05, Range::positive());
    g.density = cfg.real_or("release.density_kg_m3", 2500.0, Range::positive());
    const auto seed = static_cast<std::uint64_t>(cfg.integer_or("release.seed", 12345, 0, INT64_MAX));
    g.r_min = g.r_mean * (1.0 - spread);
    g.r_max = g.r_mean * (1.0 + spread);
    const Vec3 lo = c.block_lo, hi = c.block_hi;
    for (int a = 0; a < 3; ++a) {
        const double extent = a == 0 ? hi.x - lo.x : (a == 1 ? hi.y - lo.y : hi.z - lo.z);
        if (extent <= 2.0 * g.r_max)
            cfg.fail("release.radius_mean_m",
                     fmt::format("grains of up to {:.3f} m across do not fit in the fluid block ({:.3f} m)",
                                 2.0 * g.r_max, extent));
    }
    const double expected = dem::expected_grain_count(target, g.r_mean, spread);
    dem::check_sphere_budget(cfg, "debris.solid_fraction", expected, "grains");
    g.equivalent_radius = g.r_mean;
    g.lo = lo;
    g.hi = hi;
    g.lattice_rule =
        fmt::format("random sequential addition (seed {}), centres farther apart than r_i + r_j", seed);
    if (!place) {
        g.count = static_cast<std::size_t>(std::llround(expected));
        g.solid_volume = target;
        g.lattice_rule += " (counted, not placed)";
        return;
    }
    std::mt19937_64 rng(seed);
    OverlapGrid kept(lo, hi, 2.0 * g.r_max, true);  // centres farther apart than r_i + r_j
    constexpr int tries = 20000;
    double volume = 0.0;
    while (volume < target) {
        const double r = g.r_mean * (1.0 + spread * (2.0 * uniform01(rng) - 1.0));
        bool placed = false;
        for (int t = 0; t < tries && !placed; ++t) {
            const Vec3 x{lo.x + r + (hi.x - lo.x - 2.0 * r) * uniform01(rng),
                         lo.y + r + (hi.y - lo.y - 2.0 * r) * uniform01(rng),
                         lo.z + r + (hi.z - lo.z - 2.0 * r) * uniform01(rng)};
            if (kept.overlap(x, r, c.particles)) continue;
            kept.add(static_cast<std::uint32_t>(c.particles.size()), x);
            c.particles.add_mobile(x, r, g.density);
            volume += dem::sphere_volume(r);
            placed = true;
        }
        if (!placed)
            cfg.fail("debris.solid_fraction",
                     fmt::format("{:.3f} of the block cannot be reached by random placement with the spacing "
                                 "rule (centres farther apart than r_i + r_j): it stalled at {:.3f}; at 0.35 "
                                 "the grains are C2's lattice block",
                                 c.solid_fraction, volume / block_volume(c)));
    }
    g.count = c.particles.n_mobile;
    g.solid_volume = volume;
}

// The grains of the block: none, C2's lattice block, or random ones.
void place_grains_of(const Config& cfg, DebrisCase& c, bool place) {
    if (c.solid_fraction == 0.0) {  // the grains' scale only (S/r, the contact model's checks)
        if (c.dry) cfg.fail("debris.dry", "a dry run needs grains (debris.solid_fraction > 0)");
        c.placement = "none";
        ReleaseInfo& g = c.grains;
        const double spread = cfg.real_or("release.radius_spread", 0.05, Range::closed(0.0, 0.5));
        g.r_mean = cfg.real_or("release.radius_mean_m", 0.05, Range::positive());
        g.r_min = g.r_mean * (1.0 - spread);
        g.r_max = g.r_mean * (1.0 + spread);
        g.density = cfg.real_or("release.density_kg_m3", 2500.0, Range::positive());
        cfg.accept_unused({"release.seed"});
        return;
    }
    if (c.solid_fraction >= 0.35) {  // C2's block takes precedence (reference case C5)
        c.placement = "C2 block";
        c.grains = build_release(cfg, c.channel, c.particles, place, c.channel_mesh.get());
        if (c.grains.compaction != Compaction::low)
            cfg.fail("release.compaction", "a debris run releases the block as it is (\"low\")");
        const Vec3 lo = c.grains.lo, hi = c.grains.hi;
        if (lo.x < c.block_lo.x || lo.y < c.block_lo.y || hi.x > c.block_hi.x || hi.y > c.block_hi.y ||
            hi.z > c.block_hi.z)
            cfg.fail(
                "debris.block_length_m",
                fmt::format("C2's block (X [{:.3f}, {:.3f}], Y [{:.3f}, {:.3f}], Z up to {:.3f} m) must lie "
                            "inside the fluid block",
                            lo.x, hi.x, lo.y, hi.y, hi.z));
        return;
    }
    c.placement = "random";
    random_grains(cfg, c, c.solid_fraction * block_volume(c), place);
}

}  // namespace

DebrisCase build_debris_case(const Config& cfg, bool place_grains) {
    DebrisCase c;
    c.name = cfg.text_or("case.name", "debris");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    c.channel = read_channel_shape(cfg, c.gravity);
    const auto& ch = c.channel;
    c.solid_fraction = cfg.real_or("debris.solid_fraction", 0.0, Range::closed(0.0, 0.35));
    c.dry = cfg.boolean_or("debris.dry", false);
    c.block_lo = {0.0, 0.0, 0.0};
    // with an inflow the channel may start empty: the fluid all comes through the section
    const bool fed = cfg.has("inflow.hydrograph_file");
    c.block_hi = {cfg.real_or("debris.block_length_m", 4.75, fed ? Range::non_negative() : Range::positive()),
                  cfg.real_or("debris.block_width_m", ch.width, Range::open_closed(0.0, ch.width)),
                  cfg.real_or("debris.block_height_m", 1.10, Range::open_closed(0.0, ch.height))};
    const double y0 = 0.5 * (ch.width - c.block_hi.y);
    c.block_lo.y = y0;
    c.block_hi.y += y0;
    c.bounds = read_channel_bounds(cfg, ch, ChannelTop::open);
    c.walls = channel_walls(ch, c.bounds);
    c.channel_mesh = mesh_channel_parts(cfg, ch, c.bounds, c.walls);
    // the block stands on the bed's relief under it (the fluid fills the hollows below that level too)
    const double base =
        highest_bed_level(c.channel_mesh.get(), c.block_lo.x, c.block_hi.x, c.block_lo.y, c.block_hi.y);
    c.block_lo.z += base;
    c.block_hi.z += base;
    place_grains_of(cfg, c, place_grains);
    if (c.channel_mesh) refuse_overlap(cfg, *c.channel_mesh, c.particles);
    c.grain_radius = c.grains.r_mean;
    if (cfg.text_or("barrier.type", "slit") == "mesh") {
        c.barrier = mesh_barrier(cfg, ch, c.bounds.domain_height, c.walls);
    } else {
        c.barrier = build_barrier(cfg, ch, c.grain_radius, c.walls, c.particles);
    }
    if (c.barrier.present() && c.block_hi.x > c.barrier.face_x - 0.01)
        cfg.fail("debris.block_length_m",
                 fmt::format("the block reaches the barrier face (X = {:.3f} m)", c.barrier.face_x));
    c.inflow = read_inflow(cfg, ch.width, ch.height, c.barrier.present() ? c.barrier.face_x : ch.length);
    if (c.inflow) place_inflow_in_mesh(cfg, c.channel_mesh, *c.inflow, 0.0);  // (the fluid's inlet: X 0)
    if (c.inflow) {
        if (c.dry)
            cfg.fail("debris.dry",
                     "a dry debris run has no inflow: grains alone from a hydrograph run as case.type = "
                     "\"channel\"");
        if (c.grains.count > 0)
            cfg.fail(
                "inflow.hydrograph_file",
                "an inflow feeds a debris channel that starts without grains (debris.solid_fraction = 0): "
                "the hydrograph's solid_fraction brings them");
        // the grains the hydrograph carries enter the fluid through the inflow's zone (coupled)
        const InflowSettings& in = *c.inflow;
        if (in.hydrograph.largest_solid_fraction() > 0.0) {
            c.fed_grains = true;
            c.placement = "inflow";
            c.grains.density = in.density;
            const auto& h = in.hydrograph;
            c.grains.r_mean = h.graded() ? 0.5 * (h.smallest_radius() + h.largest_radius()) : in.radius;
            c.grains.r_min = in.r_min();
            c.grains.r_max = in.r_max();
            c.grains.equivalent_radius = c.grains.r_mean;
        }
    }
    const bool outflow = c.bounds.top == ChannelTop::open || c.bounds.end == ChannelEnd::open;
    if (outflow) {
        // beyond the barrier's last element (a vertical barrier leans downstream in the channel's frame)
        double after = c.barrier.present() ? c.barrier.face_x : c.block_hi.x;
        for (const auto& el : c.barrier.elements) after = std::max(after, el.centre.x + c.barrier.thickness);
        // three barrier heights behind it: the flow there is fast and shallow (supercritical), so what the
        // outflow does does not travel back to the barrier (an outflow at 10 or 12 m behind the reference
        // case's closed barrier at 8 m gave the same loads to 2 %); the thin film that runs on to the
        // channel's end accelerates beyond what the lattice's step carries
        // (docs/results/open_channel_fluid.md)
        const double height = c.barrier.present() ? c.barrier.height : ch.height;
        // (under a lid with an open end, the fluid leaves where the grains do: at the channel's end)
        const double fallback =
            c.bounds.top == ChannelTop::open ? std::min(ch.length, after + 3.0 * height) : ch.length;
        c.outflow_x = cfg.real_or("channel.outflow_x_m", fallback, Range::open_closed(after, ch.length));
    } else if (cfg.has("channel.outflow_x_m")) {
        cfg.fail("channel.outflow_x_m", "an outflow needs channel.top = \"open\" or channel.end = \"open\"");
    }
    // the fluid that passes the barrier keeps accelerating down to the channel's end (the jets behind a
    // slit reached 15-25 m/s in C5): the drop to the end, not to the barrier, bounds the speed
    const double drop =
        (ch.length - c.block_hi.x) * std::sin(ch.slope_deg * std::numbers::pi / 180.0) + c.block_hi.z;
    double scale = std::sqrt(2.0 * ch.gravity * drop);
    if (c.inflow) {  // the inflow enters at u at the upstream end and runs down to the channel's end
        const double fall = ch.length * std::sin(ch.slope_deg * std::numbers::pi / 180.0);
        scale = std::max(scale, std::sqrt(c.inflow->velocity * c.inflow->velocity + 2.0 * ch.gravity * fall));
    }
    c.velocity_scale = cfg.real_or("debris.velocity_scale_m_s", scale, Range::positive());
    return c;
}

bool inside_element(const DebrisCase& c, std::size_t e, const Vec3& x) {
    const BarrierElement& el = c.barrier.elements[e];
    if (el.mesh_part) return geometry::contains(*c.barrier.mesh, el.part, x);
    if (el.sphere) {
        const std::size_t i = c.barrier.sphere_position(el, c.particles.size());
        return norm2(x - c.particles.x[i]) <= c.particles.r[i] * c.particles.r[i];
    }
    const dem::Wall& w = c.walls[el.index];
    const Vec3 d = x - w.point;
    return std::abs(dot(d, w.axes[0])) <= w.half.x && std::abs(dot(d, w.axes[1])) <= w.half.y &&
           std::abs(dot(d, w.axes[2])) <= w.half.z;
}

}  // namespace sabo::scenario
