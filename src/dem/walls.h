// SPDX-License-Identifier: MIT
// Rigid walls: one-sided planes and oriented boxes. Each wall is also a force-accounting element:
// the solver accumulates the contact force it receives each step (docs/dem.md).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "geometry/triangle_bins.h"
#include "geometry/triangle_mesh.h"

namespace sabo::dem {

enum class WallShape { plane, box, mesh };

// A closed part of a triangle mesh as a wall (a barrier's pile from the user's STL, docs/geometry.md): its
// triangles, their bounding box and their bins (the neighbour lists find a grain's triangles in them).
struct MeshSurface {
    std::shared_ptr<const geometry::TriangleMesh> mesh;
    std::vector<std::uint32_t> triangles;  // of the part
    Vec3 lo{}, hi{};                       // their bounding box
    geometry::TriangleBins bins;
};

struct Wall {
    WallShape shape = WallShape::plane;
    std::string name;
    bool barrier = false;  // particle–barrier contact law and barrier force accounting
    bool active = true;    // inactive walls are ignored (e.g. an outlet gate after opening)
    // plane: a point on it and the unit normal pointing into the domain
    Vec3 point{};
    Vec3 normal{0, 0, 1};
    // box: centre, orthonormal axes and half extents along them
    std::array<Vec3, 3> axes{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
    Vec3 half{};
    // mesh: the part's surface (shared between copies of the wall)
    std::shared_ptr<const MeshSurface> surface;

    static Wall plane(std::string name, const Vec3& point, const Vec3& normal, bool barrier = false);
    static Wall box(std::string name, const Vec3& centre, const std::array<Vec3, 3>& axes, const Vec3& half,
                    bool barrier = false);
    // Part `part` of `mesh` (a closed surface), its triangles facing out.
    static Wall mesh_part(std::string name, std::shared_ptr<const geometry::TriangleMesh> mesh,
                          std::size_t part, bool barrier = false);
};

// Contact of a sphere with a wall: normal from the sphere centre towards the wall, overlap δ.
struct WallTouch {
    Vec3 n{};
    double delta = 0.0;
    std::uint32_t triangle =
        0;  // a mesh's: the triangle whose point it is (of those that share it, the first)
};

bool touches_box(const Wall& wall, const Vec3& x, double r, WallTouch& out);
// A mesh part, among its triangles `candidates` (ascending; the neighbour list's, which hold every triangle
// the sphere can reach): the contact at the part's point nearest the centre (a face, an edge or a corner),
// the normal from the centre to that point — for queries (is a grain clear of the part?); a grain's
// contacts in a run, concave corners included, are mesh_touches() (dem/mesh_contacts.h).
bool touches_mesh(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x, double r,
                  WallTouch& out);

// The triangles of a mesh wall within `reach` of x, ascending, into `out` (cleared first; left empty for
// the other shapes): a grain's candidates in the neighbour list.
void triangles_within(const Wall& wall, const Vec3& x, double reach, std::vector<std::uint32_t>& out);

// True when a sphere at x with radius r overlaps the wall (δ > 0); a mesh's triangles among `candidates`
// (triangles_within() at a reach ≥ r). A plane acts on spheres whose centre lies less than r in front of it
// and not more than r behind it.
inline bool touches(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x, double r,
                    WallTouch& out) {
    if (!wall.active) return false;
    if (wall.shape == WallShape::box) return touches_box(wall, x, r, out);
    if (wall.shape == WallShape::mesh) return touches_mesh(wall, candidates, x, r, out);
    const double d = dot(x - wall.point, wall.normal);
    if (d >= r || d <= -r) return false;
    out.n = -wall.normal;
    out.delta = r - d;
    return true;
}
// The same, a mesh's candidates found here (a query outside the time loop).
bool touches(const Wall& wall, const Vec3& x, double r, WallTouch& out);

// Distance from x to the wall surface minus r (negative when overlapping); a mesh's among `candidates`
// (1e300 when none is given). Used to skip far walls.
double clearance(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x, double r);

}  // namespace sabo::dem
