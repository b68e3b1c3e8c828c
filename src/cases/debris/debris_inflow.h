// SPDX-License-Identifier: MIT
// The fluid fed through a debris channel's inflow boundary from its hydrograph (lbm/inlet.h), as an observer
// of the run. After every lattice step the first plane's cells from the bed up to the depth Q_f / (u W)
// (whole cells, at least one) are held full at the column's hydrostatic density, moving down the channel at
// the velocity that delivers the hydrograph's fluid discharge Q_f = Q (1 − c) (its grains enter as grains:
// cases/common/inflow_observer.h): Q_f / (W h) plus what is owed — the difference
// between the hydrograph's volume so far and what entered — over the response time response_s. What the held
// cells take in is what entered (the lattice's mass grows by exactly it); inflow.csv records it at every
// series row. Before the hydrograph's first time and after its last no cell is held (the fluid left in the
// inlet runs on). A run divided among ranks: the rank whose slab holds the first plane holds the cells, and
// every rank counts what they took in (a sum over the ranks each step: the others add nothing).
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "cases/debris/debris_observer.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "lbm/inlet.h"
#include "lbm/units.h"
#include "scenario/grain_inflow.h"
#include "sim/observer.h"

namespace sabo::cases {

class FluidInflowObserver final : public sim::Checkpointed<FluidInflowObserver> {
  public:
    // `shape` the lattice's, `walls_cells` the side walls' height in cells (the deepest inflow), `seed` the
    // fluid the inlet started with (lattice mass); `debris` counts what enters in its starting mass.
    // `g_normal` gravity's component into the bed, m/s².
    FluidInflowObserver(const scenario::InflowSettings& settings, const lbm::UnitConverter& units,
                        const lbm::GridShape& shape, int walls_cells, double seed, double g_normal,
                        DebrisObserver& debris, const std::filesystem::path& out_dir, bool writes)
        : s_(settings),
          units_(units),
          g_normal_(units.acceleration(g_normal)),
          ny_(shape.ny),
          walls_cells_(std::max(1, walls_cells)),
          debris_(debris),
          entered_(seed * cell_volume()),
          series_(writes ? out_dir / "inflow.csv" : std::filesystem::path(),
                  {"time_s", "hydrograph_volume_m3", "inflow_volume_m3"}) {}

    void after_step(sim::Simulation& sim) override {
        const double t = sim.time();
        const auto& h = s_.hydrograph;
        due_ = h.fluid_volume(h.start(), t);  // (the grains the hydrograph carries enter as grains)
        const double q = h.fluid_discharge(t);
        if (!(q > 0.0)) return;
        const double dx = units_.dx(), width = s_.width;
        const int layers =
            std::clamp(static_cast<int>(std::ceil(q / (width * s_.velocity * dx) - 1e-9)), 1, walls_cells_);
        const double area = width * layers * dx;
        // the velocity that delivers Q, and what is owed over the response time (none taken back below 0);
        // at most a lattice speed of 0.1 (Mach 0.17)
        const double u =
            std::clamp((q + (due_ - entered_) / response_s) / area, 0.0, units_.velocity_si(0.1));
        cells_.clear();
        for (int z = 0; z < layers; ++z) {
            // the column's hydrostatic density below its surface at the top of the held layers: p = c_s² ρ
            const double rho = 1.0 + 3.0 * g_normal_ * (static_cast<double>(layers) - (z + 0.5));
            for (int y = 0; y < ny_; ++y) cells_.push_back({0, y, z, z == layers - 1, rho});
        }
        const parallel::Domain& d = sim.domain();
        const bool holds = d.global_x(0) == 0;  // (local x 0 is global x 0: one process, or the first slab)
        const double added = d.sum(holds ? sim.hold_inlet(cells_, Vec3{units_.velocity(u), 0.0, 0.0}) : 0.0);
        entered_ += added * cell_volume();
        debris_.state().m0 += added;  // the fluid the run has had: its start and what entered
    }

    bool sample(sim::Simulation& sim) override {
        series_.row({sim.time(), due_, entered_});
        return false;
    }

    // summary.json's keys (docs/outputs.md).
    void summarise(io::JsonObject& js) const {
        js.number("inflow_hydrograph_volume_m3", due_)
            .number("inflow_volume_m3", entered_)
            .number("inflow_volume_relative_difference", due_ > 0.0 ? (entered_ - due_) / due_ : 0.0)
            .number("inflow_velocity_m_s", s_.velocity);
    }

    template <class Archive>
    void transfer(Archive& a) {
        a(entered_, due_, series_);
    }

  private:
    static constexpr double response_s = 0.03;  // s: what is owed is delivered over this time
    [[nodiscard]] double cell_volume() const { return units_.dx() * units_.dx() * units_.dx(); }
    scenario::InflowSettings s_;
    lbm::UnitConverter units_;
    double g_normal_;  // lattice units
    int ny_, walls_cells_;
    DebrisObserver& debris_;
    double entered_;    // m³ that entered (the seed's included)
    double due_ = 0.0;  // m³, the hydrograph's volume up to the last step
    std::vector<lbm::InletCell> cells_;
    io::CsvSeries series_;
};

}  // namespace sabo::cases
