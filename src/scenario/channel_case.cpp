// SPDX-License-Identifier: MIT
#include "scenario/channel_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>

#include "core/error.h"
#include "dem/grain_budget.h"
#include "geometry/mesh_queries.h"
#include "scenario/mesh_barrier.h"

namespace sabo::scenario {

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Uniform double in [0,1) from the raw 64-bit engine: portable across standard libraries.
double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// The release as lattice sites in placement order, each with the radii of the grains it holds (drawn
// ±spread around the nominal radius). Monodisperse: one grain per site until the volume reaches the
// target. Bidisperse: the counts of large and small grains that give the target volume and Φ_small;
// a site holds one large grain or a k×k×k cluster of small ones, k = ⌊largest large diameter /
// largest small diameter⌋ ("low-compacted": the lattice spacing is one large diameter); the sites
// are shuffled with the seeded draw. `admit(sites, grains)` sees the expected counts before anything is
// drawn or allocated and fails the case when they cannot be had.
struct ReleaseSites {
    std::vector<double> radii;       // of every grain, site after site
    std::vector<std::size_t> first;  // site q holds radii[first[q]] to radii[first[q + 1]] (exclusive)
    [[nodiscard]] std::size_t size() const { return first.size() - 1; }
    void close_site() { first.push_back(radii.size()); }
};

template <class Admit>
ReleaseSites release_sites(const Config& cfg, ReleaseInfo& info, std::mt19937_64& rng, Admit&& admit) {
    const double spread = cfg.real_or("release.radius_spread", 0.05, Range::closed(0.0, 0.5));
    const double target = cfg.real_or("release.solid_volume_m3", 4.03, Range::positive());
    auto draw = [&](double nominal) { return nominal * (1.0 + spread * (2.0 * uniform01(rng) - 1.0)); };
    ReleaseSites sites;
    sites.first.push_back(0);
    info.mixture = cfg.enum_or("release.mixture", Mixture::monodisperse, mixture_names);
    if (info.mixture == Mixture::monodisperse) {
        cfg.accept_unused({"release.radius_large_m", "release.radius_small_m", "release.phi_small"});
        info.r_mean = cfg.real_or("release.radius_mean_m", 0.05, Range::positive());
        info.r_min = info.r_mean * (1.0 - spread);
        info.r_max = info.r_mean * (1.0 + spread);
        const double expected = dem::expected_grain_count(target, info.r_mean, spread);
        admit(expected, expected);
        sites.radii.reserve(static_cast<std::size_t>(1.05 * expected) + 16);
        sites.first.reserve(sites.radii.capacity() + 1);
        for (double v = 0.0; v < target;) {
            sites.radii.push_back(draw(info.r_mean));
            sites.close_site();
            v += dem::sphere_volume(sites.radii.back());
        }
        info.cluster = 1;
        return sites;
    }
    cfg.accept_unused({"release.radius_mean_m"});
    const double big = cfg.real("release.radius_large_m", Range::positive());
    const double small = cfg.real("release.radius_small_m", Range::open_closed(0.0, big));
    info.phi_small = cfg.real("release.phi_small", Range::closed(0.0, 1.0));
    info.r_large = big;
    info.r_small = small;
    info.r_mean = big;  // S/r of a mixture refers to the large radius (reference case C4: S/R)
    info.r_min = (info.phi_small > 0.0 ? small : big) * (1.0 - spread);
    info.r_max = big * (1.0 + spread);  // the lattice spacing is one large diameter even if Φ_small = 1
    // a site holds k³ small grains: beyond R/r = 100 (a million per site) the mixture is not a release
    if (big / small > 100.0)
        cfg.fail("release.radius_small_m",
                 fmt::format("R/r = {:.4g}: at most 100 (each lattice site holds (R/r)^3 small grains)",
                             big / small));
    const int k = std::max(1, static_cast<int>(std::floor(big / small + 1e-9)));
    info.cluster = k;
    const auto per_cluster = static_cast<std::size_t>(k * k * k);
    const double large_count = (1.0 - info.phi_small) * target / dem::sphere_volume(big);
    const double small_count = info.phi_small * target / dem::sphere_volume(small);
    admit(large_count + small_count / static_cast<double>(per_cluster), large_count + small_count);
    const auto n_large = static_cast<std::size_t>(std::llround(large_count));
    const auto n_small = static_cast<std::size_t>(std::llround(small_count));
    const std::size_t n_clusters = (n_small + per_cluster - 1) / per_cluster;
    std::vector<std::uint8_t> is_cluster(n_large, 0);
    is_cluster.resize(n_large + n_clusters, 1);
    for (std::size_t q = is_cluster.size(); q > 1; --q) {  // Fisher–Yates with the portable draw
        const auto j = static_cast<std::size_t>(uniform01(rng) * static_cast<double>(q));
        std::swap(is_cluster[q - 1], is_cluster[std::min(j, q - 1)]);
    }
    std::size_t small_left = n_small;
    sites.radii.reserve(n_large + n_small);
    sites.first.reserve(is_cluster.size() + 1);
    for (const auto c : is_cluster) {
        if (c == 0) {
            sites.radii.push_back(draw(big));
        } else {
            for (std::size_t q = 0; q < per_cluster && small_left > 0; ++q, --small_left)
                sites.radii.push_back(draw(small));
        }
        sites.close_site();
    }
    return sites;
}

}  // namespace

