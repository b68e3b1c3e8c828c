// SPDX-License-Identifier: MIT
#include "analysis/arching.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sabo::analysis {

double OutletArching::arch_height_ratio(double barrier_height) const {
    for (auto it = intervals.rbegin(); it != intervals.rend(); ++it) {
        if (it->halted()) return it->z_hi / barrier_height;
    }
    return 0.0;
}

double OutletArching::arch_stop_time() const {
    double t = -1.0;
    for (const auto& iv : intervals) {
        if (iv.halted()) t = std::max(t, iv.below_since);
    }
    return t;
}

int OutletArching::halted_count() const {
    return static_cast<int>(
        std::count_if(intervals.begin(), intervals.end(), [](const auto& iv) { return iv.halted(); }));
}

ArchingMonitor::ArchingMonitor(const scenario::BarrierInfo& barrier, double depth, int intervals,
                               double threshold_J)
    : barrier_(&barrier), depth_(depth), dz_(barrier.height / intervals), threshold_(threshold_J) {
    for (const auto& s : barrier.outlets) {
        OutletArching o;
        o.outlet = s;
        for (int k = 0; k < intervals; ++k) o.intervals.push_back({k * dz_, (k + 1) * dz_});
        outlets_.push_back(std::move(o));
    }
}

void ArchingMonitor::sample(double time, const dem::Particles& p) {
    for (auto& o : outlets_) {
        for (auto& iv : o.intervals) iv.kinetic_energy = 0.0, iv.grains = 0;
    }
    const auto n_int = outlets_.empty() ? 0 : static_cast<long>(outlets_.front().intervals.size());
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const Vec3& x = p.x[i];
        const double d = barrier_->upstream_distance(x);
        if (d < 0.0 || d > depth_) continue;
        const long k = static_cast<long>(std::floor(x.z / dz_));
        if (k < 0 || k >= n_int) continue;
        for (auto& o : outlets_) {
            if (x.y < o.outlet.lo || x.y >= o.outlet.hi) continue;
            const double ek = p.kinetic_energy(i);
            auto& iv = o.intervals[static_cast<std::size_t>(k)];
            iv.kinetic_energy += ek;
            ++iv.grains;
        }
    }
    for (auto& o : outlets_) {
        for (auto& iv : o.intervals) {
            if (iv.kinetic_energy >= threshold_) {
                iv.below_since = -1.0;
            } else if (iv.below_since < 0.0) {
                iv.below_since = time;
            }
        }
    }
}

// Rules (docs/analysis.md): halted intervals counted against the number of intervals N;
// "within ~1 s of t0" is the window `quick` (1.5 s).
std::string classify_clogging(const OutletArching& outlet, double t0, double non_retained_fraction) {
    constexpr double quick =
        1.5;  // s: "~1 s" of the clogging definition; the C2 deposit needs ~1.3 s to reach H_bar
    const auto n = static_cast<int>(outlet.intervals.size());
    int halted = 0, early = 0;
    for (const auto& iv : outlet.intervals) {
        if (!iv.halted()) continue;
        ++halted;
        if (iv.below_since - t0 <= quick) ++early;
    }
    if (halted == 0) return no_clogging;
    if (2 * early > n && non_retained_fraction <= 0.10) return instant_high_arch;
    if (10 * halted <= 3 * n && early == 0) return late_low_arch;
    return progressive;
}

std::string classify_run(const std::vector<std::string>& outlet_labels) {
    // ordered from the least to the most clogged: ties go to the earlier
    const std::array<const char*, 4> order = {no_clogging, late_low_arch, progressive, instant_high_arch};
    if (outlet_labels.empty()) return no_clogging;
    std::string best;
    long best_count = -1;
    for (const char* label : order) {
        const long c = std::count(outlet_labels.begin(), outlet_labels.end(), label);
        if (c > best_count) best = label, best_count = c;
    }
    return best;
}

}  // namespace sabo::analysis
