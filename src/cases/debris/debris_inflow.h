// SPDX-License-Identifier: MIT
// The fluid fed through a debris channel's inflow boundary from its hydrograph (lbm/inlet.h), as an observer
// of the run. After every lattice step the first plane's cells from the bed up to the depth Q_f / (u W)
// (whole cells, at least one; the bed: the plane, or the relief of a channel mesh under each column, a
// column a side wall fills left out of W) are held full at the column's hydrostatic density, moving down the
// channel at the velocity that delivers the hydrograph's fluid discharge Q_f = Q (1 − c) (its grains enter as
// grains: cases/common/inflow_observer.h): Q_f / (W h) plus what is owed — the difference between the
// hydrograph's volume so far and what entered — over the response time response_s. What the held cells take
// in is what entered (the lattice's mass grows by exactly it); inflow.csv records it at every series row.
// Before the hydrograph's first time and after its last no cell is held (the fluid left in the inlet runs
// on). A run divided among ranks: the rank whose slab holds the first plane holds the cells, and every rank
// counts what they took in (a sum over the ranks each step: the others add nothing).
#pragma once
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "cases/debris/debris_observer.h"
#include "core/error.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "lbm/inlet.h"
#include "lbm/units.h"
#include "scenario/grain_inflow.h"
#include "sim/observer.h"

namespace sabo::cases {

class FluidInflowObserver final : public sim::Checkpointed<FluidInflowObserver> {
  public:
    // `bed` the bed's cells under each row of the first plane (scenario::inlet_bed_cells), `walls_cells` the
    // side walls' height in cells (no cell above them is held), `seed` the fluid the inlet started with
    // (lattice mass); `debris` counts what enters in its starting mass. `g_normal` gravity's component into
    // the bed, m/s².
    FluidInflowObserver(const scenario::InflowSettings& settings, const lbm::UnitConverter& units,
                        std::vector<int> bed, int walls_cells, double seed, double g_normal,
                        DebrisObserver& debris, const std::filesystem::path& out_dir, bool writes)
        : s_(settings),
          units_(units),
          g_normal_(units.acceleration(g_normal)),
          ny_(static_cast<int>(bed.size())),
          walls_cells_(std::max(1, walls_cells)),
          bed_(std::move(bed)),
          debris_(debris),
          entered_(seed * cell_volume()),
          series_(writes ? out_dir / "inflow.csv" : std::filesystem::path(),
                  {"time_s", "hydrograph_volume_m3", "inflow_volume_m3"}) {
        for (const int b : bed_)
            if (b >= 0 && b < walls_cells_) {
                ++open_rows_;
                lowest_bed_ = std::min(lowest_bed_, b);
                highest_bed_ = std::max(highest_bed_, b);
            }
        if (open_rows_ == 0)
            throw InputError(
                fmt::format("channel.mesh_file: its parts fill the channel's first plane up to the "
                            "side walls' top ({} cells): the inflow has no section to enter by",
                            walls_cells_));
    }

    void after_step(sim::Simulation& sim) override {
        const double t = sim.time();
        const auto& h = s_.hydrograph;
        due_ = h.fluid_volume(h.start(), t);  // (the grains the hydrograph carries enter as grains)
        const double q = h.fluid_discharge(t);
        if (!(q > 0.0)) return;
        // the width the rows the side walls leave open span (W where none is closed)
        const double dx = units_.dx(), width = s_.width * (static_cast<double>(open_rows_) / ny_);
        const int layers = std::clamp(static_cast<int>(std::ceil(q / (width * s_.velocity * dx) - 1e-9)), 1,
                                      walls_cells_ - lowest_bed_);
        cells_.clear();
        int held = 0;  // (a row whose bed stands higher holds fewer layers below the walls' top)
        for (int z = lowest_bed_; z < highest_bed_ + layers; ++z)
            for (int y = 0; y < ny_; ++y) {
                const int bed = bed_[static_cast<std::size_t>(y)], top = std::min(bed + layers, walls_cells_);
                if (bed < 0 || z < bed || z >= top) continue;
                // the column's hydrostatic density below the top of its held layers (p = c_s² ρ)
                const double rho = 1.0 + 3.0 * g_normal_ * (static_cast<double>(top) - (z + 0.5));
                cells_.push_back({0, y, z, z == top - 1, rho});
                ++held;
            }
        // the velocity that delivers Q through the held cells' section, and what is owed over the response
        // time (none taken back below 0); at most a lattice speed of 0.1 (Mach 0.17)
        const double area = s_.width * (static_cast<double>(held) / ny_) * dx;
        const double u =
            std::clamp((q + (due_ - entered_) / response_s) / area, 0.0, units_.velocity_si(0.1));
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
    std::vector<int> bed_;  // the bed's cells under each row of the first plane
    int open_rows_ = 0;     // the section's rows: no side wall's, the bed below the walls' top
    int lowest_bed_ = std::numeric_limits<int>::max(), highest_bed_ = 0;  // of the open rows
    DebrisObserver& debris_;
    double entered_;    // m³ that entered (the seed's included)
    double due_ = 0.0;  // m³, the hydrograph's volume up to the last step
    std::vector<lbm::InletCell> cells_;
    io::CsvSeries series_;
};

}  // namespace sabo::cases
