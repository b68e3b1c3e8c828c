// SPDX-License-Identifier: MIT
// case.type = "fluid_box": grains at given places in a closed box full of fluid (settling, sedimentation,
// buoyancy experiments from a case file and a CSV of grains; docs/case_files.md).
#pragma once
#include <optional>

#include "cases/fluid_box/fluid_box_observer.h"
#include "cases/fluid_box/fluid_box_settings.h"
#include "sim/case_type.h"
#include "sim/frame_observers.h"

namespace sabo::cases {

class FluidBoxType final : public sim::CaseType {
  public:
    void prepare(const sim::RunRequest& req, const Config& cfg) override {
        pc_ = prepare_fluid_box(req, cfg);
    }
    void print_derived() const override { cases::print_derived(pc_); }
    [[nodiscard]] const sim::OutputSettings& output() const override { return pc_.output; }
    [[nodiscard]] double end_time() const override { return pc_.scene.end_time; }
    [[nodiscard]] sim::ProgressLine progress() const override { return {pc_.scene.particles.n_mobile, true}; }
    [[nodiscard]] parallel::Domain domain(const MpiWorld* world) const override;
    [[nodiscard]] std::optional<sim::Simulation> build(const parallel::Domain& domain,
                                                       sim::RunControl& control, bool resume) override;
    [[nodiscard]] std::vector<sim::Observer*> observers(const sim::Simulation& sim) override;
    [[nodiscard]] bool sample_at_end() const override { return true; }
    void finish(sim::Simulation&, const sim::RunEnd&) override {}
    void write_end_files(const sim::Simulation&, const sim::RunEnd&) override {}
    [[nodiscard]] sim::SummaryHead summary_head(const sim::Simulation& sim) const override;
    [[nodiscard]] int summarise(io::JsonObject& js, const sim::Simulation& sim,
                                const sim::RunEnd& end) override;
    void summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const override;
    void log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                 const sim::RunTotals& totals) const override;
    [[nodiscard]] std::string report_script() const override { return "fluid_box_report.py"; }

  private:
    PreparedFluidBox pc_;
    std::optional<FluidBoxObserver> measures_;
    std::optional<sim::FluidFrames> fluid_frames_;
    std::optional<sim::ParticleFrames> grain_frames_;
};

// A sphere's settling velocity in an unbounded fluid, m/s: Stokes' (2/9) Δρ g r² / μ, and with Schiller &
// Naumann's drag, C_D = 24/Re (1 + 0.15 Re^0.687) (Re < 800), solved by fixed-point iteration.
struct SettlingPrediction {
    double stokes = 0.0, schiller_naumann = 0.0, reynolds = 0.0;  // m/s, m/s, at the latter
};
[[nodiscard]] SettlingPrediction settling_prediction(double radius, double grain_density,
                                                     double fluid_density, double viscosity, double gravity);
// The drag of a simple cubic array of spheres at solid fraction φ over Stokes' drag at the mean (superficial)
// velocity, F / (6 π η R U) (Sangani & Acrivos 1982, Eq. 4.7, extending Hasimoto 1959; better than 1 % for
// φ < 0.2).
[[nodiscard]] double periodic_array_correction(double phi);

}  // namespace sabo::cases
