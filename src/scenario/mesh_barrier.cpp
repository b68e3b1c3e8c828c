// SPDX-License-Identifier: MIT
#include "scenario/mesh_barrier.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <utility>

#include "core/error.h"
#include "geometry/mesh_queries.h"
#include "geometry/stl_reader.h"
#include "scenario/csv_table.h"

namespace sabo::scenario {

std::shared_ptr<const geometry::TriangleMesh> placed_mesh(const Config& cfg, const std::string& table,
                                                          const ChannelShape& channel, double top,
                                                          bool inside) {
    const std::string key = table + ".mesh_file";
    const std::filesystem::path named = cfg.text(key);
    const std::filesystem::path file = beside_case(cfg.source(), named);
    const std::string what = fmt::format("{} ({})", key, file.string());
    geometry::TriangleMesh read;
    try {
        read = geometry::read_stl(file);
    } catch (const InputError& e) {
        cfg.fail(key, e.what());
    }
    const double scale = cfg.real_or(table + ".mesh_scale", 1.0, Range::positive());
    const auto angle = [&](const char* axis) {
        return cfg.real_or(fmt::format("{}.mesh_rotation_{}_deg", table, axis), 0.0,
                           Range::closed(-360.0, 360.0));
    };
    const auto shift = [&](const char* axis) {
        return cfg.real_or(fmt::format("{}.mesh_offset_{}_m", table, axis), 0.0, Range::closed(-1e4, 1e4));
    };
    const Vec3 rotation{angle("x"), angle("y"), angle("z")};
    const Vec3 offset{shift("x"), shift("y"), shift("z")};
    auto mesh =
        std::make_shared<geometry::TriangleMesh>(geometry::transformed(read, scale, rotation, offset));
    try {
        geometry::check_closed(*mesh, what);
    } catch (const InputError& e) {
        cfg.fail(key, e.what());
    }
    // in the channel: a model in millimetres read as metres is a thousand times too large
    const geometry::Bounds all = mesh->bounds();
    const double slack = 1e-9 * channel.length;
    const Vec3 size = all.size();
    const auto fits = [&](double k) {
        return size.x * k <= channel.length && size.y * k <= channel.width && size.z * k <= top;
    };
    const bool outside = all.lo.x < -slack || all.hi.x > channel.length + slack || all.lo.y < -slack ||
                         all.hi.y > channel.width + slack || all.lo.z < -slack || all.hi.z > top + slack;
    // (walls may stand beyond the domain's sides; a mesh ten times the channel's size is in other units)
    if ((inside && outside) || (!inside && !fits(0.1)))
        cfg.fail(key,
                 fmt::format("the mesh (after {0}.mesh_scale {1} and the offset) spans x {2:.4g}…{3:.4g}, y "
                             "{4:.4g}…{5:.4g}, z {6:.4g}…{7:.4g} m, outside the channel (x 0…{8:.4g}, y "
                             "0…{9:.4g}, z 0…{10:.4g} m){11}",
                             table, scale, all.lo.x, all.hi.x, all.lo.y, all.hi.y, all.lo.z, all.hi.z,
                             channel.length, channel.width, top,
                             !fits(1.0) && fits(1e-3)
                                 ? fmt::format(": a model in millimetres needs {}.mesh_scale = 0.001", table)
                             : fits(1.0) ? fmt::format(": move it with {}.mesh_offset_{{x,y,z}}_m", table)
                                         : std::string(": larger than the channel")));
    return mesh;
}

BarrierInfo mesh_barrier(const Config& cfg, const ChannelShape& channel, double top,
                         std::vector<dem::Wall>& walls) {
    BarrierInfo b;
    b.type = BarrierType::mesh;
    // the keys of the box and sphere barriers may stay in a case file that --set or a sweep switches
    cfg.accept_unused({"barrier.orientation", "barrier.model", "barrier.sphere_radius_m",
                       "barrier.thickness_m", "barrier.height_m", "barrier.face_x_m",
                       "barrier.outlet_width_over_r", "barrier.outlet_width_m", "barrier.configuration",
                       "barrier.piles", "barrier.pile_width_over_r"});
    std::shared_ptr<const geometry::TriangleMesh> mesh = placed_mesh(cfg, "barrier", channel, top);
    const geometry::Bounds all = mesh->bounds();
    // its face: the upstream end; along the bed's normal, the highest point
    b.face_x = all.lo.x;
    b.thickness = all.size().x;
    b.height = all.hi.z;
    b.face_height = all.hi.z;
    // the piles: where the parts stand across the channel at half the barrier's height (a sill lower than
    // that closes no outlet, a pile and its sill in one part stand where the pile does), merged where they
    // overlap; the outlets between them
    std::vector<Span> spans;
    for (std::size_t p = 0; p < mesh->parts(); ++p)
        for (const auto& [lo, hi] : geometry::spans_across(*mesh, p, 0.5 * b.height))
            spans.push_back({lo, hi});
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& c) { return a.lo < c.lo; });
    for (const Span& s : spans) {
        if (!b.piles.empty() && s.lo <= b.piles.back().hi)
            b.piles.back().hi = std::max(b.piles.back().hi, s.hi);
        else
            b.piles.push_back(s);
    }
    for (std::size_t k = 1; k < b.piles.size(); ++k) b.outlets.push_back({b.piles[k - 1].hi, b.piles[k].lo});
    b.outlet_width = b.outlets.empty() ? 0.0 : b.outlets.front().width();
    b.first_wall = walls.size();
    for (std::size_t p = 0; p < mesh->parts(); ++p) {
        // a part's pile: the one its centroid stands in, else the first its cut at half height meets
        const Vec3 c = mesh->centroid(p);
        const auto cut = geometry::spans_across(*mesh, p, 0.5 * b.height);
        int pile = -1;
        for (std::size_t k = 0; k < b.piles.size(); ++k)
            if (c.y >= b.piles[k].lo && c.y <= b.piles[k].hi) pile = static_cast<int>(k);
        for (std::size_t k = 0; k < b.piles.size() && pile < 0 && !cut.empty(); ++k)
            if (cut.front().first <= b.piles[k].hi && cut.front().second >= b.piles[k].lo)
                pile = static_cast<int>(k);
        pile = std::max(pile, 0);
        walls.push_back(dem::Wall::mesh_part(mesh->part_names[p], mesh, p, true));
        b.elements.push_back({false, walls.size() - 1, c, c.z, pile, true, p});
    }
    b.wall_count = walls.size() - b.first_wall;
    b.mesh = std::move(mesh);
    cfg.record("derived.barrier_face_x_m", b.face_x);
    cfg.record("derived.barrier_height_m", b.height);
    cfg.record("derived.barrier_mesh_parts", static_cast<std::int64_t>(b.elements.size()));
    cfg.record("derived.barrier_mesh_triangles", static_cast<std::int64_t>(b.mesh->triangles.size()));
    return b;
}

