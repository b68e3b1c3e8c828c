// SPDX-License-Identifier: MIT
// case.type = "sandpile" (reference case C1): settling with the outlets closed, opening, draining to a
// complete stop, and the angle of repose of the heap left on the plate.
#pragma once
#include <optional>

#include "cases/sandpile/sandpile_observer.h"
#include "cases/sandpile/sandpile_settings.h"
#include "sim/case_type.h"
#include "sim/frame_observers.h"

namespace sabo::cases {

class SandpileType final : public sim::CaseType {
  public:
    void prepare(const sim::RunRequest& req, const Config& cfg) override { pc_ = prepare_sandpile(req, cfg); }
    void print_derived() const override { cases::print_derived(pc_); }
    [[nodiscard]] const sim::OutputSettings& output() const override { return pc_.output; }
    [[nodiscard]] double end_time() const override { return pc_.scene.end_time; }
    [[nodiscard]] sim::ProgressLine progress() const override { return {pc_.scene.count, false}; }
    [[nodiscard]] parallel::Domain domain(const MpiWorld* world) const override;
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
    [[nodiscard]] std::string report_script() const override { return "sandpile_report.py"; }

  private:
    PreparedSandpile pc_;
    std::optional<analysis::PlateGeometry> plate_;
    std::optional<sim::ParticleFrames> frames_;
    std::optional<SandpileObserver> sandpile_;
    std::optional<dem::GrainView> grains_;  // every grain at the end
    std::size_t removed_ = 0;               // grains removed below the plate
};

}  // namespace sabo::cases
