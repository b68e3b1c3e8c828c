// SPDX-License-Identifier: MIT
#include "cases/common/gauge_settings.h"

#include <algorithm>
#include <vector>

#include "scenario/channel_case.h"

namespace sabo::cases {

GaugeSettings read_gauge_settings(const Config& cfg, double face_x, double channel_width, double grain_size,
                                  const geometry::TriangleMesh* channel_mesh) {
    GaugeSettings g;
    const double length = cfg.real_or("analysis.gauge_length_m", 0.5, Range::positive());
    // the section stays upstream of the face and inside the channel
    g.distance = cfg.real_or("analysis.gauge_distance_m", std::min(1.5, face_x - 0.5 * length),
                             Range::closed(0.5 * length, face_x - 0.5 * length));
    g.arrival_depth = cfg.real_or("analysis.gauge_arrival_depth_m", 0.5 * grain_size, Range::positive());
    // depth-map cells no smaller than a grain, so that each holds the bulk around the grains it counts
    g.section = {face_x - g.distance, length, channel_width, std::max(0.1, grain_size), {}};
    bool raised = false;
    std::vector<double> bed;
    for (std::size_t b = 0; b < g.section.bins(); ++b)
        for (std::size_t s = 0; s < g.section.strips(); ++s) {
            bed.push_back(scenario::bed_level(channel_mesh, g.section.cell_x(b), g.section.cell_y(s)));
            raised = raised || bed.back() > 0.0;
        }
    if (raised) g.section.bed = std::move(bed);
    return g;
}

}  // namespace sabo::cases
