// SPDX-License-Identifier: MIT
// Where a channel is closed and where it is open: its top (a lid at the side walls' height, or air above
// them up to the domain's top) and its downstream end (a wall, or open: what reaches it leaves). Shared by
// the grains-only channel and the debris case. Frame: X down-slope, Y across, Z normal to the bed.
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/config.h"
#include "core/vec3.h"
#include "dem/walls.h"
#include "scenario/barrier.h"

namespace sabo::scenario {

// channel.top: "open" — air above the side walls up to the domain's top; a grain that goes over a side wall
// has left the channel (removed, counted); "lid" — the closed box of the walls' height.
enum class ChannelTop : std::uint8_t { open, lid };
inline constexpr std::array<std::string_view, 2> channel_top_names{"open", "lid"};
[[nodiscard]] inline std::string_view name(ChannelTop t) {
    return channel_top_names[static_cast<std::size_t>(t)];
}

// channel.end: "wall" — the downstream end is a wall; "open" — a grain whose centre passes it has left the
// channel (removed, counted as passed the barrier).
enum class ChannelEnd : std::uint8_t { wall, open };
inline constexpr std::array<std::string_view, 2> channel_end_names{"wall", "open"};
[[nodiscard]] inline std::string_view name(ChannelEnd e) {
    return channel_end_names[static_cast<std::size_t>(e)];
}

// An open channel's side walls for the grains: slabs this thick (m) outside the channel, as high as the
// walls (a closed box's are planes as high as the domain).
inline constexpr double side_wall_thickness = 0.1;

struct ChannelBounds {
    ChannelTop top = ChannelTop::lid;
    ChannelEnd end = ChannelEnd::wall;
    double domain_height = 0.0;  // the domain's top above the bed, m (lid: the walls' height)
    // Whether a grain centred at x has gone over a side wall (an open top) or past the open end: it has
    // left the channel.
    [[nodiscard]] bool spilled_over_side(const Vec3& x, double width) const {
        return top == ChannelTop::open && (x.y < 0.0 || x.y > width);
    }
    [[nodiscard]] bool left_at_end(const Vec3& x, double length) const {
        return end == ChannelEnd::open && x.x > length;
    }
};

// Reads channel.top (default `default_top`), channel.domain_height_m (open top only: default three wall
// heights) and channel.end.
[[nodiscard]] ChannelBounds read_channel_bounds(const Config& cfg, const ChannelShape& shape,
                                                ChannelTop default_top);

// The channel's walls for the grains: bed, ceiling at the domain's top, the two sides (planes under a lid,
// slabs of the walls' height under an open top), the upstream end and, unless open, the downstream end.
[[nodiscard]] std::vector<dem::Wall> channel_walls(const ChannelShape& shape, const ChannelBounds& bounds);

}  // namespace sabo::scenario
