// SPDX-License-Identifier: MIT
#include "scenario/channel_bounds.h"

#include <string>

#include "scenario/channel_case.h"

namespace sabo::scenario {

ChannelBounds read_channel_bounds(const Config& cfg, const ChannelShape& shape, ChannelTop default_top) {
    ChannelBounds b;
    b.top = cfg.enum_or("channel.top", default_top, channel_top_names);
    if (b.top == ChannelTop::open) {
        // air above the walls: three times their height; the run-up's thin sheets climb higher (8 m at the
        // reference case's slit) but carry little load (a 4 m and an 8 m domain gave the same peak,
        // docs/results/open_channel_fluid.md): what rises above the top leaves there and is reported
        b.domain_height = cfg.real_or("channel.domain_height_m", 3.0 * shape.height,
                                      Range::open_closed(shape.height, 1e4 * shape.height));
    } else {
        if (cfg.has("channel.domain_height_m"))
            cfg.fail("channel.domain_height_m",
                     "a domain above the walls needs channel.top = \"open\" (a lid closes the domain at the "
                     "walls' height, channel.height_m)");
        b.domain_height = shape.height;
    }
    b.end = cfg.enum_or("channel.end", ChannelEnd::wall, channel_end_names);
    return b;
}

std::vector<dem::Wall> channel_walls(const ChannelShape& shape, const ChannelBounds& bounds) {
    ChannelShape box = shape;  // the grains' ceiling is the domain's top
    box.height = bounds.domain_height;
    std::vector<dem::Wall> walls = channel_walls(box);
    if (bounds.top == ChannelTop::open) {
        // the side walls of their own height: slabs outside the channel up to the walls' height (a grain can
        // rest on one, or go over it and leave the channel: the run removes it and counts it as spilled)
        const double t = side_wall_thickness;
        for (dem::Wall& w : walls) {
            const bool low = w.name == "side_y0", high = w.name == "side_y1";
            if (!low && !high) continue;
            w = dem::Wall::box(
                w.name, {0.5 * shape.length, low ? -0.5 * t : shape.width + 0.5 * t, 0.5 * shape.height},
                {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}},
                {0.5 * shape.length, 0.5 * t, 0.5 * shape.height});
        }
    }
    if (bounds.end == ChannelEnd::open)
        std::erase_if(walls, [](const dem::Wall& w) { return w.name == "downstream_end"; });
    return walls;
}

}  // namespace sabo::scenario
