// SPDX-License-Identifier: MIT
#include "geometry/mesh_queries.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace sabo::geometry {

namespace {

// (shifts across the ray of a cell centre or point, in units of dx: small, and not a simple fraction)
constexpr double shift_y = 1.0e-7 * 0.7071067811865476, shift_z = 1.0e-7 * 0.5772156649015329;

// Where the line {y = y0, z = z0} crosses triangle t (its x), and +1 when the triangle faces +x (the line
// leaves the solid there), −1 when it faces −x; nothing when it misses or runs along it.
std::optional<std::pair<double, int>> crossing(const TriangleMesh& m, std::size_t t, double y0, double z0) {
    const Vec3 a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    // barycentric coordinates in the y–z projection
    const double d = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
    if (d == 0.0) return std::nullopt;
    const double u = ((y0 - a.y) * (c.z - a.z) - (c.y - a.y) * (z0 - a.z)) / d;
    const double v = ((b.y - a.y) * (z0 - a.z) - (y0 - a.y) * (b.z - a.z)) / d;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) return std::nullopt;
    return std::pair{a.x + u * (b.x - a.x) + v * (c.x - a.x), d > 0.0 ? 1 : -1};
}

}  // namespace

void for_cells_inside(const TriangleMesh& mesh, std::size_t of_part, const CellGrid& grid,
                      const std::function<void(int, int, int)>& inside) {
    if (grid.nx <= 0 || grid.ny <= 0 || grid.nz <= 0) return;
    const double dx = grid.dx;
    // each row's crossings: the triangles binned by the rows their y–z extent covers
    std::vector<std::vector<std::pair<double, int>>> rows(static_cast<std::size_t>(grid.ny) *
                                                          static_cast<std::size_t>(grid.nz));
    const auto row_range = [&](double lo, double hi, double origin, int n) {
        const int first = std::max(0, static_cast<int>(std::ceil((lo - origin) / dx - 0.5 - 1e-6)));
        const int last = std::min(n - 1, static_cast<int>(std::floor((hi - origin) / dx - 0.5 + 1e-6)));
        return std::pair{first, last};
    };
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (mesh.part[t] != of_part) continue;
        const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        const auto [j0, j1] =
            row_range(std::min({a.y, b.y, c.y}), std::max({a.y, b.y, c.y}), grid.origin.y, grid.ny);
        const auto [k0, k1] =
            row_range(std::min({a.z, b.z, c.z}), std::max({a.z, b.z, c.z}), grid.origin.z, grid.nz);
        for (int k = k0; k <= k1; ++k)
            for (int j = j0; j <= j1; ++j) {
                const double y0 = grid.origin.y + (j + 0.5 + shift_y) * dx;
                const double z0 = grid.origin.z + (k + 0.5 + shift_z) * dx;
                if (const auto hit = crossing(mesh, t, y0, z0))
                    rows[static_cast<std::size_t>(k) * static_cast<std::size_t>(grid.ny) +
                         static_cast<std::size_t>(j)]
                        .push_back(*hit);
            }
    }
    for (int k = 0; k < grid.nz; ++k)
        for (int j = 0; j < grid.ny; ++j) {
            auto& row = rows[static_cast<std::size_t>(k) * static_cast<std::size_t>(grid.ny) +
                             static_cast<std::size_t>(j)];
            if (row.empty()) continue;
            std::sort(row.begin(), row.end());
            // walking along +x: a triangle facing −x is entered, one facing +x left
            std::size_t next = 0;
            int depth = 0;
            for (int i = 0; i < grid.nx; ++i) {
                const double xc = grid.origin.x + (i + 0.5) * dx;
                for (; next < row.size() && row[next].first < xc; ++next) depth -= row[next].second;
                if (depth > 0) inside(i, j, k);
            }
        }
}

