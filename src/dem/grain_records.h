// SPDX-License-Identifier: MIT
// What a grain and a contact are when they leave one solver for another (a run divided among MPI ranks,
// parallel/grain_halo.h): plain records, named by the grains' global ids, that can travel as bytes.
#pragma once
#include <cstdint>
#include <type_traits>

#include "core/vec3.h"
#include "dem/contact_law.h"

namespace sabo::dem {

// A mobile grain's whole state between steps: position, the leapfrog velocities (v half a step behind the
// positions, ω half a step ahead), the force and torque of the last evaluation, the outside force and torque
// held on it (the fluid's), its constants and its global id.
struct GrainRecord {
    Vec3 x, vh, wh, f, t, external_force, external_torque;
    double r = 0.0, m = 0.0, inv_m = 0.0, inv_j = 0.0;
    std::uint32_t id = 0;
    std::uint32_t contacts =
        0;  // active contacts in the last evaluation (the rolling updates split among them)
};

// What a ghost copy needs of its grain each step (the owner sets it): where it is and how it moves.
struct GhostState {
    Vec3 x, vh, wh;
    std::uint32_t contacts = 0;
    std::uint32_t padding = 0;
};

// The state of a live contact: grains a < b by global id (the spring ξ and the rolling torque as seen from
// a), or grain a and a wall (b = wall_key(w); a mesh wall's contacts with one grain each a record of the same
// a and b). Fixed spheres are named by their global ids like grains.
struct ContactRecord {
    std::uint32_t a = 0, b = 0;
    TangentialState history;
    Vec3 rolling;
    double normal_force = 0.0;  // of the last evaluation (> 0: the rolling sweep visits the contact)
    Vec3 normal{};              // a mesh wall's contact: its last normal (a grain has a few with one part)
};

// Keys above every grain id name walls.
inline constexpr std::uint32_t first_wall_key = 0xffff0000U;
[[nodiscard]] inline std::uint32_t wall_key(std::size_t wall) {
    return first_wall_key + static_cast<std::uint32_t>(wall);
}
// The same contact seen from its other grain (b, a): the spring and the rolling torque change sign.
[[nodiscard]] inline ContactRecord mirrored(const ContactRecord& c) {
    TangentialState seen_from_b = c.history;
    seen_from_b.xi = -seen_from_b.xi;
    return {c.b, c.a, seen_from_b, -c.rolling, c.normal_force};
}
[[nodiscard]] inline bool before(const ContactRecord& p, const ContactRecord& q) {
    return p.a != q.a ? p.a < q.a : p.b < q.b;
}

static_assert(std::is_trivially_copyable_v<GrainRecord> && std::is_trivially_copyable_v<GhostState> &&
              std::is_trivially_copyable_v<ContactRecord>);

}  // namespace sabo::dem
