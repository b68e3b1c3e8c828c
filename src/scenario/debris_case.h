// SPDX-License-Identifier: MIT
// Debris against a barrier in the inclined channel (reference case C5): a block of fluid (water + fines,
// Newtonian or Bingham) with grains in it, released at the upstream end of the C2 channel against the C2
// barrier. V_s/V_box = 0: the fluid alone; 0.35: the grains are C2's block (its 4.03 m³ is 0.366 of the
// box: the actual ratio is reported); in between, grain centres drawn at random (seeded) with centre
// distances above r_i + r_j. `dry`: the same grains without the fluid.
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
#include "scenario/channel_case.h"
#include "scenario/grain_inflow.h"

namespace sabo::scenario {

// Where fluid leaves an open debris domain (the lattice's outlets, in this order).
enum class DebrisOutlet : std::uint8_t { end, sides, top };
inline constexpr std::array<std::string_view, 3> debris_outlet_names{"end", "sides", "top"};

struct DebrisCase {
    std::string name;
    double end_time = 0.0;
    ChannelShape channel;    // its height: the side walls'
    ChannelBounds bounds;    // its top (open by default), the domain's top above the bed, its end
    double outflow_x = 0.0;  // open: the fluid that reaches X ≥ outflow_x leaves the domain, m
    Vec3 gravity{};
    Vec3 block_lo{}, block_hi{};  // the released fluid block, m (channel frame)
    double grain_radius = 0.05;   // r of S/r, m
    double solid_fraction = 0.0;  // V_s/V_box as asked
    std::string placement;        // "none", "C2 block" or "random"
    ReleaseInfo grains;           // count, V_s, radii, density, extents (count 0: the fluid alone)
    // the inflow's hydrograph carries grains (solid_fraction > 0) into the fluid: the run is coupled from an
    // empty channel, `grains` holding the fed grains' radii and density (count 0)
    bool fed_grains = false;
    bool dry = false;  // the grains alone, no fluid
    BarrierInfo barrier;
    // channel.mesh_file: the side walls' mesh (walls for the grains; on the lattice, the walls' cells)
    std::shared_ptr<const geometry::TriangleMesh> channel_mesh;
    std::vector<dem::Wall> walls;  // channel planes + barrier boxes (model = boxes)
    dem::Particles particles;      // the grains (mobile), then the barrier's fixed spheres (model = spheres)
    double velocity_scale =
        0.0;  // m/s: frictionless slide of the block front to the channel's end + its height
    std::optional<InflowSettings> inflow;  // [inflow]: the fluid (and its grains) fed from a hydrograph
};

// `place_grains` false: the grains counted but not placed (`sabo check`; random grains: the expected count).
[[nodiscard]] DebrisCase build_debris_case(const Config& cfg, bool place_grains = true);

// V_box of the fluid block, m³.
[[nodiscard]] inline double block_volume(const DebrisCase& c) {
    const Vec3 d = c.block_hi - c.block_lo;
    return d.x * d.y * d.z;
}

// True when x lies inside barrier element e (its sphere or box).
[[nodiscard]] bool inside_element(const DebrisCase& c, std::size_t e, const Vec3& x);

}  // namespace sabo::scenario
