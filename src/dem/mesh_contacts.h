// SPDX-License-Identifier: MIT
// A grain's contacts with a part of a triangle mesh (docs/geometry.md): the places where the part's surface
// comes locally nearest the grain's centre — a face, an edge or a corner — so that a grain in a concave
// corner is pushed by each face it touches while a grain over an edge or a corner that several triangles
// share is pushed once; and which of the grain's history slots for the part each contact continues.
#pragma once
#include <array>
#include <cstdint>
#include <span>

#include "core/vec3.h"
#include "dem/walls.h"

namespace sabo::dem {

// The most contacts a grain keeps with one part: three faces meeting in a corner, and one to spare.
inline constexpr std::uint32_t mesh_slots = 4;

struct MeshTouches {
    std::array<WallTouch, mesh_slots> touch;
    std::uint32_t count = 0;
};

// The contacts of a sphere (centre x, radius r) with mesh wall `wall`, among its triangles `candidates`
// (ascending; every triangle within r of x among them), nearest first. Each triangle's point nearest x
// (closer than r, x in front of the triangle's plane) is a contact unless a triangle that shares that
// point's edge or corner comes nearer (the surface is not locally nearest there) or a nearer contact lies at
// the same edge, corner or place (reported by each triangle around it, counted once). On a convex part
// this leaves one contact, at the part's nearest point.
[[nodiscard]] MeshTouches mesh_touches(const Wall& wall, std::span<const std::uint32_t> candidates,
                                       const Vec3& x, double r);

// The slot (0 .. mesh_slots − 1) each of a grain's contacts with a part takes, and whether it starts a
// fresh history there.
struct SlotChoice {
    std::array<std::uint32_t, mesh_slots> slot{};
    std::array<bool, mesh_slots> fresh{};
};
// Given each slot's last normal and whether it was touching: a lone contact continues a lone touching slot,
// however its normal turned (a grain rolling over a convex part's edge keeps its history); otherwise contacts
// and touching slots are paired most aligned normals first, within 60°, and the contacts left start afresh
// in the free slots, in order. A slot that takes no contact is released by the caller.
[[nodiscard]] SlotChoice assign_slots(const MeshTouches& now, std::span<const Vec3> last_normal,
                                      std::span<const std::uint8_t> touching);

}  // namespace sabo::dem