std::vector<dem::Wall> channel_walls(const ChannelShape& c) {
    using dem::Wall;
    return {Wall::plane("bed", {0, 0, 0}, {0, 0, 1}),
            Wall::plane("ceiling", {0, 0, c.height}, {0, 0, -1}),
            Wall::plane("side_y0", {0, 0, 0}, {0, 1, 0}),
            Wall::plane("side_y1", {0, c.width, 0}, {0, -1, 0}),
            Wall::plane("upstream_end", {0, 0, 0}, {1, 0, 0}),
            Wall::plane("downstream_end", {c.length, 0, 0}, {-1, 0, 0})};
}

ReleaseInfo build_release(const Config& cfg, const ChannelShape& c, dem::Particles& particles,
                          bool place_grains, const geometry::TriangleMesh* channel_mesh) {
    ReleaseInfo info;
    info.density = cfg.real_or("release.density_kg_m3", 2500.0, Range::positive());
    const double block_l = cfg.real_or("release.length_m", 4.60, Range::positive());
    const double block_w = cfg.real_or("release.width_m", 1.90, Range::positive());
    const double front = cfg.real_or("release.front_x_m", 4.725, Range::positive());
    const auto seed = static_cast<std::uint64_t>(cfg.integer_or("release.seed", 12345, 0, INT64_MAX));
    info.compaction = cfg.enum_or("release.compaction", Compaction::low, compaction_names);
    info.settle_max_time = cfg.real_or("release.settle_max_time_s", 20.0, Range::positive());
    std::mt19937_64 rng(seed);
    // the bed under the block (relief from the channel's mesh raises it)
    const double base = highest_bed_level(channel_mesh, std::max(0.0, front - block_l), front,
                                          0.5 * (c.width - block_w), 0.5 * (c.width + block_w));
    // The lattice the sites go on (below): columns of nx × ny sites, at most max_layers high, nx at most
    // front / s so that the block stays in the channel. Checked on the expected counts first, so that an
    // absurd volume is refused before it is drawn.
    int ny = 0, max_layers = 0;
    double s = 0.0, z0 = 0.0;
    const auto admit = [&](double sites, double grains) {
        s = 2.0 * info.r_max;
        ny = std::max(1, static_cast<int>(std::lround(std::min(block_w / s, 1e9))));
        if (ny * s > c.width)
            cfg.fail("release.width_m", fmt::format("block wider than the channel ({} m)", c.width));
        z0 = base + 0.5 * s + 0.001;  // 1 mm above the bed
        max_layers = static_cast<int>(std::floor(std::min((c.height - z0) / s + 0.5, 1e9)));
        if (max_layers < 1) cfg.fail("release.radius_mean_m", "grains larger than the channel height");
        const double capacity = std::floor(front / s + 1e-9) * ny * max_layers;
        // the drawn count scatters around the expected one by a few per cent at most
        if (sites > 1.05 * capacity + 16.0) {
            cfg.fail("release.solid_volume_m3",
                     fmt::format("the block needs about {:.4g} lattice sites of {:.3f} m, but the channel "
                                 "upstream of its front at X = {} m holds at most {:.0f} ({:.0f} x {} per "
                                 "layer, {} layers under the {} m ceiling)",
                                 sites, s, front, capacity, std::floor(front / s + 1e-9), ny, max_layers,
                                 c.height));
        }
        dem::check_sphere_budget(cfg, "release.solid_volume_m3", grains, "grains");
    };
    const auto sites = release_sites(cfg, info, rng, admit);
    // Every centre displaced by a tiny random amount, drawn from its own stream so the radii stay those of
    // release.seed; its seed gives realizations of the same block. On by default (0.2 % of the smallest
    // radius): a simple cubic stack with every grain exactly above the one below is a singular state — the
    // arithmetic keeps its symmetry and the block slides as a crystal, hitting the C2 barrier 40 % harder
    // and locking in 15 % more static load than any block displaced by 1 µm or more
    // (docs/results/c2_static_load.md). 0: the exact lattice. Bounded so that no grain reaches the bed and
    // two touching grains of the largest size overlap by at most 2 sqrt(3) p ≤ 3.5 % of r.
    const double perturbation = cfg.real_or("release.perturbation_m", 0.002 * info.r_min,
                                            Range::closed(0.0, std::min(0.01 * info.r_min, 0.001)));
    std::mt19937_64 jitter(
        static_cast<std::uint64_t>(cfg.integer_or("release.perturbation_seed", 1, 0, INT64_MAX)));
    const auto displaced = [&](const Vec3& at) {
        if (perturbation == 0.0) return at;
        const double dx = 2.0 * uniform01(jitter) - 1.0, dy = 2.0 * uniform01(jitter) - 1.0,
                     dz = 2.0 * uniform01(jitter) - 1.0;
        return at + perturbation * Vec3{dx, dy, dz};
    };

    // Lattice rule: simple cubic, spacing = largest (large) diameter (no overlap whatever the draw),
    // nx × ny columns = round(length/s) × round(width/s), filled layer by layer from the bed with
    // the sites in order. The front grain surface touches X = front_x_m. A block that does not fit
    // under the ceiling is lengthened upstream (front and width kept).
    int nx = std::max(1, static_cast<int>(std::lround(std::min(block_l / s, 1e9))));
    const auto columns = static_cast<std::size_t>(ny) * static_cast<std::size_t>(max_layers);
    nx = std::max(nx, static_cast<int>((sites.size() + columns - 1) / columns));
    const double x0 = front - 0.5 * s - (nx - 1) * s;
    if (x0 - 0.5 * s < 0.0) {
        cfg.fail(
            "release.solid_volume_m3",
            fmt::format(
                "the block ({} lattice sites of {:.3f} m, {} x {} per layer, at most {} layers under the "
                "{} m ceiling) would need {:.2f} m upstream of its front at X = {} m",
                sites.size(), s, nx, ny, max_layers, c.height, nx * s, front));
    }
    const double y0 = 0.5 * (c.width - ny * s) + 0.5 * s;
    const auto per_layer = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    const auto layers = static_cast<int>((sites.size() + per_layer - 1) / per_layer);
    const int k = info.cluster;
    const double sub = s / k;  // spacing of small grains inside a cluster site (≥ their diameter)
    double volume = 0.0;
    for (const double r : sites.radii) volume += dem::sphere_volume(r);
    info.count = sites.radii.size();
    for (std::size_t q = 0; q < sites.size() && place_grains; ++q) {
        const auto layer = static_cast<int>(q / per_layer), in_layer = static_cast<int>(q % per_layer);
        const int j = in_layer / nx, i = in_layer % nx;
        const Vec3 centre{x0 + i * s, y0 + j * s, z0 + layer * s};
        for (std::size_t g = 0; g < sites.first[q + 1] - sites.first[q]; ++g) {
            const double r = sites.radii[sites.first[q] + g];
            Vec3 at = centre;
            if (k > 1 && r < 0.75 * info.r_max) {  // a small grain (r ≤ R/2 here) sits in its cluster slot
                const int a = static_cast<int>(g) % k, bq = (static_cast<int>(g) / k) % k,
                          cq = static_cast<int>(g) / (k * k);
                at = centre +
                     Vec3{(a + 0.5) * sub - 0.5 * s, (bq + 0.5) * sub - 0.5 * s, (cq + 0.5) * sub - 0.5 * s};
            }
            particles.add_mobile(displaced(at), r, info.density);
        }
    }
    info.solid_volume = volume;
    info.lo = {x0 - 0.5 * s, y0 - 0.5 * s, z0 - 0.5 * s};
    info.hi = {x0 + (nx - 0.5) * s, y0 + (ny - 0.5) * s, z0 + (layers - 0.5) * s};
    info.lattice_rule = fmt::format(
        "simple cubic, spacing {:.4f} m (largest diameter), {} x {} columns, {} layers "
        "(last one partly filled), filled bottom-up{}",
        s, nx, ny, layers,
        k > 1 ? fmt::format("; small grains in {0}x{0}x{0} clusters per site", k) : std::string());
    if (info.mixture == Mixture::bidisperse) {
        const double fl = 1.0 - info.phi_small;
        info.equivalent_radius =
            std::cbrt(fl * std::pow(info.r_large, 3) + info.phi_small * std::pow(info.r_small, 3));
    } else {
        info.equivalent_radius = info.r_mean;
    }
    return info;
}

