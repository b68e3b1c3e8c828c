// SPDX-License-Identifier: MIT
// The gauge section's keys, shared by the case types whose flow approaches a barrier (channel, debris).
#pragma once
#include "analysis/flow_gauge.h"
#include "core/config.h"
#include "geometry/triangle_mesh.h"

namespace sabo::cases {

// The gauge section upstream of the barrier that measures the approaching flow (docs/design.md, "The
// approaching flow"): analysis.gauge_distance_m, analysis.gauge_length_m, analysis.gauge_arrival_depth_m.
struct GaugeSettings {
    analysis::GaugeSection section;
    double distance = 0.0;       // m, from the section's centre up-slope to the barrier's upstream face
    double arrival_depth = 0.0;  // m: the front has reached the gauge when its depth first reaches this
};
// Reads them for a barrier face at X = face_x across a channel of the given width, with `grain_size` the mean
// grain diameter (the fluid alone: two lattice spacings): the depth map's cells are no smaller and the
// arrival depth defaults to half of it. Refuses a section that reaches the barrier or leaves the channel.
// `channel_mesh`: its bed parts raise the bed the depth is measured from (scenario::bed_level).
[[nodiscard]] GaugeSettings read_gauge_settings(const Config& cfg, double face_x, double channel_width,
                                                double grain_size,
                                                const geometry::TriangleMesh* channel_mesh = nullptr);

}  // namespace sabo::cases
