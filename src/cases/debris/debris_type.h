// SPDX-License-Identifier: MIT
// case.type = "debris" (reference case C5): the block of fluid with grains in it released against the barrier
// — the fluid alone (V_s/V_box = 0), grains and fluid coupled, or the same grains dry (debris.dry). The
// barrier's solid, fluid and total force (history, per element) and the solid and fluid non-retained
// fractions.
#pragma once
#include <optional>
#include <vector>

#include "cases/common/gauge_observer.h"
#include "cases/debris/debris_inflow.h"
#include "cases/debris/debris_observer.h"
#include "cases/debris/debris_settings.h"
#include "sim/case_type.h"
#include "sim/frame_observers.h"

namespace sabo::cases {

// The domain of the case's mode: the channel's lattice (divided among the ranks of `world` by its planes),
// or for the dry twin the grains' box (divided as grains alone).
[[nodiscard]] parallel::Domain debris_domain(const PreparedDebris& pc, const MpiWorld* world);
// The simulation of the case's mode on `domain`: the fluid alone, grains and fluid coupled, or the grains
// dry; `barrier_cells` gets the lattice cells of each barrier element (over all ranks).
[[nodiscard]] sim::Simulation debris_simulation(const PreparedDebris& pc, const parallel::Domain& domain,
                                                std::vector<std::size_t>& barrier_cells,
                                                double* inlet_seed = nullptr);

class DebrisType final : public sim::CaseType {
  public:
    void prepare(const sim::RunRequest& req, const Config& cfg) override { pc_ = prepare_debris(req, cfg); }
    void print_derived() const override { cases::print_derived(pc_); }
    [[nodiscard]] const sim::OutputSettings& output() const override { return pc_.output; }
    [[nodiscard]] double end_time() const override { return pc_.scene.end_time; }
    [[nodiscard]] sim::ProgressLine progress() const override { return {0, true}; }
    [[nodiscard]] parallel::Domain domain(const MpiWorld* world) const override {
        return debris_domain(pc_, world);
    }
    [[nodiscard]] std::optional<sim::Simulation> build(const parallel::Domain& domain,
                                                       sim::RunControl& control, bool resume) override;
    [[nodiscard]] std::vector<sim::Observer*> observers(const sim::Simulation& sim) override;
    void finish(sim::Simulation& sim, const sim::RunEnd& end) override;
    void write_end_files(const sim::Simulation& sim, const sim::RunEnd& end) override;
    [[nodiscard]] sim::SummaryHead summary_head(const sim::Simulation& sim) const override;
    [[nodiscard]] int summarise(io::JsonObject& js, const sim::Simulation& sim,
                                const sim::RunEnd& end) override;
    void summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const override;
    void log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                 const sim::RunTotals& totals) const override;
    [[nodiscard]] std::string report_script() const override { return "debris_report.py"; }
    [[nodiscard]] const lbm::UnitConverter& fluid_units() const { return pc_.fluid.units; }

  private:
    PreparedDebris pc_;
    std::vector<std::size_t> barrier_cells_;  // lattice cells of each barrier element
    std::size_t blocked_cells_ = 0;           // their sum
    double fluid_volume_ = 0.0;               // m3, the block's less the grains'
    double weight_along_ = 0.0;               // W_tot sin θ, N
    std::optional<DebrisObserver> debris_;
    std::optional<FluidInflowObserver> inflow_;
    std::optional<InflowObserver> grain_inflow_;  // the grains the hydrograph carries (coupled)
    double inlet_seed_ = 0.0;                     // the inflow's seed on this rank, lattice mass
    std::optional<GaugeObserver> gauge_;
    std::optional<sim::FluidFrames> fluid_frames_;
    std::optional<sim::ParticleFrames> grain_frames_;
    std::optional<dem::GrainView> grains_;  // every grain at the end (with grains)
};

}  // namespace sabo::cases