std::shared_ptr<const geometry::TriangleMesh> mesh_channel_parts(const Config& cfg, const ChannelShape& shape,
                                                                 const ChannelBounds& bounds,
                                                                 std::vector<dem::Wall>& walls) {
    if (!cfg.has("channel.mesh_file")) return nullptr;
    auto mesh = placed_mesh(cfg, "channel", shape, bounds.domain_height, false);
    bool sides = false;
    for (const std::string& name : mesh->part_names) sides = sides || !is_bed_part(name);
    if (sides)
        std::erase_if(walls, [](const dem::Wall& w) { return w.name == "side_y0" || w.name == "side_y1"; });
    for (std::size_t p = 0; p < mesh->parts(); ++p) {  // (by name: the force balance adds bed and sides up)
        const std::string& name = mesh->part_names[p];
        walls.push_back(
            dem::Wall::mesh_part((is_bed_part(name) ? "bed_mesh_" : "side_mesh_") + name, mesh, p));
    }
    return mesh;
}

bool is_bed_part(std::string_view name) {
    return name.size() >= 3 && std::tolower(static_cast<unsigned char>(name[0])) == 'b' &&
           std::tolower(static_cast<unsigned char>(name[1])) == 'e' &&
           std::tolower(static_cast<unsigned char>(name[2])) == 'd';
}

