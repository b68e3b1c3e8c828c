// SPDX-License-Identifier: MIT
// Debris against a barrier in the inclined channel (CASES C5): a block of fluid (water + fines,
// Newtonian or Bingham) released at the upstream end of the C2 channel, against the C2 barrier. This
// version runs the fluid alone (V_s/V_box = 0); grains in the block (the coupling of SPEC §2.4) are
// the next step and refused until then.
#pragma once
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "scenario/barrier.h"

namespace sabo::scenario {

struct DebrisCase {
    std::string name;
    double end_time = 0.0;
    ChannelShape channel;
    Vec3 gravity{};
    Vec3 block_lo{}, block_hi{};  // the released fluid block, m (channel frame)
    double grain_radius = 0.05;   // r of S/r, m
    BarrierInfo barrier;
    std::vector<dem::Wall> walls;    // channel planes + barrier boxes (model = boxes)
    dem::Particles barrier_spheres;  // fixed spheres (model = spheres)
    double velocity_scale =
        0.0;  // m/s: frictionless slide of the block front to the channel's end + its height
};

[[nodiscard]] DebrisCase build_debris_case(const Config& cfg);

// True when x lies inside barrier element e (its sphere or box).
[[nodiscard]] bool inside_element(const DebrisCase& c, std::size_t e, const Vec3& x);

}  // namespace sabo::scenario
