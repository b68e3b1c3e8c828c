// SPDX-License-Identifier: MIT
// Arching at the outlets (docs/analysis.md). Per outlet, a box upstream of the face, `depth` (4 r) deep in X
// and as wide as the outlet, is split into equal height intervals over the barrier height H_bar.
// An interval halts at t_stop when the summed kinetic energy E_K = Σ (½ m v² + ½ J ω²) of the grains
// whose centres lie in it drops below the threshold (1e−5 J) and stays there to the end of the run.
// H_arch is the top of the highest halted, occupied interval. The clogging mechanism is labelled
// from the halt times (docs/analysis.md gives the rules).
#pragma once
#include <string>
#include <vector>

#include "dem/particles.h"
#include "scenario/barrier.h"

namespace sabo::analysis {

struct ArchingInterval {
    double z_lo = 0.0, z_hi = 0.0;  // m above the bed
    double kinetic_energy = 0.0;    // J, at the last sample
    std::size_t grains = 0;         // at the last sample
    double below_since = -1.0;      // s, time E_K last dropped below the threshold (−1: it is above)
    [[nodiscard]] bool halted() const { return grains > 0 && below_since >= 0.0; }
};

struct OutletArching {
    scenario::Span outlet;
    std::vector<ArchingInterval> intervals;  // bottom to top
    // H_arch / H_bar: top of the highest halted, occupied interval (0 if none)
    [[nodiscard]] double arch_height_ratio(double barrier_height) const;
    // t_stop of the arch: latest halt time among the halted intervals up to H_arch (−1 if none)
    [[nodiscard]] double arch_stop_time() const;
    [[nodiscard]] int halted_count() const;
    template <class Archive>
    void transfer(Archive& a) {
        a(outlet, intervals);
    }
};

class ArchingMonitor {
  public:
    ArchingMonitor(const scenario::BarrierInfo& barrier, double depth, int intervals = 10,
                   double threshold_J = 1e-5);
    // One sample of the synchronous state (positions and velocities) at `time`.
    void sample(double time, const dem::Particles& p);
    [[nodiscard]] const std::vector<OutletArching>& outlets() const { return outlets_; }
    [[nodiscard]] double threshold() const { return threshold_; }
    // The intervals' state so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(outlets_);
    }

  private:
    const scenario::BarrierInfo* barrier_;
    double depth_, dz_, threshold_;
    std::vector<OutletArching> outlets_;
};

// The clogging mechanisms of docs/analysis.md.
inline constexpr const char* no_clogging = "no clogging";
inline constexpr const char* instant_high_arch = "instant high arch";
inline constexpr const char* progressive = "progressive";
inline constexpr const char* late_low_arch = "late low arch";

// Label of one outlet from its intervals, the first arrival t0 and the run's non-retained fraction.
[[nodiscard]] std::string classify_clogging(const OutletArching& outlet, double t0,
                                            double non_retained_fraction);
// Label of a run with several outlets: the most frequent label; a tie goes to the less clogged one.
[[nodiscard]] std::string classify_run(const std::vector<std::string>& outlet_labels);

}  // namespace sabo::analysis