double bed_level(const geometry::TriangleMesh* mesh, double x, double y) {
    double level = 0.0;
    if (mesh == nullptr) return level;
    for (std::size_t p = 0; p < mesh->parts(); ++p)
        if (is_bed_part(mesh->part_names[p]))
            if (const double top = geometry::highest_crossing(*mesh, p, x, y); top > level) level = top;
    return level;  // (NaN, no crossing, is not above it)
}

std::string describe_channel_mesh(const geometry::TriangleMesh& m) {
    std::size_t bed = 0;
    for (const std::string& name : m.part_names) bed += is_bed_part(name) ? 1 : 0;
    const geometry::Bounds b = m.bounds();
    return fmt::format(
        "channel walls from a mesh: {} triangles in {} parts ({} side walls, {} on the bed), x "
        "{:.3f}…{:.3f}, "
        "y {:.3f}…{:.3f}, z {:.3f}…{:.3f} m",
        m.triangles.size(), m.parts(), m.parts() - bed, bed, b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z, b.hi.z);
}

double highest_bed_level(const geometry::TriangleMesh* mesh, double x0, double x1, double y0, double y1) {
    // The relief's top is linear on each triangle, so over the rectangle it peaks at a vertex inside it,
    // where an edge crosses the rectangle's sides, or at a corner. Every point of a part lies at or below its
    // top, so those points of all its triangles (top, sides and bottom) give the top's highest exactly.
    double level = 0.0;
    if (mesh == nullptr) return level;
    const auto inside = [&](double x, double y) { return x >= x0 && x <= x1 && y >= y0 && y <= y1; };
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
        if (!is_bed_part(mesh->part_names[mesh->part[t]])) continue;
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = mesh->corner(t, k), b = mesh->corner(t, (k + 1) % 3);
            if (inside(a.x, a.y)) level = std::max(level, a.z);
            // the edge's crossings of the lines x = x0, x1 and y = y0, y1 within the rectangle
            for (const auto& [from, to, at] : {std::tuple{a.x, b.x, x0}, std::tuple{a.x, b.x, x1},
                                               std::tuple{a.y, b.y, y0}, std::tuple{a.y, b.y, y1}}) {
                if ((from - at) * (to - at) > 0.0 || from == to) continue;
                const Vec3 p = a + (b - a) * ((at - from) / (to - from));
                // (on the line by construction: its other coordinate within the rectangle, to round-off)
                const double e = 1e-12 * (1.0 + std::abs(at));
                if (p.x >= x0 - e && p.x <= x1 + e && p.y >= y0 - e && p.y <= y1 + e)
                    level = std::max(level, p.z);
            }
        }
    }
    for (const double x : {x0, x1})
        for (const double y : {y0, y1}) level = std::max(level, bed_level(mesh, x, y));
    return level;
}