std::vector<std::size_t> mesh_cells_on_lattice(const Config& cfg, const BarrierInfo& barrier, double dx) {
    std::vector<std::size_t> counts;
    if (!barrier.mesh) return counts;
    const geometry::TriangleMesh& mesh = *barrier.mesh;
    for (std::size_t p = 0; p < mesh.parts(); ++p) {
        const geometry::Bounds pb = mesh.bounds(p);
        const auto span = [&](double lo, double hi) {
            return static_cast<int>(std::ceil((hi - lo) / dx)) + 2;
        };
        const geometry::CellGrid grid{
            {std::floor(pb.lo.x / dx - 1.0) * dx, std::floor(pb.lo.y / dx - 1.0) * dx,
             std::floor(pb.lo.z / dx - 1.0) * dx},
            dx,
            span(pb.lo.x, pb.hi.x) + 1,
            span(pb.lo.y, pb.hi.y) + 1,
            span(pb.lo.z, pb.hi.z) + 1};
        std::size_t cells = 0;
        geometry::for_cells_inside(mesh, p, grid, [&](int, int, int) { ++cells; });
        counts.push_back(cells);
        if (cells == 0) {
            const Vec3 size = pb.size();
            cfg.fail(
                "barrier.mesh_file",
                fmt::format("part '{}' ({:.3g} x {:.3g} x {:.3g} m) holds no lattice cell's centre at dx = "
                            "{:.3g} m: it is too thin for the lattice (refine lattice.dx_m or thicken it)",
                            mesh.part_names[p], size.x, size.y, size.z, dx));
        }
    }
    return counts;
}

std::string describe_mesh(const BarrierInfo& barrier, const std::vector<std::size_t>& cells) {
    const geometry::TriangleMesh& mesh = *barrier.mesh;
    const geometry::Bounds b = mesh.bounds();
    std::string parts;
    for (std::size_t p = 0; p < mesh.parts(); ++p)
        parts += fmt::format("{}'{}' {:.4g} m3{}", p > 0 ? ", " : "", mesh.part_names[p], mesh.volume(p),
                             p < cells.size() ? fmt::format(" on {} cells", cells[p]) : "");
    return fmt::format(
        "barrier mesh: {} triangles in {} parts ({}); X [{:.3f}, {:.3f}] Y [{:.3f}, {:.3f}] Z "
        "[{:.3f}, {:.3f}] m; {} outlet(s) across the channel",
        mesh.triangles.size(), mesh.parts(), parts, b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z, b.hi.z,
        barrier.outlets.size());
}

namespace {
// Triangles of mean edge `edge` (each about an equilateral one's area, √3/4 edge²) on a flat face within the
// reach of a grain of radius r (its list's reach: about 1.5 r)
double triangles_in_reach(double r, double edge) {
    return std::numbers::pi * std::pow(1.5 * r, 2) / (0.25 * std::sqrt(3.0) * edge * edge);
}
}  // namespace

std::string fine_mesh_warning(const std::string& key, const geometry::TriangleMesh& mesh, double r_min) {
    const double edge = mesh.mean_edge();
    if (r_min <= 0.0 || edge >= 0.25 * r_min) return {};
    return fmt::format(
        "{}: its {} triangles' edges are {:.3g} m on average, "
        "under a quarter of the grains' smallest radius ({:.3g} m): "
        "a grain near it looks at about {:.0f} of them every step, which slows the run; "
        "a coarser export of the same shape (its flat faces in fewer triangles) gives the same contacts",
        key, mesh.triangles.size(), edge, r_min, triangles_in_reach(r_min, edge));
}

std::vector<std::string> fine_mesh_warnings(const geometry::TriangleMesh* barrier_mesh,
                                            const geometry::TriangleMesh* channel_mesh, double r_min) {
    std::vector<std::string> warnings;
    for (const auto& [key, mesh] :
         {std::pair{"barrier.mesh_file", barrier_mesh}, std::pair{"channel.mesh_file", channel_mesh}})
        if (mesh != nullptr)
            if (std::string w = fine_mesh_warning(key, *mesh, r_min); !w.empty())
                warnings.push_back(std::move(w));
    return warnings;
}

}  // namespace sabo::scenario
