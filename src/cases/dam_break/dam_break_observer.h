// SPDX-License-Identifier: MIT
// The dam break's measures as an observer of the run: the front along the floor and the height of the water
// at the wall at every series row, the lattice's health, and the front's history for the comparison with
// the experiment.
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "cases/dam_break/dam_break_settings.h"
#include "io/run_output.h"
#include "lbm/units.h"
#include "sim/observer.h"

namespace sabo::cases {

// The front along the floor (mid-slab row): the downstream face of the last bottom cell holding at
// least a tenth of a cell of fluid (the tip the experiment's observers followed, not the body of the
// surge: with 0.5 the front lags the tip by a cell or two and reads up to 7 % short late in the run).
// Global cells, over every rank's own planes.
[[nodiscard]] inline double front_cells(const lbm::FluidFields& f, const parallel::Domain& domain) {
    int last = -1;
    for (int x = 0; x < f.nx; ++x)
        if (f.fill[f.cell(x, f.ny / 2, 0)] >= 0.1) last = domain.global_x(f.first_x + x);
    return domain.max(last + 1.0);
}

// Height of the water at the left wall (the column's remains), cells.
[[nodiscard]] inline double wall_height_cells(const lbm::FluidFields& f, const parallel::Domain& domain) {
    double h = 0.0;
    if (domain.global_x(f.first_x) == 0)  // the rank that owns the first plane
        for (int z = 0; z < f.nz; ++z) h += f.fill[f.cell(0, f.ny / 2, z)];
    return domain.sum(h);
}

// The front, the height at the wall and the lattice's health at every series row; the front's history
// for the comparison with the experiment.
class DamBreakObserver final : public sim::Checkpointed<DamBreakObserver> {
  public:
    DamBreakObserver(const PreparedDamBreak& pc, double mass0, const parallel::Domain& domain)
        : dx_(pc.fluid.units.dx()),
          a_(pc.column_cells * dx_),
          t_scale_(std::sqrt(2.0 * pc.scene.gravity / a_)),
          m0_(mass0),
          units_(pc.fluid.units),
          max_mass_drift_(pc.fluid.max_mass_drift),
          series_(domain.writes_outputs() ? pc.output.out_dir / "series.csv" : std::filesystem::path(),
                  {"time_s", "T_scaled", "front_m", "front_over_a", "wall_height_m", "mass_relative_drift",
                   "max_speed_m_s", "interface_cells", "tau_min_cells", "tau_max_cells"}) {}

    bool sample(sim::Simulation& sim) override {
        const double t = sim.time();
        const parallel::Domain& domain = sim.domain();  // (a divided run's slabs may have moved)
        const lbm::FluidFields& l = sim.fluid_fields();
        const lbm::FluidTotals& now = l.totals;
        const double vmax = domain.max(now.max_speed);
        const double drift = (domain.sum(now.mass) - m0_) / m0_;
        worst_drift_ = std::max(worst_drift_, std::abs(drift));
        const double front = front_cells(l, domain) * dx_;
        const double wall = wall_height_cells(l, domain) * dx_;
        times_.push_back(t * t_scale_);
        fronts_.push_back(front / a_);
        // (a divided run's clamp counts include the ghost planes, counted by both neighbours)
        series_.row({t, t * t_scale_, front, front / a_, wall, drift, units_.velocity_si(vmax),
                     domain.sum(static_cast<double>(l.interface_cells)),
                     domain.sum(static_cast<double>(l.clamps.at_min)),
                     domain.sum(static_cast<double>(l.clamps.at_max))});
        lbm::check_fluid_stable(t, drift, vmax, max_mass_drift_);
        return false;
    }

    [[nodiscard]] double worst_drift() const { return worst_drift_; }
    [[nodiscard]] const std::vector<double>& times() const { return times_; }    // T
    [[nodiscard]] const std::vector<double>& fronts() const { return fronts_; }  // x / a
    // The history so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(m0_, series_, times_, fronts_, worst_drift_);
    }

  private:
    double dx_, a_, t_scale_, m0_;
    lbm::UnitConverter units_;
    double max_mass_drift_;
    io::CsvSeries series_;
    std::vector<double> times_, fronts_;
    double worst_drift_ = 0.0;
};

}  // namespace sabo::cases