std::string open_top_mesh_warning(const ChannelBounds& bounds, const geometry::TriangleMesh* mesh,
                                  double height) {
    if (mesh == nullptr || bounds.top != ChannelTop::open) return {};
    double top = -std::numeric_limits<double>::infinity();  // (the side walls': bed parts are low)
    for (std::size_t p = 0; p < mesh->parts(); ++p)
        if (!is_bed_part(mesh->part_names[p])) top = std::max(top, mesh->bounds(p).hi.z);
    if (!std::isfinite(top)) return {};
    if (std::abs(top - height) <= 0.02 * height) return {};
    return fmt::format(
        "channel.mesh_file: its walls rise to {:.3f} m but channel.height_m is {:.3f} m; under an open top "
        "the "
        "fluid leaves the domain's sides only above channel.height_m (set it to the walls' height)",
        top, height);
}

void place_inflow_in_mesh(const Config& cfg, const std::shared_ptr<const geometry::TriangleMesh>& mesh,
                          InflowSettings& inflow, double from_x) {
    const double x1 = inflow.x0 + inflow.length;
    inflow.base = highest_bed_level(mesh.get(), inflow.x0, x1, 0.0, inflow.width);
    const double level = std::max(
        inflow.base, highest_bed_level(mesh.get(), std::min(from_x, inflow.x0), x1, 0.0, inflow.width));
    if (mesh) {
        // the triangles whose bounds reach the zone's box, grown by the largest radius
        const double reach = inflow.r_max();
        const Vec3 lo{inflow.x0 - reach, -reach, inflow.base - reach},
            hi{x1 + reach, inflow.width + reach, inflow.height + reach};
        inflow.mesh = mesh;
        for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
            Vec3 a = mesh->corner(t, 0), b = a;
            for (int k = 1; k < 3; ++k) {
                const Vec3 v = mesh->corner(t, k);
                a = {std::min(a.x, v.x), std::min(a.y, v.y), std::min(a.z, v.z)};
                b = {std::max(b.x, v.x), std::max(b.y, v.y), std::max(b.z, v.z)};
            }
            if (b.x < lo.x || a.x > hi.x || b.y < lo.y || a.y > hi.y || b.z < lo.z || a.z > hi.z) continue;
            inflow.mesh_near.push_back(static_cast<std::uint32_t>(t));
            // (a grain's centre lies in the zone, above the relief's highest level there: never inside the
            // relief, so only the side walls are asked whether they hold it)
            const std::size_t part = mesh->part[t];
            const auto listed = [&](const InflowSettings::MeshPart& w) { return w.part == part; };
            if (!is_bed_part(mesh->part_names[part]) && std::ranges::none_of(inflow.walls_near, listed))
                inflow.walls_near.push_back({part, mesh->bounds(part)});
        }
    }
    if (level > 0.0 && level + inflow.deepest() > inflow.height)
        cfg.fail(
            "inflow.velocity_m_s",
            fmt::format("the inflow at the hydrograph's largest discharge would be {:.3f} m deep on the "
                        "bed's relief (channel.mesh_file), which rises {:.3f} m under X {:.3f}…{:.3f} m: "
                        "{:.3f} m, above the side walls ({:.3f} m): raise the velocity or the walls "
                        "(channel.height_m)",
                        inflow.deepest(), level, std::min(from_x, inflow.x0), x1, level + inflow.deepest(),
                        inflow.height));
}

void refuse_overlap(const Config& cfg, const geometry::TriangleMesh& mesh, const dem::Particles& p) {
    for (std::size_t part = 0; part < mesh.parts(); ++part) {
        const geometry::Bounds b = mesh.bounds(part);
        for (std::size_t i = 0; i < p.n_mobile; ++i) {
            const Vec3& x = p.x[i];
            const double r = p.r[i];
            if (x.x + r < b.lo.x || x.x - r > b.hi.x || x.y + r < b.lo.y || x.y - r > b.hi.y ||
                x.z + r < b.lo.z || x.z - r > b.hi.z)
                continue;
            if (geometry::contains(mesh, part, x) || geometry::distance(mesh, part, x) < r)
                cfg.fail("channel.mesh_file",
                         fmt::format(
                             "the released block overlaps the channel mesh's part '{}' (a grain at ({:.3f}, "
                             "{:.3f}, {:.3f}) m): narrow the block (release.width_m) or move it "
                             "(release.front_x_m) where the walls are apart",
                             mesh.part_names[part], x.x, x.y, x.z));
        }
    }
}

