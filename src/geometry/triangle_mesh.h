// SPDX-License-Identifier: MIT
// A surface of triangles with shared vertices, in named parts (one STL solid each: a pile, a wing, a sill),
// the form in which a user's own barrier or channel enters a run (docs/geometry.md). Units: whatever the
// file's, until transformed() scales them to metres.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace sabo::geometry {

struct Bounds {
    Vec3 lo{}, hi{};
    [[nodiscard]] Vec3 size() const { return hi - lo; }
};

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
    std::vector<std::uint16_t> part;                      // per triangle
    std::vector<std::string> part_names;

    [[nodiscard]] std::size_t parts() const { return part_names.size(); }
    [[nodiscard]] Vec3 corner(std::size_t t, int k) const {
        return vertices[triangles[t][static_cast<std::size_t>(k)]];
    }
    // (b − a) × (c − a): along the outward normal, twice the area
    [[nodiscard]] Vec3 area_vector(std::size_t t) const {
        return cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0));
    }
    [[nodiscard]] Bounds bounds() const;
    [[nodiscard]] Bounds bounds(std::size_t of_part) const;
    // The volume a closed part encloses (positive when its triangles face outward), and its centroid.
    [[nodiscard]] double volume(std::size_t of_part) const;
    [[nodiscard]] Vec3 centroid(std::size_t of_part) const;
    // The mean length of the triangles' edges (each edge as often as triangles have it).
    [[nodiscard]] double mean_edge() const;
};

// The mesh scaled by `scale`, rotated by `rotation_deg` about x, then y, then z (degrees), then moved by
// `translation` (metres after the scale).
[[nodiscard]] TriangleMesh transformed(const TriangleMesh& mesh, double scale, const Vec3& rotation_deg,
                                       const Vec3& translation);

// Throws InputError naming `what` (the file, or the case key that names it) when a part is not a closed
// surface (an edge not shared by exactly two of its triangles, in opposite directions), a triangle is
// degenerate (area below 1e-12 of the part's size squared), or a part's triangles face inward (negative
// volume). What a barrier of solid cells needs: inside and outside well defined.
void check_closed(const TriangleMesh& mesh, const std::string& what);

}  // namespace sabo::geometry
