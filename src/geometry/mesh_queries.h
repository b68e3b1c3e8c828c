// SPDX-License-Identifier: MIT
// What a run asks of a closed mesh (docs/geometry.md): which lattice cells' centres lie inside a part (the
// solid cells of a barrier on the lattice), whether a point does, and how far a point is from the surface.
// Inside is decided by the crossings of a ray along +x, each counted with the side its triangle faces (a
// winding number: a part that overlaps itself still counts once); the ray is shifted by 1e-7 Δx across, so
// that a ray along a shared edge or through a vertex is counted in exactly one of the triangles there.
#pragma once
#include <cstddef>
#include <functional>

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

// The point of triangle t nearest to p.
[[nodiscard]] Vec3 closest_point(const TriangleMesh& mesh, std::size_t t, const Vec3& p);
// The distance from p to the surface of part `of_part`.
[[nodiscard]] double distance(const TriangleMesh& mesh, std::size_t of_part, const Vec3& p);

}  // namespace sabo::geometry
