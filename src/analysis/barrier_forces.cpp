// SPDX-License-Identifier: MIT
#include "analysis/barrier_forces.h"

#include <algorithm>

namespace sabo::analysis {

namespace {
// copy-assignment reuses the map's storage: no allocation in the time loop after the first snapshot
void take(ForceMap& map, double time, const std::vector<Vec3>& forces) {
    map.time = time;
    map.force = forces;
}
}  // namespace

BarrierForceMonitor::BarrierForceMonitor(const scenario::BarrierInfo& barrier)
    : elements_(barrier.elements),
      normal_(barrier.face_normal),
      current_(barrier.elements.size()),
      envelope_(barrier.elements.size(), 0.0),
      piles_(barrier.piles.size()) {}

void BarrierForceMonitor::record(double time, std::span<const Vec3> particle_forces,
                                 std::span<const Vec3> wall_forces) {
    global_ = {};
    double local_max = 0.0;
    for (auto& p : piles_) p.normal = p.moment = 0.0;
    for (std::size_t e = 0; e < elements_.size(); ++e) {
        const auto& el = elements_[e];
        const Vec3 f = el.sphere ? particle_forces[el.index] : wall_forces[el.index];
        current_[e] = f;
        global_ += f;
        const double fe = norm(f);
        envelope_[e] = std::max(envelope_[e], fe);
        local_max = std::max(local_max, fe);
        const double fn = dot(f, normal_);
        PileLoad& pile = piles_[static_cast<std::size_t>(el.pile)];
        pile.normal += fn;
        pile.moment += fn * el.height;
    }
    for (auto& p : piles_) {
        if (p.normal > p.max_normal) p.max_normal = p.normal, p.time_of_max_normal = time;
        if (p.moment > p.max_moment) p.max_moment = p.moment, p.time_of_max_moment = time;
    }
    const double fg = resultant();
    interval_peak_ = std::max(interval_peak_, fg);
    if (std::isnan(map_t1_.time) && fg > 0.0) take(map_t1_, time, current_);
    if (local_max > max_local_) {
        max_local_ = local_max;
        take(map_t2_, time, current_);
    }
    if (fg > max_global_) {
        max_global_ = fg;
        take(map_t3_, time, current_);
    }
    const double fn = normal();
    new_normal_peak_ = fn > max_normal_;
    if (new_normal_peak_) {
        max_normal_ = fn;
        time_of_max_normal_ = time;
    }
}

void BarrierForceMonitor::finish(double time) {
    take(map_end_, time, current_);
}

double BarrierForceMonitor::take_interval_peak() {
    const double peak = interval_peak_;
    interval_peak_ = 0.0;
    return peak;
}

}  // namespace sabo::analysis
