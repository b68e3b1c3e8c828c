// SPDX-License-Identifier: MIT
// What a run asks of a closed mesh (docs/geometry.md): which lattice cells' centres lie inside a part (the
// solid cells of a barrier on the lattice), whether a point does, and how far a point is from the surface.
// Inside is decided by the crossings of a ray along +x, each counted with the side its triangle faces (a
// winding number: a part that overlaps itself still counts once); the ray is shifted by 1e-7 Δx across, so
// that a ray along a shared edge or through a vertex is counted in exactly one of the triangles there.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace sabo::geometry {

// Cells of side dx, cell (i, j, k) centred at origin + ((i, j, k) + 0.5) dx.
struct CellGrid {
    Vec3 origin{};
    double dx = 1.0;
    int nx = 0, ny = 0, nz = 0;
};

// Calls inside(i, j, k) for every cell of `grid` whose centre lies inside part `of_part`, row by row (k, j,
// then i ascending).
void for_cells_inside(const TriangleMesh& mesh, std::size_t of_part, const CellGrid& grid,
                      const std::function<void(int, int, int)>& inside);

[[nodiscard]] bool contains(const TriangleMesh& mesh, std::size_t of_part, const Vec3& p);

// Where part `of_part` stands across y at height z: the y-extents of its cut by the plane z = const (each
// triangle that reaches the plane adds the y-range of its cut, a face lying in it its own), merged where
// they overlap, ascending. A pile and its sill in one part stand only where the pile does above the sill.
[[nodiscard]] std::vector<std::pair<double, double>> spans_across(const TriangleMesh& mesh,
                                                                  std::size_t of_part, double z);

// The highest z at which the vertical line through (x, y) meets part `of_part`'s surface (a triangle whose
// projection on the x–y plane holds the point, edges included), or NaN where it meets none: the top of a
// bed's relief there.
[[nodiscard]] double highest_crossing(const TriangleMesh& mesh, std::size_t of_part, double x, double y);

// The point of triangle t nearest to p.
[[nodiscard]] Vec3 closest_point(const TriangleMesh& mesh, std::size_t t, const Vec3& p);
// Where on its triangle a nearest point lies: a corner (vertex a = b), an edge (vertices a < b) or inside
// the face.
struct TriangleFeature {
    enum class Kind : std::uint8_t { vertex, edge, face } kind = Kind::face;
    std::uint32_t a = 0, b = 0;
    // True when triangle t of `mesh` has this corner or edge (a face belongs to its triangle alone).
    [[nodiscard]] bool on(const TriangleMesh& mesh, std::size_t t) const;
    friend bool operator==(const TriangleFeature&, const TriangleFeature&) = default;
};
// The same point (the same arithmetic), and where on the triangle it lies.
[[nodiscard]] Vec3 closest_point(const TriangleMesh& mesh, std::size_t t, const Vec3& p,
                                 TriangleFeature& where);
// The distance from p to the surface of part `of_part`.
[[nodiscard]] double distance(const TriangleMesh& mesh, std::size_t of_part, const Vec3& p);

}  // namespace sabo::geometry
