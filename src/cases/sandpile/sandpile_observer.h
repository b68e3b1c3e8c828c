// SPDX-License-Identifier: MIT
// The sandpile's phases as an observer of the run (settling, draining, the complete stop of the heap) and
// the state of the grains above the plate it judges them by.
#pragma once
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "analysis/repose_angle.h"
#include "analysis/stop_detector.h"
#include "cases/sandpile/sandpile_settings.h"
#include "io/run_output.h"
#include "sim/observer.h"

namespace sabo::cases {

struct HeapState {
    std::size_t on_plate = 0;   // PlateGeometry::holds
    std::size_t above = 0;      // PlateGeometry::above
    double above_energy = 0.0;  // J, kinetic energy of those
};

[[nodiscard]] inline HeapState heap_state(const dem::Particles& p, const analysis::PlateGeometry& plate) {
    HeapState h;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        if (!plate.above(p.x[i])) continue;
        ++h.above;
        h.above_energy += p.kinetic_energy(i);
        h.on_plate += plate.holds(p.x[i]) ? 1 : 0;
    }
    return h;
}

// The sandpile's phases as an observer of the run: settling with the outlets closed until the mass is at
// rest (or sandpile.settle_max_time_s), then draining to the complete stop of the heap; grains that fell
// below the plate leave the run (sandpile.remove_drained).
class SandpileObserver final : public sim::Checkpointed<SandpileObserver> {
  public:
    // `domain`: a run divided among ranks (every rank analyses every grain; the first writes series.csv).
    SandpileObserver(const PreparedSandpile& pc, const analysis::PlateGeometry& plate,
                     const parallel::Domain& domain)
        : pc_(pc),
          plate_(plate),
          settle_steps_(static_cast<std::uint64_t>(std::ceil(pc.scene.settle_max_time / pc.dem.dt - 1e-9))),
          // Grains that fell through an outlet to 2 d below the plate's underside can no longer touch the
          // heap: with remove_drained they leave the run there instead of piling up on the floor, where
          // they cost as much as the heap itself and change nothing that is measured.
          drained_z_(pc.scene.plate_z - pc.scene.plate_thickness - 2.0 * pc.scene.diameter),
          // the stop is judged on the grains above the plate (grains that drained to the floor do not
          // change the heap; frictionless ones would roll there for ever), as mean energy per grain
          quiet_(pc.stop_energy_per_grain, pc.stop_hold),
          series_(domain.writes_outputs() ? pc.output.out_dir / "series.csv" : std::filesystem::path(),
                  {"time_s", "phase", "kinetic_energy_J", "above_plate_kinetic_energy_J", "contacts",
                   "sliding_fraction", "grains_on_plate", "max_overlap_over_d"}) {}

    void before_step(sim::Simulation& sim) override {
        if (phase_ == 0 && sim.steps() >= settle_steps_) open_outlets(sim, "settle_max_time_s reached");
    }

    bool sample(sim::Simulation& sim) override {
        const dem::GrainView grains = sim.grain_view();  // every rank: a collective call when divided
        const auto ke = grains.kinetic_energy();
        const HeapState h = heap_state(grains.particles, plate_);
        const auto& st = grains.stats;
        series_.row(
            {grains.time, static_cast<double>(phase_), ke.translational + ke.rotational, h.above_energy,
             static_cast<double>(st.contacts),
             st.contacts > 0 ? static_cast<double>(st.sliding) / static_cast<double>(st.contacts) : 0.0,
             static_cast<double>(h.on_plate), st.max_overlap_ratio});
        const bool quiet =
            quiet_.sample(grains.time, h.above > 0 ? h.above_energy / static_cast<double>(h.above) : 0.0);
        if (sim.steps() == 0) return false;  // the first row, before any step
        if (quiet && phase_ == 1) {
            stopped_at_ = grains.time;
            spdlog::info("complete stop at t = {:.4f} s", stopped_at_);
            return true;
        }
        if (quiet) open_outlets(sim, "the settling mass came to rest");
        if (phase_ == 1 && pc_.remove_drained)
            sim.remove_grains([&](const Vec3& x) { return x.z < drained_z_; });
        return false;
    }

    [[nodiscard]] std::string phase() const override { return phase_ == 0 ? "settling" : "draining"; }
    [[nodiscard]] bool draining() const { return phase_ == 1; }
    [[nodiscard]] double opened_at() const { return opened_at_; }
    [[nodiscard]] double stopped_at() const { return stopped_at_; }
    // The phase and what was measured so far (io/checkpoint.h); the gates' state is the solver's.
    template <class Archive>
    void transfer(Archive& a) {
        a(quiet_, series_, phase_, opened_at_, stopped_at_);
    }

  private:
    void open_outlets(sim::Simulation& sim, const char* why) {
        for (const std::size_t gate : pc_.scene.gates) sim.grains().set_wall_active(gate, false);
        phase_ = 1;
        opened_at_ = sim.time();
        quiet_ = analysis::StopDetector(pc_.stop_energy_per_grain, pc_.stop_hold);
        spdlog::info("outlets opened at t = {:.4f} s ({})", opened_at_, why);
    }

    const PreparedSandpile& pc_;
    analysis::PlateGeometry plate_;
    std::uint64_t settle_steps_;
    double drained_z_;
    analysis::StopDetector quiet_;
    io::CsvSeries series_;
    int phase_ = 0;  // 0 settling (outlets closed), 1 draining
    double opened_at_ = -1.0, stopped_at_ = -1.0;
};

}  // namespace sabo::cases
