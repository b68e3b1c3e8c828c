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
      sphere_count_(barrier.sphere_count),
      normal_(barrier.face_normal),
      current_(barrier.elements.size()),
      envelope_(barrier.elements.size(), 0.0),
      piles_(barrier.piles.size()),
      fluid_envelope_(barrier.elements.size(), 0.0) {}

void BarrierForceMonitor::record(double time, std::span<const Vec3> particle_forces,
                                 std::span<const Vec3> wall_forces, std::span<const Vec3> fluid) {
    global_ = fluid_global_ = {};
    double local_max = 0.0;
    for (auto& p : piles_) p.normal = p.moment = 0.0;
    const bool grains = !particle_forces.empty() || !wall_forces.empty();
    const std::size_t sphere_offset = grains ? particle_forces.size() - sphere_count_ : 0;
    for (std::size_t e = 0; e < elements_.size(); ++e) {
        const auto& el = elements_[e];
        Vec3 f{};
        if (grains)  // (the fixed spheres follow the mobile grains, whose number changes as grains leave)
            f = el.sphere ? particle_forces[sphere_offset + el.index] : wall_forces[el.index];
        if (!fluid.empty()) {
            fluid_global_ += fluid[e];
            fluid_envelope_[e] = std::max(fluid_envelope_[e], norm(fluid[e]));
            f += fluid[e];
        }
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
    if (fluid_normal() > max_fluid_normal_) {
        max_fluid_normal_ = fluid_normal();
        time_of_max_fluid_normal_ = time;
    }
    if (solid_normal() > max_solid_normal_) {
        max_solid_normal_ = solid_normal();
        time_of_max_solid_normal_ = time;
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
