// SPDX-License-Identifier: MIT
// case.type = "dam_break" (issue 5): the free-surface fluid alone, its front compared with Martin & Moyce
// (1952).
#pragma once
#include <optional>

#include "analysis/dam_break_front.h"
#include "cases/dam_break/dam_break_observer.h"
#include "cases/dam_break/dam_break_settings.h"
#include "sim/case_type.h"
#include "sim/frame_observers.h"

namespace sabo::cases {

class DamBreakType final : public sim::CaseType {
  public:
    void prepare(const sim::RunRequest& req, const Config& cfg) override {
        pc_ = prepare_dam_break(req, cfg);
    }
    void print_derived() const override { cases::print_derived(pc_); }
    [[nodiscard]] const sim::OutputSettings& output() const override { return pc_.output; }
    [[nodiscard]] double end_time() const override { return pc_.scene.end_time; }
    [[nodiscard]] sim::ProgressLine progress() const override { return {0, true}; }
    [[nodiscard]] parallel::Domain domain(const MpiWorld* world) const override;
    [[nodiscard]] std::optional<sim::Simulation> build(const parallel::Domain& domain,
                                                       sim::RunControl& control, bool resume) override;
    [[nodiscard]] std::vector<sim::Observer*> observers(const sim::Simulation& sim) override;
    void finish(sim::Simulation&, const sim::RunEnd&) override {}
    void write_end_files(const sim::Simulation&, const sim::RunEnd&) override {}
    [[nodiscard]] sim::SummaryHead summary_head(const sim::Simulation& sim) const override;
    [[nodiscard]] int summarise(io::JsonObject& js, const sim::Simulation& sim,
                                const sim::RunEnd& end) override;
    void summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const override;
    void log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                 const sim::RunTotals& totals) const override;
    [[nodiscard]] std::string report_script() const override { return "dam_break_report.py"; }

  private:
    [[nodiscard]] double final_front() const;  // x / a at the last row

    PreparedDamBreak pc_;
    std::optional<DamBreakObserver> front_;
    std::optional<sim::FluidFrames> frames_;
    analysis::FrontComparison versus_;  // the front against the experiment, at the end
};

}  // namespace sabo::cases
