// SPDX-License-Identifier: MIT
#include "dem/walls.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/mesh_queries.h"

namespace sabo::dem {

Wall Wall::plane(std::string name, const Vec3& point, const Vec3& normal, bool barrier) {
    Wall w;
    w.shape = WallShape::plane;
    w.name = std::move(name);
    w.point = point;
    w.normal = normal / norm(normal);
    w.barrier = barrier;
    return w;
}

Wall Wall::box(std::string name, const Vec3& centre, const std::array<Vec3, 3>& axes, const Vec3& half,
               bool barrier) {
    Wall w;
    w.shape = WallShape::box;
    w.name = std::move(name);
    w.point = centre;
    for (int k = 0; k < 3; ++k) w.axes[k] = axes[k] / norm(axes[k]);
    w.half = half;
    w.barrier = barrier;
    return w;
}

Wall Wall::mesh_part(std::string name, std::shared_ptr<const geometry::TriangleMesh> mesh, std::size_t part,
                     bool barrier) {
    Wall w;
    w.shape = WallShape::mesh;
    w.name = std::move(name);
    w.barrier = barrier;
    auto surface = std::make_shared<MeshSurface>();
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t)
        if (mesh->part[t] == part) surface->triangles.push_back(static_cast<std::uint32_t>(t));
    const geometry::Bounds b = mesh->bounds(part);
    surface->lo = b.lo;
    surface->hi = b.hi;
    surface->bins = geometry::TriangleBins(*mesh, surface->triangles);
    w.point = mesh->centroid(part);
    surface->mesh = std::move(mesh);
    w.surface = std::move(surface);
    return w;
}

namespace {

// The distance from x to the part's bounding box (0 inside it).
double box_gap(const MeshSurface& s, const Vec3& x) {
    const Vec3 d{std::max({s.lo.x - x.x, 0.0, x.x - s.hi.x}), std::max({s.lo.y - x.y, 0.0, x.y - s.hi.y}),
                 std::max({s.lo.z - x.z, 0.0, x.z - s.hi.z})};
    return norm(d);
}

// The point nearest x among the part's triangles `candidates`, and its distance (infinite: none).
double mesh_distance(const MeshSurface& s, std::span<const std::uint32_t> candidates, const Vec3& x,
                     Vec3& nearest) {
    double best = std::numeric_limits<double>::infinity();
    for (const std::uint32_t t : candidates) {
        const Vec3 c = geometry::closest_point(*s.mesh, t, x);
        const double d = norm(c - x);
        if (d < best) {
            best = d;
            nearest = c;
        }
    }
    return best;
}

// Closest-point query on an oriented box. Returns the signed distance from x to the surface
// (negative inside) and the outward unit normal at the closest surface point.
double box_distance(const Wall& b, const Vec3& x, Vec3& outward) {
    const Vec3 d = x - b.point;
    const double p[3] = {dot(d, b.axes[0]), dot(d, b.axes[1]), dot(d, b.axes[2])};
    const double h[3] = {b.half.x, b.half.y, b.half.z};
    double q[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
        q[k] = std::clamp(p[k], -h[k], h[k]);
        if (q[k] != p[k]) inside = false;
    }
    if (inside) {
        int best = 0;
        double depth = h[0] - std::abs(p[0]);
        for (int k = 1; k < 3; ++k) {
            const double dk = h[k] - std::abs(p[k]);
            if (dk < depth) {
                depth = dk;
                best = k;
            }
        }
        outward = b.axes[best] * (p[best] >= 0.0 ? 1.0 : -1.0);
        return -depth;
    }
    const Vec3 local{p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    const double dist = norm(local);
    const Vec3 dir = local / dist;
    outward = b.axes[0] * dir.x + b.axes[1] * dir.y + b.axes[2] * dir.z;
    return dist;
}

}  // namespace

bool touches_box(const Wall& wall, const Vec3& x, double r, WallTouch& out) {
    Vec3 outward;
    const double d = box_distance(wall, x, outward);
    if (d >= r) return false;
    out.n = -outward;
    out.delta = r - d;
    return true;
}

bool touches_mesh(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x, double r,
                  WallTouch& out) {
    Vec3 nearest;
    const double d = mesh_distance(*wall.surface, candidates, x, nearest);
    if (d >= r || d <= 0.0) return false;
    out.n = (nearest - x) / d;
    out.delta = r - d;
    return true;
}

void triangles_within(const Wall& wall, const Vec3& x, double reach, std::vector<std::uint32_t>& out) {
    out.clear();
    if (wall.shape != WallShape::mesh || !wall.active) return;
    const MeshSurface& s = *wall.surface;
    if (box_gap(s, x) >= reach) return;
    s.bins.near(x, reach, out,
                [&](std::uint32_t t) { return norm(geometry::closest_point(*s.mesh, t, x) - x) < reach; });
}

bool touches(const Wall& wall, const Vec3& x, double r, WallTouch& out) {
    std::vector<std::uint32_t> candidates;
    triangles_within(wall, x, r, candidates);
    return touches(wall, candidates, x, r, out);
}

double clearance(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x, double r) {
    if (!wall.active) return 1e300;
    if (wall.shape == WallShape::mesh) {
        Vec3 nearest;
        const double d = mesh_distance(*wall.surface, candidates, x, nearest);
        return std::isfinite(d) ? d - r : 1e300;
    }
    if (wall.shape == WallShape::plane) {
        const double d = dot(x - wall.point, wall.normal);
        return d <= -r ? 1e300 : d - r;
    }
    Vec3 outward;
    return box_distance(wall, x, outward) - r;
}

}  // namespace sabo::dem
