// SPDX-License-Identifier: MIT
// What leaves a channel run's grains, or passes its barrier, as a part of a case's observer: the grains
// that go over a side wall of an open top (neither retained nor passed) or past an open end (passed), taken
// out of the run and counted, and the mass that crossed the barrier above its crest (overtopping) and below
// it (through the outlets), from the crest flux integrated at every grain step. Each rank of a divided run
// counts its own grains between series rows; the sums over the ranks are taken at the rows (no wait in the
// step), and every rank keeps its share in its checkpoint.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "analysis/crest_flux.h"
#include "io/json_writer.h"
#include "scenario/barrier.h"
#include "scenario/channel_bounds.h"
#include "sim/simulation.h"

namespace sabo::cases {

// summary.json's keys of the channel's bounds (docs/outputs.md).
inline void summarise_bounds(io::JsonObject& js, const scenario::ChannelBounds& bounds) {
    js.text("channel_top", scenario::name(bounds.top))
        .text("channel_end", scenario::name(bounds.end))
        .number("domain_height_m", bounds.domain_height);
}

class GrainOutflow {
  public:
    // The channel's `length` and `width`, m.
    GrainOutflow(const scenario::ChannelBounds& bounds, double length, double width,
                 const scenario::BarrierInfo& barrier)
        : bounds_(bounds), length_(length), width_(width), barrier_(barrier) {}

    // After every grain step: the crest flux's share of the step. Only the grains near the barrier are looked
    // at, found again at every list build (until the next one no grain moves more than the lists' skin).
    void after_grain_step(const sim::Simulation& sim) {
        if (!barrier_.present()) return;
        const dem::DemSolver& solver = sim.grains();
        if (solver.list_builds() != builds_) {
            analysis::crest_flux_candidates(solver.particles(), solver.own_count(), barrier_,
                                            solver.skin_max(), near_);
            builds_ = solver.list_builds();
        }
        const analysis::CrestFlux f = analysis::crest_flux(solver.particles(), near_, barrier_);
        pending_[over] += f.over * solver.dt();
        pending_[through] += f.through * solver.dt();
    }

    // After every step (a coupled step's grain sub-steps done): the grains that left, out of the run.
    void remove_exits(sim::Simulation& sim) {
        if (bounds_.top != scenario::ChannelTop::open && bounds_.end != scenario::ChannelEnd::open) return;
        const dem::DemSolver& solver = sim.grains();
        const dem::Particles& p = solver.particles();
        const std::size_t n = solver.own_count();
        bool any = false;
        for (std::size_t i = 0; i < n; ++i) {
            if (bounds_.spilled_over_side(p.x[i], width_)) {
                pending_[spilled_mass] += p.m[i];
                pending_[spilled_count] += 1.0;
                any = true;
            } else if (bounds_.left_at_end(p.x[i], length_)) {
                pending_[end_mass] += p.m[i];
                pending_[end_count] += 1.0;
                any = true;
            }
        }
        if (any)
            sim.remove_grains([this](const Vec3& x) {
                return bounds_.spilled_over_side(x, width_) || bounds_.left_at_end(x, length_);
            });
    }

    // At a series row (every rank): the ranks' counts since the last row added to the totals.
    void sample(const parallel::Domain& domain) {
        for (std::size_t k = 0; k < totals_.size(); ++k) {
            totals_[k] += domain.sum(pending_[k]);
            pending_[k] = 0.0;
        }
    }

    // Totals as of the last row: kg and grains.
    [[nodiscard]] double spilled_mass_kg() const { return totals_[spilled_mass]; }
    [[nodiscard]] double spilled_grains() const { return totals_[spilled_count]; }
    [[nodiscard]] double left_end_mass_kg() const { return totals_[end_mass]; }
    [[nodiscard]] double left_end_grains() const { return totals_[end_count]; }
    [[nodiscard]] double over_crest_kg() const { return totals_[over]; }
    [[nodiscard]] double through_outlets_kg() const { return totals_[through]; }

    // The share of the grains' mass `solid_mass` (kg) held upstream of the barrier, given the non-retained
    // fraction: neither passed nor gone over a side wall (0 without grains).
    [[nodiscard]] double retained(double non_retained, double solid_mass) const {
        return solid_mass > 0.0 ? 1.0 - non_retained - spilled_mass_kg() / solid_mass : 0.0;
    }

    // summary.json's keys (docs/outputs.md): the tallies as shares of the grains' mass `solid_mass` (kg),
    // and counts.
    void summarise(io::JsonObject& js, double solid_mass) const {
        js.number("solid_spilled_fraction", spilled_mass_kg() / solid_mass)
            .integer("grains_spilled", static_cast<std::int64_t>(spilled_grains()))
            .number("solid_left_end_fraction", left_end_mass_kg() / solid_mass)
            .integer("grains_left_end", static_cast<std::int64_t>(left_end_grains()))
            .number("solid_over_crest_fraction", over_crest_kg() / solid_mass)
            .number("solid_through_outlets_fraction", through_outlets_kg() / solid_mass);
    }

    template <class Archive>
    void transfer(Archive& a) {
        a(totals_, pending_);
    }

  private:
    enum Tally : std::size_t { spilled_mass, spilled_count, end_mass, end_count, over, through, tallies };
    scenario::ChannelBounds bounds_;
    double length_, width_;
    const scenario::BarrierInfo& barrier_;
    std::array<double, tallies> totals_{}, pending_{};
    std::vector<std::uint32_t> near_;  // the grains near the barrier since the last list build
    // the list build they were found at (none yet; not in a checkpoint: a resumed run finds them again)
    std::size_t builds_ = std::numeric_limits<std::size_t>::max();
};

}  // namespace sabo::cases