bool contains(const TriangleMesh& mesh, std::size_t of_part, const Vec3& p) {
    const Bounds b = mesh.bounds(of_part);
    const double scale = std::max(norm(b.size()), 1e-300);
    const double y0 = p.y + shift_y * scale, z0 = p.z + shift_z * scale;
    int depth = 0;  // of the crossings behind p along x
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (mesh.part[t] != of_part) continue;
        if (const auto hit = crossing(mesh, t, y0, z0); hit && hit->first < p.x) depth -= hit->second;
    }
    return depth > 0;
}

std::vector<std::pair<double, double>> spans_across(const TriangleMesh& mesh, std::size_t of_part, double z) {
    std::vector<std::pair<double, double>> cuts;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (mesh.part[t] != of_part) continue;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        const auto add = [&](double y) {
            lo = std::min(lo, y);
            hi = std::max(hi, y);
        };
        for (int k = 0; k < 3; ++k) {  // each edge's point at height z (an edge in the plane: both ends)
            const Vec3 a = mesh.corner(t, k), b = mesh.corner(t, (k + 1) % 3);
            if (a.z == z) add(a.y);
            if ((a.z < z && b.z > z) || (a.z > z && b.z < z))
                add(a.y + (b.y - a.y) * (z - a.z) / (b.z - a.z));
        }
        if (lo <= hi) cuts.emplace_back(lo, hi);
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::pair<double, double>> spans;
    for (const auto& c : cuts) {
        if (!spans.empty() && c.first <= spans.back().second)
            spans.back().second = std::max(spans.back().second, c.second);
        else
            spans.push_back(c);
    }
    return spans;
}

double highest_crossing(const TriangleMesh& mesh, std::size_t of_part, double x, double y) {
    double highest = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (mesh.part[t] != of_part) continue;
        const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        // barycentric coordinates of (x, y) in the projected triangle (a vertical face projects on a line:
        // its crossings are those of the faces beside it)
        const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (std::abs(det) <= 1e-12 * norm(b - a) * norm(c - a)) continue;
        const double u = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
        const double v = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
        const double margin = -1e-12;
        if (u < margin || v < margin || u + v > 1.0 - margin) continue;
        const double z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
        if (!(z <= highest)) highest = z;  // (the first: NaN)
    }
    return highest;
}

Vec3 closest_point(const TriangleMesh& mesh, std::size_t t, const Vec3& p, TriangleFeature& where) {
    // by the region of the triangle's plane p projects into: a vertex, an edge or the face
    using Kind = TriangleFeature::Kind;
    const auto& v = mesh.triangles[t];
    const auto corner = [&](int k) {
        where = {Kind::vertex, v[static_cast<std::size_t>(k)], v[static_cast<std::size_t>(k)]};
    };
    const auto edge = [&](int i, int j) {
        const std::uint32_t a = v[static_cast<std::size_t>(i)], b = v[static_cast<std::size_t>(j)];
        where = {Kind::edge, std::min(a, b), std::max(a, b)};
    };
    const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        corner(0);
        return a;
    }
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        corner(1);
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        edge(0, 1);
        return a + ab * (d1 / (d1 - d3));
    }
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        corner(2);
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        edge(0, 2);
        return a + ac * (d2 / (d2 - d6));
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        edge(1, 2);
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    where = {Kind::face, 0, 0};
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

Vec3 closest_point(const TriangleMesh& mesh, std::size_t t, const Vec3& p) {
    TriangleFeature where;
    return closest_point(mesh, t, p, where);
}

bool TriangleFeature::on(const TriangleMesh& mesh, std::size_t t) const {
    if (kind == Kind::face) return false;
    const auto& v = mesh.triangles[t];
    const auto has = [&](std::uint32_t q) { return v[0] == q || v[1] == q || v[2] == q; };
    return has(a) && has(b);
}

double distance(const TriangleMesh& mesh, std::size_t of_part, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        if (mesh.part[t] == of_part) best = std::min(best, norm(closest_point(mesh, t, p) - p));
    return best;
}

}  // namespace sabo::geometry
