// SPDX-License-Identifier: MIT
// Inclined-channel scenario of reference case C2: six frictional walls, a released block of spheres on a
// cubic lattice, and an optional barrier (scenario/barrier.h). Frame: X down-slope, Y across, Z
// normal to the bed; gravity 9.81 (sin θ, 0, −cos θ).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "scenario/barrier.h"
#include "scenario/channel_bounds.h"
#include "scenario/grain_inflow.h"

namespace sabo::scenario {

// release.mixture and release.compaction (high: pre-settled against a temporary barrier, reference case C4)
enum class Mixture : std::uint8_t { monodisperse, bidisperse };
enum class Compaction : std::uint8_t { low, high };
inline constexpr std::array<std::string_view, 2> mixture_names{"monodisperse", "bidisperse"};
inline constexpr std::array<std::string_view, 2> compaction_names{"low", "high"};
[[nodiscard]] constexpr std::string_view name(Mixture m) {
    return mixture_names[static_cast<std::size_t>(m)];
}
[[nodiscard]] constexpr std::string_view name(Compaction c) {
    return compaction_names[static_cast<std::size_t>(c)];
}

struct ReleaseInfo {
    std::string lattice_rule;
    std::size_t count = 0;
    double solid_volume = 0.0;  // m³
    Vec3 lo{}, hi{};            // extents of the grains (surfaces), m
    // r_mean: the reference radius r of S/r (the mean radius; the large radius R of a mixture)
    double r_mean = 0.0, r_min = 0.0, r_max = 0.0, density = 0.0;
    Mixture mixture = Mixture::monodisperse;               // or bidisperse (reference case C4)
    double r_large = 0.0, r_small = 0.0, phi_small = 0.0;  // bidisperse: R, r, V_small/V_total
    double equivalent_radius = 0.0;  // r* = (Φ_large R³ + Φ_small r³)^(1/3); r_mean if monodisperse
    int cluster = 1;                 // bidisperse: small grains per site along each axis
    Compaction compaction =
        Compaction::low;  // high: pre-settled against a temporary barrier (cases/channel/presettle.h)
    double settle_max_time = 20.0;  // s, longest pre-settling
};

struct ChannelCase {
    std::string name;
    dem::Particles particles;
    std::vector<dem::Wall> walls;
    Vec3 gravity{};
    double slope_deg = 0.0;
    double length = 0.0, width = 0.0, height = 0.0;  // height: the side walls'
    ChannelBounds bounds;  // its top (a lid by default), the domain's top above the bed, its end
    double end_time = 0.0;
    double velocity_scale = 0.0;  // m/s, free-fall speed over the drop from the block to the barrier
    ReleaseInfo release;  // count 0 when the grains come from the inflow alone (release.solid_volume_m3 = 0)
    BarrierInfo barrier;
    std::optional<InflowSettings> inflow;  // [inflow]: grains fed from a hydrograph
    // channel.mesh_file: the side walls' mesh (its parts walls for the grains, after the box's walls)
    std::shared_ptr<const geometry::TriangleMesh> channel_mesh;
};

// `place_grains` false: the release counted but not placed (`sabo check`).
[[nodiscard]] ChannelCase build_channel_case(const Config& cfg, bool place_grains = true);

// The six walls of the channel: bed, ceiling, two sides, upstream and downstream ends.
[[nodiscard]] std::vector<dem::Wall> channel_walls(const ChannelShape& shape);

// The channel's side walls and bed relief from a mesh (channel.mesh_file, scaled, rotated and moved as a
// barrier's mesh; none without): its parts appended to `walls` — a part whose name begins with "bed"
// (is_bed_part) as bed_mesh_<part>, on the inclined bed plane, the others as side_mesh_<part> in place of the
// box's side planes, which it then takes out (under an open top, the box's side slabs). Under an open top
// the domain's sides open above channel.height_m, whatever the mesh's height: open_top_mesh_warning() says
// when its side walls' top differs.
[[nodiscard]] std::shared_ptr<const geometry::TriangleMesh> mesh_channel_parts(const Config& cfg,
                                                                               const ChannelShape& shape,
                                                                               const ChannelBounds& bounds,
                                                                               std::vector<dem::Wall>& walls);
// Whether a channel mesh's part named `name` is relief on the bed (a sill, a step, a hump: its name begins
// with "bed", in any case) rather than a side wall.
[[nodiscard]] bool is_bed_part(std::string_view name);
// The bed's level at (x, y), m above the inclined bed plane: the highest top of the mesh's bed parts there,
// or 0 (no mesh, no bed part above the point, or one below the plane).
[[nodiscard]] double bed_level(const geometry::TriangleMesh* mesh, double x, double y);
// The bed's highest level over the rectangle [x0, x1] × [y0, y1] (a released block's footprint: the block
// stands on it), exactly: of the bed parts' vertices inside it, their edges' crossings of its sides and the
// levels at its corners.
[[nodiscard]] double highest_bed_level(const geometry::TriangleMesh* mesh, double x0, double x1, double y0,
                                       double y1);
// The log's line on the channel's mesh: its triangles, parts (side walls, bed relief) and extent.
[[nodiscard]] std::string describe_channel_mesh(const geometry::TriangleMesh& mesh);
// Places the inflow in the channel's mesh (none: the box alone): its grains are placed from the bed relief's
// highest level under the zone up (where the relief lies lower they drop onto it: InflowSettings::base) and
// clear of the mesh's triangles that reach the zone (side walls inside the channel's width); refuses
// (naming inflow.velocity_m_s) an inflow whose deepest batch would stand above the side walls over the
// relief's highest level from `from_x` (a debris run's fluid enters at the channel's first plane: 0; a
// channel run's grains: the zone's start) to the zone's end.
void place_inflow_in_mesh(const Config& cfg, const std::shared_ptr<const geometry::TriangleMesh>& mesh,
                          InflowSettings& inflow, double from_x);
// Refuses (naming channel.mesh_file) a mobile grain of `p` that overlaps a part of the channel's mesh.
void refuse_overlap(const Config& cfg, const geometry::TriangleMesh& mesh, const dem::Particles& p);
// A warning (empty: none) for side walls from a mesh under an open top whose top is not at the channel's
// `height` (within 2 %): the domain's sides open only above `height` (the fluid leaves there; grains leave
// wherever they pass the domain's sides).
[[nodiscard]] std::string open_top_mesh_warning(const ChannelBounds& bounds,
                                                const geometry::TriangleMesh* mesh, double height);

// No released block (release.solid_volume_m3 = 0 with an inflow): the release keys that still matter (the
// density, the mean radius S/r refers to), no grains.
[[nodiscard]] ReleaseInfo no_release(const Config& cfg);

// The released block of [release] (reference case C2's lattice rule, or a bidisperse mixture) added to
// `particles` as mobile grains. `place_grains` false: only counted (`sabo check`: the same counts, extents
// and volume). `channel_mesh`: its bed parts' highest level under the block's footprint (its length and
// width as asked, up-slope of its front) is the level the block stands on.
[[nodiscard]] ReleaseInfo build_release(const Config& cfg, const ChannelShape& shape,
                                        dem::Particles& particles, bool place_grains = true,
                                        const geometry::TriangleMesh* channel_mesh = nullptr);

}  // namespace sabo::scenario
