// SPDX-License-Identifier: MIT
// Grains fed through a channel's inflow section from its hydrograph (scenario/grain_inflow.h), as an observer
// of the run: every batch interval the interval's solid volume, with what earlier batches could not place,
// is placed in the section's zone and added to the run; `inflow.csv` records each batch (the hydrograph's
// solid volume up to then, what entered, the grains) — `inflow_grains.csv` in a debris run, where the fluid's
// inflow writes `inflow.csv`. Divided among ranks, every rank places the same batch among
// every grain of the run (gathered) and keeps those in its slab.
#pragma once
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "io/json_writer.h"
#include "io/run_output.h"
#include "scenario/grain_inflow.h"
#include "sim/observer.h"

namespace sabo::cases {

class InflowObserver final : public sim::Checkpointed<InflowObserver> {
  public:
    // `dt` the run's step (the DEM step; with the fluid, the lattice step): a batch lasts a whole number of
    // steps, L/u rounded (the zone's length with it). `beside_fluid`: a debris run's grains, beside the
    // fluid's inflow (its file and summary keys apart).
    InflowObserver(const scenario::InflowSettings& settings, double dt, const std::filesystem::path& out_dir,
                   bool writes, bool beside_fluid = false)
        : s_(settings),
          batch_steps_(std::max<std::uint64_t>(
              1, static_cast<std::uint64_t>(std::llround(settings.length / (settings.velocity * dt))))),
          batch_dt_(static_cast<double>(batch_steps_) * dt),
          beside_fluid_(beside_fluid),
          series_(writes ? out_dir / (beside_fluid ? "inflow_grains.csv" : "inflow.csv")
                         : std::filesystem::path(),
                  {"time_s", "hydrograph_solid_volume_m3", "inflow_solid_volume_m3", "inflow_grains"}) {
        s_.length = settings.velocity * batch_dt_;
    }

    void after_step(sim::Simulation& sim) override {
        // the run's clock: the DEM's alone, the lattice's with the fluid
        const bool fluid = sim.has_fluid();
        if ((fluid ? sim.steps() : sim.grains().steps()) % batch_steps_ != 0) return;
        const double t = fluid ? sim.time() : sim.grains().time();
        const auto& h = s_.hydrograph;
        if (t - batch_dt_ > h.end()) return;  // the hydrograph has ended (and its last interval placed)
        owed_ += h.solid_volume(t - batch_dt_, t);
        due_ = h.solid_volume(h.start(), t);
        double placed = 0.0;
        std::vector<dem::GrainRecord> grains = scenario::inflow_batch(s_, t - 0.5 * batch_dt_, owed_, batch_,
                                                                      sim.grain_view().particles, placed);
        ++batch_;
        owed_ -= placed;
        entered_ += placed;
        count_ += static_cast<double>(grains.size());
        if (!grains.empty()) sim.add_grains(std::move(grains));
        series_.row({t, due_, entered_, count_});
        // more than three batches behind: the zone stays full (the flow does not leave it fast enough)
        if (!warned_ && owed_ > 3.0 * std::max(h.solid_volume(t - batch_dt_, t), 1e-12)) {
            warned_ = true;
            spdlog::warn(
                "t = {:.3f} s: the inflow zone is full: {:.4g} m3 of grains wait to enter (the grains there "
                "do "
                "not move on at inflow.velocity_m_s = {:.3g} m/s: a faster inflow, a longer zone or a "
                "steeper "
                "channel)",
                t, owed_, s_.velocity);
        }
    }

    // summary.json's keys (docs/outputs.md).
    void summarise(io::JsonObject& js) const {
        js.number("inflow_hydrograph_solid_volume_m3", due_)
            .number("inflow_solid_volume_m3", entered_)
            .number(beside_fluid_ ? "inflow_solid_volume_relative_difference"
                                  : "inflow_volume_relative_difference",
                    due_ > 0.0 ? (entered_ - due_) / due_ : 0.0)
            .integer("inflow_grains", static_cast<std::int64_t>(count_))
            .number("inflow_velocity_m_s", s_.velocity)
            .number("inflow_batch_interval_s", batch_dt_)
            .number("inflow_zone_length_m", s_.length);
    }

    // m³ of grains placed so far
    [[nodiscard]] double entered() const { return entered_; }

    template <class Archive>
    void transfer(Archive& a) {
        a(batch_, owed_, due_, entered_, count_, warned_, series_);
    }

  private:
    scenario::InflowSettings s_;
    std::uint64_t batch_steps_;
    double batch_dt_;
    bool beside_fluid_;
    io::CsvSeries series_;
    std::uint64_t batch_ = 0;
    double owed_ = 0.0;     // m³ the batches could not place yet
    double due_ = 0.0;      // m³, the hydrograph's solid volume up to the last batch
    double entered_ = 0.0;  // m³ placed
    double count_ = 0.0;    // grains placed
    bool warned_ = false;
};

}  // namespace sabo::cases
