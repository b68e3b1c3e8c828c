// SPDX-License-Identifier: MIT
// The measures of a fluid box as an observer of the run: every grain's position, velocity and the fluid's
// force on it split into drag and buoyancy (grains_series.csv, one row per grain and sample), the lattice's
// health, the grains' mean vertical velocity and the fluid's mean velocity along X (series.csv), and each
// grain's velocity and force averaged over the run's last fifth (its settling velocity once terminal; a held
// grain's drag in a steady flow). Held grains (grains.held) are put back where they started, at rest, after
// every DEM step.
#pragma once
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "cases/fluid_box/fluid_box_settings.h"
#include "io/run_output.h"
#include "sim/observer.h"

namespace sabo::cases {

class FluidBoxObserver final : public sim::Checkpointed<FluidBoxObserver> {
  public:
    FluidBoxObserver(const PreparedFluidBox& pc, double mass0)
        : pc_(pc),
          m0_(mass0),
          velocity_sum_(pc.scene.particles.n_mobile),
          force_sum_(pc.scene.particles.n_mobile),
          series_(pc.output.out_dir / "series.csv",
                  {"time_s", "grain_mean_vz_m_s", "grain_max_speed_m_s", "mass_relative_drift",
                   "max_speed_m_s", "fluid_mean_vx_m_s"}),
          grains_(pc.output.out_dir / "grains_series.csv",
                  {"time_s", "grain", "x_m", "y_m", "z_m", "vx_m_s", "vy_m_s", "vz_m_s", "drag_x_N",
                   "drag_y_N", "drag_z_N", "buoyancy_x_N", "buoyancy_y_N", "buoyancy_z_N"}) {}

    bool sample(sim::Simulation& sim) override {
        const double t = sim.time();
        const dem::Particles& p = sim.grains().particles();
        const auto& coupling = sim.coupling();
        const std::size_t n = p.n_mobile;
        // (forces of the last exchange: none yet at the start of a run or a resumed one)
        const bool exchanged = coupling.forces().size() >= n && coupling.buoyancies().size() >= n;
        const bool averaging = t >= pc_.average_from - 1e-12;
        // a run resumed with a later end time has a later window: what the first part averaged before it goes
        if (averaged_ > 0 && averaged_since_ < pc_.average_from - 1e-12) {
            std::fill(velocity_sum_.begin(), velocity_sum_.end(), Vec3{});
            std::fill(force_sum_.begin(), force_sum_.end(), Vec3{});
            flow_sum_ = 0.0;
            averaged_ = 0;
        }
        if (averaging && averaged_ == 0) averaged_since_ = t;
        double mean_vz = 0.0, fastest = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 b = exchanged ? coupling.buoyancies()[i] : Vec3{};
            const Vec3 drag = exchanged ? coupling.forces()[i] - b : Vec3{};
            grains_.row({t, static_cast<double>(i), p.x[i].x, p.x[i].y, p.x[i].z, p.v[i].x, p.v[i].y,
                         p.v[i].z, drag.x, drag.y, drag.z, b.x, b.y, b.z});
            mean_vz += p.v[i].z / static_cast<double>(n);
            fastest = std::max(fastest, norm(p.v[i]));
            if (averaging) {
                velocity_sum_[i] += p.v[i];
                force_sum_[i] += b + drag;
            }
        }
        const lbm::FluidFields& f = sim.fluid_fields();
        // the fluid's mean velocity along X over the box (Σ ρ u_x / Σ ρ: the superficial velocity of a
        // periodic array, the grains' cells counted as the fluid they hold)
        double momentum = 0.0, mass = 0.0;
        for (std::size_t c = 0; c < f.cells(); ++c) {
            momentum += f.density[c] * f.velocity[c].x;
            mass += f.density[c];
        }
        const double flow = mass > 0.0 ? pc_.fluid.units.velocity_si(momentum / mass) : 0.0;
        if (averaging) {
            flow_sum_ += flow;
            ++averaged_;
        }
        const double drift = (f.totals.mass - m0_) / m0_;
        worst_drift_ = std::max(worst_drift_, std::abs(drift));
        const double speed = pc_.fluid.units.velocity_si(f.totals.max_speed);
        series_.row({t, mean_vz, fastest, drift, speed, flow});
        lbm::check_fluid_stable(t, drift, f.totals.max_speed, pc_.fluid.max_mass_drift);
        return false;
    }

    [[nodiscard]] double worst_drift() const { return worst_drift_; }
    // Grain i's mean velocity over the samples of the run's last fifth (m/s; zero before any).
    [[nodiscard]] Vec3 late_velocity(std::size_t i) const {
        return averaged_ > 0 ? velocity_sum_[i] / static_cast<double>(averaged_) : Vec3{};
    }
    // Grain i's mean force (drag + buoyancy) over the same samples, N.
    [[nodiscard]] Vec3 late_force(std::size_t i) const {
        return averaged_ > 0 ? force_sum_[i] / static_cast<double>(averaged_) : Vec3{};
    }
    // The fluid's mean velocity along X over the same samples, m/s.
    [[nodiscard]] double late_flow() const {
        return averaged_ > 0 ? flow_sum_ / static_cast<double>(averaged_) : 0.0;
    }
    [[nodiscard]] std::size_t averaged_samples() const { return averaged_; }

    void after_grain_step(sim::Simulation& sim) override {
        if (!pc_.scene.held) return;
        dem::Particles& p = sim.grains().particles();
        for (std::size_t i = 0; i < p.n_mobile; ++i) {
            p.x[i] = pc_.scene.particles.x[i];
            p.v[i] = {};
            p.w[i] = {};
        }
    }
    // The history so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(m0_, worst_drift_, velocity_sum_, force_sum_, flow_sum_, averaged_, averaged_since_, series_,
          grains_);
    }

  private:
    const PreparedFluidBox& pc_;
    double m0_;
    double worst_drift_ = 0.0;
    std::vector<Vec3> velocity_sum_, force_sum_;
    double flow_sum_ = 0.0;  // m/s
    std::size_t averaged_ = 0;
    double averaged_since_ = 0.0;  // s: the first sample in the sums
    io::CsvSeries series_, grains_;
};

}  // namespace sabo::cases