ReleaseInfo no_release(const Config& cfg) {
    cfg.accept_unused({"release.length_m", "release.width_m", "release.front_x_m", "release.seed",
                       "release.radius_spread", "release.compaction", "release.settle_max_time_s",
                       "release.perturbation_m", "release.perturbation_seed", "release.mixture",
                       "release.radius_large_m", "release.radius_small_m", "release.phi_small"});
    ReleaseInfo info;
    info.density = cfg.real_or("release.density_kg_m3", 2500.0, Range::positive());
    info.r_mean =
        cfg.real_or("inflow.radius_mean_m", cfg.real_or("release.radius_mean_m", 0.05, Range::positive()),
                    Range::positive());
    info.r_min = info.r_max = info.equivalent_radius = info.r_mean;
    info.lattice_rule = "none: the grains come through the inflow section";
    return info;
}

ChannelShape read_channel_shape(const Config& cfg, Vec3& gravity) {
    ChannelShape c;
    c.slope_deg = cfg.real("channel.slope_deg", Range::closed(0.0, 60.0));
    c.length = cfg.real_or("channel.length_m", 20.0, Range::positive());
    c.width = cfg.real_or("channel.width_m", 2.10, Range::positive());
    c.height = cfg.real_or("channel.height_m", 1.35, Range::positive());
    const double g = cfg.real_or("channel.gravity_m_s2", 9.81, Range::non_negative());
    c.gravity = g;
    gravity = {g * std::sin(c.slope_deg * deg), 0.0, -g * std::cos(c.slope_deg * deg)};
    return c;
}

ChannelCase build_channel_case(const Config& cfg, bool place_grains) {
    ChannelCase c;
    c.name = cfg.text_or("case.name", "channel");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    const ChannelShape shape = read_channel_shape(cfg, c.gravity);
    c.slope_deg = shape.slope_deg;
    c.length = shape.length;
    c.width = shape.width;
    c.height = shape.height;
    const double g = shape.gravity;
    c.bounds = read_channel_bounds(cfg, shape, ChannelTop::lid);
    // side walls from a mesh (a narrowing or curving reach in plan) and relief on the inclined bed plane
    c.walls = channel_walls(shape, c.bounds);
    c.channel_mesh = mesh_channel_parts(cfg, shape, c.bounds, c.walls);
    // with an inflow the channel may start empty: the grains all come through the section
    const bool fed = cfg.has("inflow.hydrograph_file");
    if (fed && cfg.real_or("release.solid_volume_m3", 4.03, Range::non_negative()) == 0.0)
        c.release = no_release(cfg);
    else
        c.release = build_release(cfg, shape, c.particles, place_grains, c.channel_mesh.get());
    if (cfg.text_or("barrier.type", "slit") == "mesh")
        c.barrier = mesh_barrier(cfg, shape, c.bounds.domain_height, c.walls);
    else
        c.barrier = build_barrier(cfg, shape, c.release.r_mean, c.walls, c.particles);
    if (c.channel_mesh) refuse_overlap(cfg, *c.channel_mesh, c.particles);
    c.inflow = read_inflow(cfg, c.width, c.height, c.barrier.present() ? c.barrier.face_x : c.length);
    if (c.inflow) place_inflow_in_mesh(cfg, c.channel_mesh, *c.inflow, c.inflow->x0);
    // Velocity scale: frictionless slide of the block front to the barrier (or the channel end)
    // plus the fall of the block height — the impact speed used for contact-time and overlap
    // estimates (docs/dem.md).
    const double stop_x = c.barrier.present() ? c.barrier.face_x : c.length;
    const double drop = std::max(0.0, stop_x - c.release.hi.x) * std::sin(c.slope_deg * deg) + c.release.hi.z;
    double scale = c.release.count > 0 ? std::sqrt(2.0 * g * drop) : 0.0;
    if (c.inflow) {  // the inflow's grains from the section at u, sliding to the barrier
        const double fall = std::max(0.0, stop_x - c.inflow->x0) * std::sin(c.slope_deg * deg);
        scale = std::max(scale, std::sqrt(c.inflow->velocity * c.inflow->velocity + 2.0 * g * fall));
    }
    c.velocity_scale = cfg.real_or("dem.velocity_scale_m_s", scale, Range::positive());
    return c;
}

}  // namespace sabo::scenario
