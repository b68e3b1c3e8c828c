// SPDX-License-Identifier: MIT
#include "scenario/debris_case.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace sabo::scenario {

DebrisCase build_debris_case(const Config& cfg) {
    DebrisCase c;
    c.name = cfg.text_or("case.name", "debris");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    c.channel = read_channel_shape(cfg, c.gravity);
    const auto& ch = c.channel;
    const double fraction = cfg.real_or("debris.solid_fraction", 0.0, Range::closed(0.0, 0.35));
    if (fraction > 0.0)
        cfg.fail("debris.solid_fraction",
                 "grains in the fluid (the particle-fluid coupling of SPEC 2.4) are not available yet: only "
                 "0 (the "
                 "fluid alone) runs in this version");
    c.block_lo = {0.0, 0.0, 0.0};
    c.block_hi = {cfg.real_or("debris.block_length_m", 4.75, Range::positive()),
                  cfg.real_or("debris.block_width_m", ch.width, Range::open_closed(0.0, ch.width)),
                  cfg.real_or("debris.block_height_m", 1.10, Range::open_closed(0.0, ch.height))};
    const double y0 = 0.5 * (ch.width - c.block_hi.y);
    c.block_lo.y = y0;
    c.block_hi.y += y0;
    c.grain_radius = cfg.real_or("debris.grain_radius_m", 0.05, Range::positive());
    c.barrier = build_barrier(cfg, ch, c.grain_radius, c.walls, c.barrier_spheres);
    if (c.barrier.present() && c.block_hi.x > c.barrier.face_x - 0.01)
        cfg.fail("debris.block_length_m",
                 fmt::format("the block reaches the barrier face (X = {:.3f} m)", c.barrier.face_x));
    // the fluid that passes the barrier keeps accelerating down to the channel's end (the jets behind a
    // slit reached 15-25 m/s in C5): the drop to the end, not to the barrier, bounds the speed
    const double drop =
        (ch.length - c.block_hi.x) * std::sin(ch.slope_deg * std::numbers::pi / 180.0) + c.block_hi.z;
    c.velocity_scale =
        cfg.real_or("debris.velocity_scale_m_s", std::sqrt(2.0 * ch.gravity * drop), Range::positive());
    return c;
}

bool inside_element(const DebrisCase& c, std::size_t e, const Vec3& x) {
    const BarrierElement& el = c.barrier.elements[e];
    if (el.sphere) {
        const double r = c.barrier_spheres.r[el.index];
        return norm2(x - c.barrier_spheres.x[el.index]) <= r * r;
    }
    const dem::Wall& w = c.walls[el.index];
    const Vec3 d = x - w.point;
    return std::abs(dot(d, w.axes[0])) <= w.half.x && std::abs(dot(d, w.axes[1])) <= w.half.y &&
           std::abs(dot(d, w.axes[2])) <= w.half.z;
}

}  // namespace sabo::scenario
