// SPDX-License-Identifier: MIT
// Open rigid barriers across an inclined channel (reference case C2, C3): closed, slit (one centred outlet)
// and sectional (n piles, n − 1 equal outlets, boundary piles flush with the side walls), normal to
// the bed ("OB") or vertical ("VB"), modelled by fixed overlapping spheres (the reference
// modelling) or by exact boxes. Besides the geometry, the builder lists the barrier's force
// elements (one per sphere or box, with the pile it belongs to) and its outlets, which the
// analyses of docs/analysis.md work on. Frame: X down-slope, Y across, Z normal to the bed.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "geometry/triangle_mesh.h"

namespace sabo::scenario {

struct Span {
    double lo = 0.0, hi = 0.0;  // m, across the channel (Y)
    [[nodiscard]] double width() const { return hi - lo; }
};

// One force-accounting element: a fixed sphere (index into the particles) or a box (index into the
// walls). `height` is the element centre's distance from the bed along the face.
struct BarrierElement {
    bool sphere = true;
    // the sphere's among the fixed spheres (BarrierInfo::sphere_position: they follow the mobile grains,
    // whose number changes when grains leave), or the box's or mesh part's (walls)
    std::size_t index = 0;
    Vec3 centre{};
    double height = 0.0;
    int pile = 0;
    bool mesh_part = false;  // a part of BarrierInfo::mesh (barrier.type = "mesh") …
    std::size_t part = 0;    // … this one
};

// barrier.type, barrier.orientation (OB: its face orthogonal to the bed; VB: vertical), barrier.model
enum class BarrierType : std::uint8_t { none, closed, slit, sectional, mesh };
enum class BarrierOrientation : std::uint8_t { OB, VB };
enum class BarrierModel : std::uint8_t { spheres, boxes };
inline constexpr std::array<std::string_view, 5> barrier_type_names{"none", "closed", "slit", "sectional",
                                                                    "mesh"};
inline constexpr std::array<std::string_view, 2> barrier_orientation_names{"OB", "VB"};
inline constexpr std::array<std::string_view, 2> barrier_model_names{"spheres", "boxes"};
// The case file's word for each (what summary.json and the logs print).
[[nodiscard]] constexpr std::string_view name(BarrierType t) {
    return barrier_type_names[static_cast<std::size_t>(t)];
}
[[nodiscard]] constexpr std::string_view name(BarrierOrientation o) {
    return barrier_orientation_names[static_cast<std::size_t>(o)];
}
[[nodiscard]] constexpr std::string_view name(BarrierModel m) {
    return barrier_model_names[static_cast<std::size_t>(m)];
}

struct BarrierInfo {
    BarrierType type = BarrierType::none;
    BarrierOrientation orientation = BarrierOrientation::OB;
    BarrierModel model = BarrierModel::spheres;
    std::string configuration;  // sectional: A–L or "custom"
    double face_x = 0.0;        // upstream face at Z = 0, m (type none: the reference plane)
    double thickness = 0.0;     // m, along the face normal
    double outlet_width = 0.0;  // S, m (0 for closed)
    double pile_width = 0.0;    // P of interior piles (sectional), m
    double height = 0.0;        // H_bar, m: bed to ceiling, normal to the bed
    double face_height = 0.0;   // length of the face from bed to ceiling, m
    Vec3 face_normal{1, 0, 0};  // unit normal of the face, pointing downstream
    Vec3 up{0, 0, 1};           // unit vector along the face, away from the bed
    double tan_tilt = 0.0;      // VB: the face is X = face_x − Z tan θ
    std::vector<Span> piles;    // ascending Y
    std::vector<Span> outlets;  // ascending Y
    std::vector<BarrierElement> elements;
    std::size_t first_wall = 0, wall_count = 0;          // barrier boxes in the wall list
    std::size_t sphere_count = 0;                        // fixed spheres (model = spheres)
    std::shared_ptr<const geometry::TriangleMesh> mesh;  // type mesh: its parts are the elements

    [[nodiscard]] bool present() const { return type != BarrierType::none; }
    // Where sphere element `el` is in a particle array of `size` entries whose last `sphere_count` are the
    // barrier's fixed spheres.
    [[nodiscard]] std::size_t sphere_position(const BarrierElement& el, std::size_t size) const {
        return size - sphere_count + el.index;
    }
    // Distance along X from the upstream face (at the point's height) to x; positive upstream.
    [[nodiscard]] double upstream_distance(const Vec3& x) const { return face_x - x.z * tan_tilt - x.x; }
    // Distance along the face normal from the upstream face plane to x; positive downstream.
    [[nodiscard]] double depth_into(const Vec3& x) const {
        return dot(x - Vec3{face_x, 0.0, 0.0}, face_normal);
    }
    // A grain is non-retained when its centre is downstream of the downstream face plane.
    [[nodiscard]] bool downstream(const Vec3& x) const { return depth_into(x) > thickness; }
    // Within the barrier's thickness (the slab over which the flux across it is measured, crest_flux.h).
    [[nodiscard]] bool in_slab(const Vec3& x) const {
        const double s = depth_into(x);
        return s >= 0.0 && s < thickness;
    }
};

// One sectional configuration of reference case C3: n piles (boundary piles included), interior pile width P,
// outlet width S (both absolute, m).
struct SectionalLayout {
    std::string name;
    int piles = 0;
    double pile_width = 0.0;
    double outlet_width = 0.0;
};
// A–L of reference case C3 (P as listed in cm, S = S/r × 5 cm).
[[nodiscard]] const std::vector<SectionalLayout>& sectional_configurations();
// Pile spans for n piles of width P (boundary piles b = (W − (n−2)P − (n−1)S)/2) across width W;
// throws InputError (naming `key`) when they do not fit.
[[nodiscard]] std::vector<Span> sectional_piles(const Config& cfg, const std::string& key,
                                                double channel_width, const SectionalLayout& layout);

struct ChannelShape {
    double length = 0.0, width = 0.0, height = 0.0;  // m
    double slope_deg = 0.0;                          // θ
    double gravity = 9.81;                           // m/s², its magnitude
};

// Reads [channel] (slope_deg, length_m, width_m, height_m); `gravity` gets gravity_m_s2 in the channel
// frame, g (sin θ, 0, −cos θ).
[[nodiscard]] ChannelShape read_channel_shape(const Config& cfg, Vec3& gravity);

// Reads [barrier] and adds its walls (boxes) or fixed spheres. `r_ref` is the released grains'
// mean radius (a slit's S/r refers to it).
[[nodiscard]] BarrierInfo build_barrier(const Config& cfg, const ChannelShape& channel, double r_ref,
                                        std::vector<dem::Wall>& walls, dem::Particles& particles);

}  // namespace sabo::scenario
