// SPDX-License-Identifier: MIT
// Barrier forces of docs/analysis.md, followed every time step so that no peak is lost to output decimation:
// the global force F_G (sum over the barrier elements) and its components normal and tangential to
// the face; each element's local force F_L; the local force maps at first impact t1, at the time of
// the largest local force t2, at the time of the largest global force t3 and at the end; the
// envelope of each element's largest resultant; per pile the largest normal force and basal moment.
#pragma once
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "core/vec3.h"
#include "scenario/barrier.h"

namespace sabo::analysis {

// A snapshot of the element forces; time is NaN until taken.
struct ForceMap {
    double time = std::numeric_limits<double>::quiet_NaN();
    std::vector<Vec3> force;  // per element, N
    template <class Archive>
    void transfer(Archive& a) {
        a(time, force);
    }
};

struct PileLoad {
    double normal = 0.0;  // N, force along the face normal (positive = pushed downstream), this step
    double moment = 0.0;  // N·m, basal moment M_X = Σ F_n,e h_e (about the pile's base line on the bed)
    double max_normal = 0.0, time_of_max_normal = 0.0;
    double max_moment = 0.0, time_of_max_moment = 0.0;
};

class BarrierForceMonitor {
  public:
    explicit BarrierForceMonitor(const scenario::BarrierInfo& barrier);

    // One time step, every force in N. The grains' component: `particle_forces` and `wall_forces` are the
    // DEM solver's (fixed spheres' forces are the particle entries of the sphere elements; boxes the wall
    // entries), both empty without grains. The fluid's component: `fluid`, one entry per element (the
    // lattice's momentum exchange), empty without a fluid. Everything below is of their sum, except the
    // fluid_* accessors.
    void record(double time, std::span<const Vec3> particle_forces, std::span<const Vec3> wall_forces,
                std::span<const Vec3> fluid = {});
    // Takes the end map (the state the run stops in).
    void finish(double time);

    [[nodiscard]] std::size_t element_count() const { return elements_.size(); }
    [[nodiscard]] const Vec3& global() const { return global_; }  // this step, N
    [[nodiscard]] double normal() const { return dot(global_, normal_); }
    [[nodiscard]] double tangential() const { return norm(global_ - normal_ * normal()); }
    [[nodiscard]] double resultant() const { return norm(global_); }
    // Largest |F_G| since the last call (peak-preserving decimation of the time series).
    [[nodiscard]] double take_interval_peak();

    [[nodiscard]] double first_impact_time() const { return map_t1_.time; }  // t1 (NaN: never hit)
    [[nodiscard]] double max_global() const { return max_global_; }          // N, at t3
    [[nodiscard]] double max_local() const { return max_local_; }            // N, at t2
    [[nodiscard]] double max_normal() const { return max_normal_; }          // N, F_n,max
    [[nodiscard]] double time_of_max_normal() const { return time_of_max_normal_; }
    [[nodiscard]] const ForceMap& map_t1() const { return map_t1_; }
    [[nodiscard]] const ForceMap& map_t2() const { return map_t2_; }
    [[nodiscard]] const ForceMap& map_t3() const { return map_t3_; }
    [[nodiscard]] const ForceMap& map_end() const { return map_end_; }
    [[nodiscard]] const std::vector<double>& envelope() const { return envelope_; }  // N per element
    [[nodiscard]] const std::vector<PileLoad>& piles() const { return piles_; }
    [[nodiscard]] bool new_normal_peak() const { return new_normal_peak_; }  // set by the last record()
    // the fluid component alone: this step's global force, its largest normal component and when, and
    // each element's largest fluid force
    [[nodiscard]] const Vec3& fluid_global() const { return fluid_global_; }
    [[nodiscard]] double fluid_normal() const { return dot(fluid_global_, normal_); }
    [[nodiscard]] double max_fluid_normal() const { return max_fluid_normal_; }
    [[nodiscard]] double time_of_max_fluid_normal() const { return time_of_max_fluid_normal_; }
    [[nodiscard]] const std::vector<double>& fluid_envelope() const { return fluid_envelope_; }
    // the grains' component alone (the total less the fluid's): this step's normal force, its largest and
    // when
    [[nodiscard]] double solid_normal() const { return normal() - fluid_normal(); }
    [[nodiscard]] double max_solid_normal() const { return max_solid_normal_; }
    [[nodiscard]] double time_of_max_solid_normal() const { return time_of_max_solid_normal_; }

    // Everything recorded so far (io/checkpoint.h); the barrier itself is the set-up's.
    template <class Archive>
    void transfer(Archive& a) {
        a(current_, global_, interval_peak_, max_global_, max_local_, max_normal_, time_of_max_normal_,
          new_normal_peak_, map_t1_, map_t2_, map_t3_, map_end_, envelope_, piles_, fluid_global_,
          max_fluid_normal_, time_of_max_fluid_normal_, fluid_envelope_, max_solid_normal_,
          time_of_max_solid_normal_);
    }

  private:
    std::vector<scenario::BarrierElement> elements_;
    std::size_t sphere_count_;  // the fixed spheres, last in the particle arrays
    Vec3 normal_{};
    std::vector<Vec3> current_;
    Vec3 global_{};
    double interval_peak_ = 0.0;
    double max_global_ = 0.0, max_local_ = 0.0, max_normal_ = 0.0, time_of_max_normal_ = 0.0;
    bool new_normal_peak_ = false;
    ForceMap map_t1_, map_t2_, map_t3_, map_end_;
    std::vector<double> envelope_;
    std::vector<PileLoad> piles_;
    Vec3 fluid_global_{};
    double max_fluid_normal_ = 0.0, time_of_max_fluid_normal_ = 0.0;
    std::vector<double> fluid_envelope_;
    double max_solid_normal_ = 0.0, time_of_max_solid_normal_ = 0.0;
};

}  // namespace sabo::analysis
