// SPDX-License-Identifier: MIT
// case.type = "channel" (the default; reference case C2–C4): the grains released against the barrier, the
// barrier analyses computed during the run (cases/channel/channel_observer.h), stop detection, and the
// outputs of docs/outputs.md.
#pragma once
#include <optional>

#include "cases/channel/channel_observer.h"
#include "cases/channel/channel_settings.h"
#include "cases/common/gauge_observer.h"
#include "cases/common/inflow_observer.h"
#include "sim/case_type.h"
#include "sim/frame_observers.h"

namespace sabo::cases {

class ChannelType final : public sim::CaseType {
  public:
    void prepare(const sim::RunRequest& req, const Config& cfg) override { pc_ = prepare_channel(req, cfg); }
    void print_derived() const override { cases::print_derived(pc_); }
    [[nodiscard]] const sim::OutputSettings& output() const override { return pc_.output; }
    [[nodiscard]] double end_time() const override { return pc_.scene.end_time; }
    [[nodiscard]] sim::ProgressLine progress() const override { return {pc_.scene.release.count, false}; }
    [[nodiscard]] parallel::Domain domain(const MpiWorld* world) const override;
    [[nodiscard]] std::optional<sim::Simulation> build(const parallel::Domain& domain,
                                                       sim::RunControl& control, bool resume) override;
    [[nodiscard]] std::vector<sim::Observer*> observers(const sim::Simulation& sim) override;
    [[nodiscard]] bool sample_at_end() const override { return true; }
    void finish(sim::Simulation& sim, const sim::RunEnd& end) override;
    void write_end_files(const sim::Simulation& sim, const sim::RunEnd& end) override;
    [[nodiscard]] sim::SummaryHead summary_head(const sim::Simulation& sim) const override;
    [[nodiscard]] int summarise(io::JsonObject& js, const sim::Simulation& sim,
                                const sim::RunEnd& end) override;
    void summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const override;
    void log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                 const sim::RunTotals& totals) const override;
    [[nodiscard]] std::string report_script() const override { return "report.py"; }

  private:
    PreparedCase pc_;
    std::optional<ChannelObserver> analysis_;
    std::optional<GaugeObserver> gauge_;
    std::optional<sim::ParticleFrames> frames_;
    std::optional<InflowObserver> inflow_;
    std::optional<dem::GrainView> grains_;  // every grain at the end
};

}  // namespace sabo::cases
