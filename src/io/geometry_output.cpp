// SPDX-License-Identifier: MIT
#include "io/geometry_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <vector>

#include "io/vtk_writer.h"

namespace sabo::io {

namespace {

// A surface of polygons, each with the cell data of the wall or sphere it belongs to.
struct Surface {
    std::vector<Vec3> points;
    std::vector<std::int64_t> connectivity, offsets;
    // per polygon: indices (−1: not one), 1 for the barrier's
    std::vector<double> wall, sphere, barrier, part;

    void polygon(std::span<const Vec3> corners, double wall_index, double sphere_index, bool of_barrier) {
        for (const Vec3& c : corners) {
            connectivity.push_back(static_cast<std::int64_t>(points.size()));
            points.push_back(c);
        }
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        wall.push_back(wall_index);
        sphere.push_back(sphere_index);
        barrier.push_back(of_barrier ? 1.0 : 0.0);
        part.push_back(-1.0);
    }
    // a barrier sphere's facet of points already added
    void polygon_of(std::initializer_list<std::int64_t> corners, double sphere_index) {
        connectivity.insert(connectivity.end(), corners);
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        wall.push_back(-1.0);
        sphere.push_back(sphere_index);
        barrier.push_back(1.0);
        part.push_back(-1.0);
    }
};

// The polygon where the plane through `point` with unit `normal` cuts the box [0, box]: the points where
// it crosses the box's 12 edges (an edge lying in the plane gives both ends), ordered around their centre.
std::vector<Vec3> plane_in_box(const Vec3& point, const Vec3& normal, const Vec3& box) {
    const double eps = 1e-9 * (box.x + box.y + box.z);
    const auto corner = [&](int i) {
        return Vec3{(i & 1) != 0 ? box.x : 0.0, (i & 2) != 0 ? box.y : 0.0, (i & 4) != 0 ? box.z : 0.0};
    };
    std::vector<Vec3> cut;
    const auto add = [&](const Vec3& p) {
        for (const Vec3& q : cut)
            if (norm(q - p) <= eps) return;
        cut.push_back(p);
    };
    for (int a = 0; a < 8; ++a)
        for (int bit = 1; bit < 8; bit <<= 1) {
            if ((a & bit) != 0) continue;  // each edge once: from the corner without the bit
            const Vec3 p = corner(a), q = corner(a | bit);
            const double dp = dot(p - point, normal), dq = dot(q - point, normal);
            if (std::abs(dp) <= eps) add(p);
            if (std::abs(dq) <= eps) add(q);
            if ((dp < -eps && dq > eps) || (dp > eps && dq < -eps)) add(p + (q - p) * (dp / (dp - dq)));
        }
    if (cut.size() < 3) return {};
    Vec3 centre{};
    for (const Vec3& p : cut) centre += p;
    centre = centre / static_cast<double>(cut.size());
    // a basis of the plane: u along the first point, v = n × u
    const Vec3 u = (cut[0] - centre) / norm(cut[0] - centre);
    const Vec3 v = cross(normal, u);
    std::sort(cut.begin(), cut.end(), [&](const Vec3& a, const Vec3& b) {
        return std::atan2(dot(a - centre, v), dot(a - centre, u)) <
               std::atan2(dot(b - centre, v), dot(b - centre, u));
    });
    return cut;
}

void add_box(Surface& s, const dem::Wall& w, double index) {
    // face ±axis a: its four corners in order around it
    for (int a = 0; a < 3; ++a)
        for (const double side : {-1.0, 1.0}) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const auto axis = [&](int k) { return w.axes[static_cast<std::size_t>(k)] * w.half[k]; };
            const Vec3 centre = w.point + axis(a) * side;  // (a box's point is its centre)
            const Vec3 eb = axis(b), ec = axis(c);
            const std::array<Vec3, 4> q{centre - eb - ec, centre + eb - ec, centre + eb + ec,
                                        centre - eb + ec};
            s.polygon(q, index, -1.0, w.barrier);
        }
}

void add_sphere(Surface& s, const Vec3& x, double r, double index) {
    // the poles and `rings` − 1 circles of `around` points, shared by the facets around them
    constexpr int around = 8, rings = 4;
    const auto first = static_cast<std::int64_t>(s.points.size());
    s.points.push_back(x + Vec3{0, 0, r});
    for (int j = 1; j < rings; ++j)
        for (int i = 0; i < around; ++i) {
            const double theta = std::numbers::pi * j / rings, phi = 2.0 * std::numbers::pi * i / around;
            s.points.push_back(
                x +
                Vec3{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)} * r);
        }
    s.points.push_back(x - Vec3{0, 0, r});
    const std::int64_t south = static_cast<std::int64_t>(s.points.size()) - 1;
    const auto at = [&](int i, int j) {  // circle j (1 … rings − 1), point i
        return first + 1 + static_cast<std::int64_t>((j - 1) * around + i % around);
    };
    for (int i = 0; i < around; ++i) {
        s.polygon_of({first, at(i, 1), at(i + 1, 1)}, index);
        for (int j = 1; j + 1 < rings; ++j)
            s.polygon_of({at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)}, index);
        s.polygon_of({at(i, rings - 1), south, at(i + 1, rings - 1)}, index);
    }
}

}  // namespace

void write_geometry(const std::filesystem::path& file, std::span<const dem::Wall> walls,
                    const dem::Particles& particles, const Vec3& box, const geometry::TriangleMesh* mesh) {
    Surface s;
    for (std::size_t w = 0; w < walls.size(); ++w) {
        const dem::Wall& wall = walls[w];
        if (wall.shape == dem::WallShape::mesh) {
            if (wall.barrier) continue;                             // (a barrier's mesh: written whole below)
            const geometry::TriangleMesh& m = *wall.surface->mesh;  // a channel's mesh part: its triangles
            for (const std::uint32_t t : wall.surface->triangles) {
                const std::array<Vec3, 3> c{m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)};
                s.polygon(c, static_cast<double>(w), -1.0, false);
            }
            continue;
        }
        if (wall.shape == dem::WallShape::box) {
            add_box(s, wall, static_cast<double>(w));
        } else {
            const std::vector<Vec3> cut = plane_in_box(wall.point, wall.normal, box);
            if (!cut.empty()) s.polygon(cut, static_cast<double>(w), -1.0, wall.barrier);
        }
    }
    for (std::size_t i = particles.n_mobile; i < particles.x.size(); ++i)
        add_sphere(s, particles.x[i], particles.r[i], static_cast<double>(i - particles.n_mobile));
    if (mesh != nullptr) {  // (its parts numbered as the barrier's elements, in `barrier_part`)
        for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
            const std::array<Vec3, 3> c{mesh->corner(t, 0), mesh->corner(t, 1), mesh->corner(t, 2)};
            s.polygon(c, -1.0, -1.0, true);
            s.part.back() = mesh->part[t];
        }
    }
    SurfaceWriter out(s.points, s.connectivity, s.offsets);
    out.cell_scalar("barrier_part", s.part);
    out.cell_scalar("wall", s.wall);
    out.cell_scalar("barrier_sphere", s.sphere);
    out.cell_scalar("barrier", s.barrier);
    out.write(file);
}

}  // namespace sabo::io
