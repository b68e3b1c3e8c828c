// SPDX-License-Identifier: MIT
// The analyses of a debris run (reference case C5) as an observer of the run.
#pragma once
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "analysis/barrier_forces.h"
#include "analysis/facet_maps.h"
#include "analysis/flow_measures.h"
#include "analysis/moving_average.h"
#include "cases/common/grain_outflow.h"
#include "cases/common/inflow_observer.h"
#include "cases/debris/debris_settings.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "lbm/fluid_setup.h"
#include "sim/observer.h"

namespace sabo::cases {

// The barrier's forces after every step (every DEM sub-step with grains: no peak is lost to the
// decimation), the solid and fluid downstream of the barrier, the front and the solvers' health at every
// series row. A fluid-only run writes the series it always wrote; with grains, the solid, fluid and total
// columns.
class DebrisObserver final : public sim::Checkpointed<DebrisObserver> {
  public:
    // `domain`: a run divided among ranks (the fluid's sums over them, every grain's view on every rank; the
    // first rank writes series.csv).
    DebrisObserver(const PreparedDebris& pc, double weight_along, const parallel::Domain& domain = {})
        : pc_(pc),
          weight_along_(weight_along),
          forces_(pc.scene.barrier),
          outflow_(pc.scene.bounds, pc.scene.channel.length, pc.scene.channel.width, pc.scene.barrier),
          fluid_on_element_(pc.fluid_on() ? pc.scene.barrier.elements.size() : 0),
          element_part_(element_parts(pc.scene.barrier)),
          normal_means_{analysis::MovingAverage(0.01, recording_dt(pc)),
                        analysis::MovingAverage(0.05, recording_dt(pc)),
                        analysis::MovingAverage(0.1, recording_dt(pc))},
          series_(domain.writes_outputs() ? pc.output.out_dir / "series.csv" : std::filesystem::path(),
                  series_columns(pc.grains())) {}

