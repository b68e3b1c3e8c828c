// SPDX-License-Identifier: MIT
#include "geometry/triangle_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "core/error.h"

namespace sabo::geometry {

namespace {

Bounds bounds_of(const TriangleMesh& m, const auto& use) {
    constexpr double big = 1e300;
    Bounds b{{big, big, big}, {-big, -big, -big}};
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        if (!use(t)) continue;
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = m.corner(t, k);
            b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
            b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
        }
    }
    return b;
}

Vec3 rotated(const Vec3& p, const Vec3& deg) {
    const double to_rad = std::numbers::pi / 180.0;
    Vec3 q = p;
    const double ax = deg.x * to_rad, ay = deg.y * to_rad, az = deg.z * to_rad;
    q = {q.x, std::cos(ax) * q.y - std::sin(ax) * q.z, std::sin(ax) * q.y + std::cos(ax) * q.z};
    q = {std::cos(ay) * q.x + std::sin(ay) * q.z, q.y, -std::sin(ay) * q.x + std::cos(ay) * q.z};
    q = {std::cos(az) * q.x - std::sin(az) * q.y, std::sin(az) * q.x + std::cos(az) * q.y, q.z};
    return q;
}

}  // namespace

Bounds TriangleMesh::bounds() const {
    return bounds_of(*this, [](std::size_t) { return true; });
}

Bounds TriangleMesh::bounds(std::size_t of_part) const {
    return bounds_of(*this, [&](std::size_t t) { return part[t] == of_part; });
}

double TriangleMesh::volume(std::size_t of_part) const {
    // the divergence theorem: Σ a · (b × c) / 6 over the triangles
    double v = 0.0;
    for (std::size_t t = 0; t < triangles.size(); ++t)
        if (part[t] == of_part) v += dot(corner(t, 0), cross(corner(t, 1), corner(t, 2))) / 6.0;
    return v;
}

double TriangleMesh::mean_edge() const {
    if (triangles.empty()) return 0.0;
    double sum = 0.0;
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) sum += norm(corner(t, (k + 1) % 3) - corner(t, k));
    return sum / (3.0 * static_cast<double>(triangles.size()));
}

Vec3 TriangleMesh::centroid(std::size_t of_part) const {
    // each tetrahedron (origin, a, b, c) weighted by its signed volume; relative to a corner of the part
    // (fewer digits lost far from the origin)
    const Bounds b = bounds(of_part);
    Vec3 sum{};
    double v = 0.0;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        if (part[t] != of_part) continue;
        const Vec3 a = corner(t, 0) - b.lo, p = corner(t, 1) - b.lo, c = corner(t, 2) - b.lo;
        const double w = dot(a, cross(p, c)) / 6.0;
        sum += (a + p + c) * (w / 4.0);
        v += w;
    }
    return v != 0.0 ? b.lo + sum / v : b.lo + b.size() * 0.5;
}

TriangleMesh transformed(const TriangleMesh& mesh, double scale, const Vec3& rotation_deg,
                         const Vec3& translation) {
    TriangleMesh out = mesh;
    for (Vec3& p : out.vertices) p = rotated(p * scale, rotation_deg) + translation;
    return out;
}

void check_closed(const TriangleMesh& mesh, const std::string& what) {
    for (std::size_t p = 0; p < mesh.parts(); ++p) {
        const std::string name = mesh.part_names[p];
        const Bounds b = mesh.bounds(p);
        const double size = norm(b.size());
        // each directed edge once; its reverse once
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
        std::size_t count = 0;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            if (mesh.part[t] != p) continue;
            ++count;
            if (norm(mesh.area_vector(t)) <= 2e-12 * size * size)
                throw InputError(
                    fmt::format("{}: part '{}': triangle {} is degenerate (its corners on a line or "
                                "one point)",
                                what, name, t));
            for (int k = 0; k < 3; ++k) {
                const auto a = mesh.triangles[t][static_cast<std::size_t>(k)];
                const auto c = mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
                if (++edges[{a, c}] > 1)
                    throw InputError(
                        fmt::format("{}: part '{}': the edge between vertices {} and {} is used twice in "
                                    "one direction (triangles facing opposite ways, or more than "
                                    "two triangles on an edge)",
                                    what, name, a, c));
            }
        }
        if (count == 0) throw InputError(fmt::format("{}: part '{}' has no triangles", what, name));
        for (const auto& [edge, n] : edges)
            if (edges.find({edge.second, edge.first}) == edges.end()) {
                const Vec3 at = mesh.vertices[edge.first];
                throw InputError(
                    fmt::format("{}: part '{}' is not closed: the edge from ({:.6g}, {:.6g}, {:.6g}) "
                                "has a triangle on one side only (a hole; a closed surface is needed "
                                "to tell inside from outside)",
                                what, name, at.x, at.y, at.z));
            }
        if (mesh.volume(p) <= 0.0)
            throw InputError(
                fmt::format("{}: part '{}' faces inward (its enclosed volume is negative): reverse "
                            "its triangles' order",
                            what, name));
    }
}

}  // namespace sabo::geometry
