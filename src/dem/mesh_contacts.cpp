// SPDX-License-Identifier: MIT
#include "dem/mesh_contacts.h"

#include <algorithm>

#include "geometry/mesh_queries.h"

namespace sabo::dem {

namespace {

// What one triangle reports: its point nearest the centre, how far, and where on it.
struct Report {
    Vec3 point;
    double distance;
    std::uint32_t triangle;
    geometry::TriangleFeature where;
};

// Enough for a corner where 24 triangles meet and some neighbours; a finer fan keeps its nearest reports.
constexpr std::size_t max_reports = 48;

}  // namespace

MeshTouches mesh_touches(const Wall& wall, std::span<const std::uint32_t> candidates, const Vec3& x,
                         double r) {
    MeshTouches out;
    if (!wall.active || candidates.empty()) return out;
    const geometry::TriangleMesh& mesh = *wall.surface->mesh;
    std::array<Report, max_reports> reports;
    std::size_t n = 0;
    for (const std::uint32_t t : candidates) {
        Report q{};
        q.point = geometry::closest_point(mesh, t, x, q.where);
        q.distance = norm(q.point - x);
        q.triangle = t;
        // behind the triangle's plane: the far side of a thin part, or a centre that crossed the surface
        if (q.distance >= r || q.distance <= 0.0 || dot(x - q.point, mesh.area_vector(t)) <= 0.0) continue;
        if (n < max_reports) {
            reports[n++] = q;
        } else {  // keep the nearest
            auto farthest =
                std::max_element(reports.begin(), reports.end(),
                                 [](const Report& a, const Report& b) { return a.distance < b.distance; });
            if (q.distance < farthest->distance) *farthest = q;
        }
    }
    // a report stands where no triangle sharing its edge or corner comes nearer
    std::array<bool, max_reports> stands{};
    for (std::size_t i = 0; i < n; ++i) {
        stands[i] = true;
        for (std::size_t j = 0; j < n && stands[i]; ++j)
            if (reports[j].distance < reports[i].distance && reports[i].where.on(mesh, reports[j].triangle))
                stands[i] = false;
    }
    // nearest first (ties in the candidates' order), each edge, corner or place once
    std::array<std::uint8_t, max_reports> order{};
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (stands[i]) order[m++] = static_cast<std::uint8_t>(i);
    std::stable_sort(
        order.begin(), order.begin() + static_cast<std::ptrdiff_t>(m),
        [&](std::uint8_t a, std::uint8_t b) { return reports[a].distance < reports[b].distance; });
    const double same_place2 = 1e-18 * r * r;
    std::array<std::uint8_t, mesh_slots> taken{};
    for (std::size_t k = 0; k < m && out.count < mesh_slots; ++k) {
        const Report& q = reports[order[k]];
        bool repeated = false;
        for (std::uint32_t s = 0; s < out.count && !repeated; ++s) {
            const Report& p = reports[taken[s]];
            repeated = (q.where.kind != geometry::TriangleFeature::Kind::face && q.where == p.where) ||
                       norm2(q.point - p.point) < same_place2;
        }
        if (repeated) continue;
        taken[out.count] = order[k];
        out.touch[out.count++] = {(q.point - x) / q.distance, r - q.distance, q.triangle};
    }
    return out;
}

SlotChoice assign_slots(const MeshTouches& now, std::span<const Vec3> last_normal,
                        std::span<const std::uint8_t> touching) {
    SlotChoice choice;
    auto& slot_of = choice.slot;
    std::array<bool, mesh_slots> slot_used{}, placed{};
    std::uint32_t touching_count = 0, lone = 0;
    for (std::uint32_t s = 0; s < mesh_slots; ++s)
        if (touching[s] != 0) {
            ++touching_count;
            lone = s;
        }
    if (now.count == 1 && touching_count == 1) {
        slot_of[0] = lone;
        return choice;
    }
    // most aligned pairs first (ties: contact, then slot order)
    constexpr double within = 0.5;  // cos 60°
    while (true) {
        double best = within;
        std::uint32_t bc = mesh_slots, bs = mesh_slots;
        for (std::uint32_t c = 0; c < now.count; ++c) {
            if (placed[c]) continue;
            for (std::uint32_t s = 0; s < mesh_slots; ++s) {
                if (slot_used[s] || touching[s] == 0) continue;
                const double aligned = dot(now.touch[c].n, last_normal[s]);
                if (aligned > best) {
                    best = aligned;
                    bc = c;
                    bs = s;
                }
            }
        }
        if (bc == mesh_slots) break;
        slot_of[bc] = bs;
        placed[bc] = slot_used[bs] = true;
    }
    // the rest start afresh: in free slots in order, then in slots whose contact ended (now.count <=
    // mesh_slots: a slot is always left)
    for (std::uint32_t c = 0; c < now.count; ++c) {
        if (placed[c]) continue;
        std::uint32_t s = 0;
        while (s < mesh_slots && (slot_used[s] || touching[s] != 0)) ++s;
        if (s == mesh_slots)
            s = static_cast<std::uint32_t>(std::find(slot_used.begin(), slot_used.end(), false) -
                                           slot_used.begin());
        slot_of[c] = s;
        choice.fresh[c] = true;
        slot_used[s] = placed[c] = true;
    }
    return choice;
}

}  // namespace sabo::dem