    // The fluid's measures that outlive a row.
    struct State {
        double m0 = 0.0;  // lattice mass at the start of the run (a resumed run keeps its start's)
        double worst_drift = 0.0, non_retained = 0.0;
        // m above the bed: the top of the highest cell holding a tenth of fluid, over the run (the run-up);
        // and whether the fluid reached the domain's top, which then acts as a lid (said once)
        double max_height = 0.0;
        bool top_reached = false;
        // an open channel: the share of the starting fluid mass that left through each outlet
        // (scenario::DebrisOutlet: the channel's end, the sides above the walls, the top)
        std::array<double, 3> left{};
        // the share of the fluid the run has had that entered the region behind the barrier: over its crest,
        // below it, and by the free surface's spreads (lbm::FluidLattice::region_inflow)
        std::array<double, 3> behind{};
    };
    [[nodiscard]] State& state() { return state_; }
    [[nodiscard]] const State& state() const { return state_; }
    [[nodiscard]] const analysis::BarrierForceMonitor& forces() const { return forces_; }
    // A mesh barrier's triangles: the grains' and the fluid's force on each at the force maps' times.
    [[nodiscard]] const analysis::FacetMaps& facet_maps() const { return facets_; }
    // Takes the end map (the state the run stops in) of the forces and of the triangles (collective).
    void finish_forces(const sim::Simulation& sim, double time) {
        forces_.finish(time);
        take_facet_maps(sim, time, true);
    }
    [[nodiscard]] double solid_non_retained() const { return solid_non_retained_; }
    // The fluid that entered the region behind the barrier so far, over the fluid the run has had
    // (docs/analysis.md, "Overflow"): over its crest (0), through its outlets (1), moved there by the free
    // surface's spreads (2).
    [[nodiscard]] double fluid_behind_fraction(std::size_t part) const { return state_.behind[part]; }
    // Grains fed through an inflow count in the grains' mass as they enter.
    void feed_from(const InflowObserver& inflow) { fed_ = &inflow; }
    // The grains the run has had so far (released and fed), m³ and kg.
    [[nodiscard]] double solid_volume_m3() const {
        const auto& g = pc_.scene.grains;
        return fed_ != nullptr ? g.solid_volume + fed_->entered() : g.solid_volume;
    }
    [[nodiscard]] double solid_mass_kg() const { return pc_.scene.grains.density * solid_volume_m3(); }
    // The grains that left the channel or passed the barrier's crest, as of the last series row.
    [[nodiscard]] const GrainOutflow& outflow() const { return outflow_; }
    // The barrier's normal force (solid + fluid) averaged over 10, 50 and 100 ms windows: its largest means
    // tell a load that lasts from the lattice's acoustic ringing at the front's arrival and from contact
    // spikes (docs/results/open_channel_fluid.md).
    [[nodiscard]] const std::array<analysis::MovingAverage, 3>& normal_means() const { return normal_means_; }
    // Everything accumulated so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(state_.m0, state_.worst_drift, state_.non_retained, state_.max_height, state_.top_reached,
          state_.left, state_.behind, forces_, normal_means_[0], normal_means_[1], normal_means_[2], series_,
          solid_non_retained_, facets_);
        outflow_.transfer(a);  // (by its transfer: a byte copy would carry its reference to the barrier)
    }

    void after_step(sim::Simulation& sim) override {
        if (pc_.grains()) {  // forces recorded at every DEM sub-step
            outflow_.remove_exits(sim);
            return;
        }
        fluid_forces(sim);
        forces_.record(sim.time(), {}, {}, fluid_on_element_);
        take_facet_maps(sim, sim.time(), false);
        for (auto& m : normal_means_) m.add(sim.time(), forces_.normal());
    }

    void after_grain_step(sim::Simulation& sim) override {
        if (sim.has_fluid()) fluid_forces(sim);             // the lattice step's, held over its sub-steps
        const dem::ContactForces f = sim.contact_forces();  // a divided run's: summed over the ranks
        forces_.record(sim.grains().time(), f.particles, f.walls, fluid_on_element_);
        take_facet_maps(sim, sim.grains().time(), false);
        for (auto& m : normal_means_) m.add(sim.grains().time(), forces_.normal());
        outflow_.after_grain_step(sim);
    }

    bool sample(sim::Simulation& sim) override {
        const double t = sim.time();
        Fluid fl;
        if (sim.has_fluid()) fl = fluid_state(sim);
        if (!pc_.grains()) {
            const Vec3& total = forces_.fluid_global();
            const double normal = forces_.fluid_normal();
            series_.row({t, total.x, total.y, total.z, normal, normal / weight_along_,
                         forces_.take_interval_peak(), state_.non_retained, fl.front, fl.drift, fl.speed,
                         fl.interface, fl.at_min, fl.at_max, state_.left[0] + state_.left[1] + state_.left[2],
                         fluid_behind_fraction(0)});
        } else {
            const dem::GrainView grains = sim.grain_view();  // every rank: a collective call when divided
            outflow_.sample(sim.domain());
            // the grains that went over the side walls count in the whole (neither retained nor passed),
            // those that left at an open end passed
            solid_non_retained_ = analysis::non_retained_fraction(
                grains.particles, pc_.scene.barrier, outflow_.spilled_mass_kg(), outflow_.left_end_mass_kg());
            const auto ke = grains.kinetic_energy();
            const double n = forces_.normal(), ns = forces_.solid_normal(), nf = forces_.fluid_normal();
            const Vec3& g = forces_.global();
            const double nan = io::not_a_number;
            const bool wet = sim.has_fluid();
            series_.row({t,
                         n,
                         ns,
                         nf,
                         n / weight_along_,
                         ns / weight_along_,
                         nf / weight_along_,
                         g.x,
                         g.y,
                         g.z,
                         forces_.take_interval_peak(),
                         solid_non_retained_,
                         wet ? state_.non_retained : nan,
                         ke.translational + ke.rotational,
                         wet ? fl.front : nan,
                         wet ? fl.drift : nan,
                         wet ? fl.speed : nan,
                         wet ? fl.interface : nan,
                         wet ? fl.at_min : nan,
                         wet ? fl.at_max : nan,
                         wet ? state_.left[0] + state_.left[1] + state_.left[2] : nan,
                         solid_mass_kg() > 0.0 ? outflow_.over_crest_kg() / solid_mass_kg() : 0.0,
                         wet ? fluid_behind_fraction(0) : nan});
        }
        if (sim.has_fluid()) lbm::check_fluid_stable(t, fl.drift, fl.lattice_speed, pc_.fluid.max_mass_drift);
        return false;
    }

  private:
    static std::vector<std::string> series_columns(bool grains) {
        std::vector<std::string> columns =
            grains ? std::vector<std::string>{"time_s",
                                              "force_normal_N",
                                              "solid_force_normal_N",
                                              "fluid_force_normal_N",
                                              "force_normal_over_W_sin_theta",
                                              "solid_force_normal_over_W_sin_theta",
                                              "fluid_force_normal_over_W_sin_theta",
                                              "force_x_N",
                                              "force_y_N",
                                              "force_z_N",
                                              "force_peak_N",
                                              "solid_non_retained_fraction",
                                              "fluid_non_retained_fraction",
                                              "grain_kinetic_energy_J"}
                   : std::vector<std::string>{"time_s",
                                              "fluid_force_x_N",
                                              "fluid_force_y_N",
                                              "fluid_force_z_N",
                                              "fluid_force_normal_N",
                                              "fluid_force_normal_over_W_sin_theta",
                                              "fluid_force_peak_N",
                                              "fluid_non_retained_fraction"};
        // the fluid's front and health close both, then what left an open channel
        for (const char* c : {"front_x_m", "mass_relative_drift", "max_speed_m_s", "interface_cells",
                              "tau_min_cells", "tau_max_cells", "fluid_left_domain_fraction"})
            columns.emplace_back(c);
        if (grains) columns.emplace_back("solid_over_crest_fraction");
        columns.emplace_back("fluid_over_crest_fraction");
        return columns;
    }
    struct Fluid {
        double front = 0.0, drift = 0.0, speed = 0.0, lattice_speed = 0.0;
        double interface = 0.0, at_min = 0.0, at_max = 0.0;
    };
    // The fluid's force on each barrier element in the last lattice step, N.
    void fluid_forces(sim::Simulation& sim) {
        const double force_unit = pc_.fluid.units.force_si(1.0);
        const std::span<const Vec3> f = sim.fluid_element_forces();
        for (std::size_t e = 0; e < fluid_on_element_.size(); ++e)
            fluid_on_element_[e] = f[e + 1] * force_unit;
    }
    // The lattice's mass, largest speed, the fluid downstream of the barrier (the fluid in grain cells moves
    // with its grain and counts as neither) and the front: sums made where the lattice is (on a device
    // there; sim::Simulation::set_fluid_region holds the barrier's downstream side).
    Fluid fluid_state(sim::Simulation& sim) {
        const parallel::Domain& d = sim.domain();
        Fluid out;
        const lbm::FluidSummary& l = sim.fluid_summary();
        double downstream = l.region_mass, all = l.free_mass;
        const double front = l.front_x < 0 ? 0.0 : d.cell_centre(l.first_x + l.front_x, 0, 0).x + 0.5 * d.dx;
        const int top = l.top_z;  // the highest cell plane holding a tenth of fluid
        // a divided run's: over every rank's own planes (its clamp counts include the ghost planes)
        all = d.sum(all);
        downstream = d.sum(downstream);
        // what left an open channel: through its end it passed the barrier; over the side walls or through
        // the top it left the channel (neither retained nor passed)
        std::array<double, 3> drained{};
        for (std::size_t o = 0; o < drained.size(); ++o) {
            drained[o] = d.sum(l.drained[o]);
            state_.left[o] = drained[o] / state_.m0;
        }
        const double end = drained[static_cast<std::size_t>(scenario::DebrisOutlet::end)];
        const double gone = drained[0] + drained[1] + drained[2];
        state_.non_retained = all + gone > 0.0 ? (downstream + end) / (all + gone) : 0.0;
        for (std::size_t part = 0; part < state_.behind.size(); ++part)
            state_.behind[part] = all + gone > 0.0 ? d.sum(l.region_inflow[part]) / (all + gone) : 0.0;
        out.drift = (d.sum(l.totals.mass) + gone - state_.m0) / state_.m0;
        state_.worst_drift = std::max(state_.worst_drift, std::abs(out.drift));
        out.front = d.max(front);
        const double height = d.max((top + 1) * d.dx);
        state_.max_height = std::max(state_.max_height, height);
        if (!state_.top_reached && height >= (l.nz - 1) * d.dx) {
            state_.top_reached = true;
            if (pc_.scene.bounds.top == scenario::ChannelTop::open)
                spdlog::warn(
                    "t = {:.3f} s: the fluid reached the top of the domain ({:.3g} m, "
                    "channel.domain_height_m) "
                    "and leaves there: the run-up above it is lost (its share: fluid_left_top_fraction in "
                    "summary.json); raise channel.domain_height_m if that is more than a trace",
                    sim.time(), l.nz * d.dx);
            else
                spdlog::warn(
                    "t = {:.3f} s: the fluid reached the lid ({:.3g} m, channel.top = \"lid\"), which turns "
                    "the run-up back onto the flow: a real barrier has no lid (channel.top = \"open\")",
                    sim.time(), l.nz * d.dx);
        }
        out.lattice_speed = d.max(l.totals.max_speed);
        out.speed = pc_.fluid.units.velocity_si(out.lattice_speed);
        out.interface = d.sum(static_cast<double>(l.interface_cells));
        out.at_min = d.sum(static_cast<double>(l.clamps.at_min));
        out.at_max = d.sum(static_cast<double>(l.clamps.at_max));
        return out;
    }

    // A mesh barrier's triangles at the steps the force maps are taken (every rank alike: collective): the
    // grains' contacts and the fluid's last lattice step (held over the grains' sub-steps, as its elements'
    // forces are).
    void take_facet_maps(const sim::Simulation& sim, double time, bool end) {
        const auto& mesh = pc_.scene.barrier.mesh;
        if (!mesh) return;
        facets_.take(forces_, time, end, [&](std::vector<Vec3>& grains, std::vector<Vec3>& fluid) {
            if (pc_.grains()) sim.triangle_forces(*mesh, grains);
            if (!sim.has_fluid()) return;
            sim.fluid_triangle_forces(*mesh, element_part_, fluid);
            const double force_unit = pc_.fluid.units.force_si(1.0);
            for (Vec3& f : fluid) f *= force_unit;
        });
    }
    // Each barrier element's mesh part (the lattice's element e + 1 is the barrier's element e).
    [[nodiscard]] static std::vector<std::size_t> element_parts(const scenario::BarrierInfo& barrier) {
        std::vector<std::size_t> parts;
        for (const auto& el : barrier.elements) parts.push_back(el.part);
        return parts;
    }
    // The barrier's forces are recorded every DEM step with grains, every lattice step without.
    [[nodiscard]] static double recording_dt(const PreparedDebris& pc) {
        return pc.grains() ? pc.dem->dt : pc.fluid.units.dt();
    }

    const PreparedDebris& pc_;
    double weight_along_;
    analysis::BarrierForceMonitor forces_;
    analysis::FacetMaps facets_;  // a mesh barrier's triangles
    GrainOutflow outflow_;
    std::vector<Vec3> fluid_on_element_;
    const std::vector<std::size_t> element_part_;  // each barrier element's mesh part (a mesh barrier's)
    std::array<analysis::MovingAverage, 3> normal_means_;
    io::CsvSeries series_;
    State state_;
    double solid_non_retained_ = 0.0;
    const InflowObserver* fed_ = nullptr;  // feed_from()
};

}  // namespace sabo::cases
