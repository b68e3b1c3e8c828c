// SPDX-License-Identifier: MIT
// The barrier analyses of one channel run (docs/analysis.md) as an observer of the run: forces after
// every step, flow measures, arching and the complete stop at every series sample, the end-of-run
// outputs and the analysis keys of summary.json.
#pragma once
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <limits>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "analysis/facet_maps.h"
#include "analysis/flow_measures.h"
#include "analysis/force_balance.h"
#include "analysis/moving_average.h"
#include "analysis/stop_detector.h"
#include "cases/channel/channel_settings.h"
#include "cases/common/grain_outflow.h"
#include "dem/dem_solver.h"
#include "io/barrier_output.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "sim/observer.h"

namespace sabo::cases {

using io::not_a_number;

// Flow state in the reach upstream of the barrier at one step (the first impact, the largest normal force).
struct PeakFlow {
    double time = not_a_number;
    analysis::UpstreamFlow flow;
};

// The per-run analysis state and the series it writes.
class ChannelObserver final : public sim::Checkpointed<ChannelObserver> {
  public:
    // Divided among ranks (domain), every rank analyses every grain (sim.grain_view()); the first writes.
    explicit ChannelObserver(const PreparedCase& pc, const parallel::Domain& domain = {})
        : pc_(pc),
          writes_(domain.writes_outputs()),
          barrier_(pc.scene.barrier),
          forces_(barrier_),
          outflow_(pc.scene.bounds, pc.scene.length, pc.scene.width, barrier_),
          arching_(barrier_, pc.analysis.arching_depth, pc.analysis.arching_intervals,
                   pc.analysis.arching_threshold),
          stop_(pc.analysis.stop_threshold, pc.analysis.stop_hold),
          mass_(grain_mass(pc.scene.particles)),
          global_means_{analysis::MovingAverage(0.01, pc.dem.dt), analysis::MovingAverage(0.05, pc.dem.dt),
                        analysis::MovingAverage(0.1, pc.dem.dt)},
          series_(writes_ ? pc.output.out_dir / "series.csv" : std::filesystem::path(), series_columns()),
          piles_(writes_ ? pc.output.out_dir / "barrier_piles.csv" : std::filesystem::path(),
                 pile_columns(barrier_.piles.size())) {}

    // Every step: barrier forces (peaks are never decimated) and, at a new peak of the normal force,
    // the upstream flow for k_st and k_dyn.
    void after_grain_step(sim::Simulation& sim) override { outflow_.after_grain_step(sim); }
    void after_step(sim::Simulation& sim) override {
        outflow_.remove_exits(sim);
        if (!barrier_.present()) return;
        const dem::ContactForces f = sim.contact_forces();
        forces_.record(sim.time(), f.particles, f.walls);
        take_facet_maps(sim, false);
        for (auto& m : global_means_) m.add(sim.time(), forces_.resultant());
        if (std::isnan(arrival_.time) && !std::isnan(forces_.first_impact_time()))  // the front arrives
            arrival_ = upstream_now(sim);
        if (forces_.new_normal_peak()) peak_flow_ = upstream_now(sim);
    }

    // A series sample; returns true when the complete stop is reached.
    bool sample(sim::Simulation& sim) override {
        const dem::GrainView grains = sim.grain_view();
        const auto ke = grains.kinetic_energy();
        const auto& p = grains.particles;
        const auto& st = grains.stats;
        const double t = grains.time;
        // without a barrier, "downstream" is past the plane X = barrier.face_x_m (the reference run); the
        // grains that went over a side wall of an open top count in the whole, those past an open end as
        // passed
        outflow_.sample(sim.domain());
        // the grains' mass so far: those in the run and those that left it (an inflow adds to it)
        mass_ = outflow_.spilled_mass_kg() + outflow_.left_end_mass_kg();
        for (std::size_t i = 0; i < p.n_mobile; ++i) mass_ += p.m[i];
        const double non_retained = analysis::non_retained_fraction(p, barrier_, outflow_.spilled_mass_kg(),
                                                                    outflow_.left_end_mass_kg());
        const analysis::DownstreamEnergy down = analysis::downstream_energy(p, barrier_);
        if (barrier_.present()) arching_.sample(t, p);
        last_non_retained_ = non_retained;
        walls_ = analysis::wall_loads(grains.walls, grains.wall_forces);
        const Vec3 fg = forces_.global();
        series_.row(
            {t,
             ke.translational,
             ke.rotational,
             grains.elastic_energy,
             st.max_overlap_ratio,
             static_cast<double>(st.contacts),
             st.contacts > 0 ? static_cast<double>(st.sliding) / static_cast<double>(st.contacts) : 0.0,
             fg.x,
             fg.y,
             fg.z,
             forces_.normal(),
             forces_.tangential(),
             forces_.resultant(),
             forces_.take_interval_peak(),
             non_retained,
             down.mean_J,
             static_cast<double>(down.grains),
             walls_.bed_x,
             walls_.side_walls_x,
             walls_.other_x,
             mass_ > 0.0 ? outflow_.over_crest_kg() / mass_ : 0.0});
        std::vector<double> row{t};
        for (const auto& pl : forces_.piles()) row.push_back(pl.normal), row.push_back(pl.moment);
        piles_.row(row);
        if (!pc_.analysis.stop_enabled || t < pc_.analysis.stop_not_before ||
            !stop_.sample(t, ke.translational + ke.rotational))
            return false;
        stopped_at_ = t;
        spdlog::info("complete stop at t = {:.3f} s (kinetic energy below {:.3g} J for {:.3g} s)", t,
                     pc_.analysis.stop_threshold, pc_.analysis.stop_hold);
        return true;
    }

    [[nodiscard]] const analysis::BarrierForceMonitor& forces() const { return forces_; }
    [[nodiscard]] double non_retained() const { return last_non_retained_; }
    // The share of the grains' mass held upstream of the barrier at the last sample (neither passed nor gone
    // over a side wall).
    [[nodiscard]] double retained() const { return outflow_.retained(last_non_retained_, mass_); }
    // The run ended at complete stop: only then is the load at the end the deposit's static load.
    [[nodiscard]] bool deposit_at_rest() const { return !std::isnan(stopped_at_); }
    // The deposit in the reach upstream of the barrier at the end.
    [[nodiscard]] const analysis::UpstreamFlow& deposit() const { return deposit_; }

    // After the run: the force maps, the arching table and the deposit.
    void finish(const sim::Simulation& sim) {
        if (!barrier_.present()) return;
        deposit_ = upstream_now(sim).flow;
        forces_.finish(sim.time());
        take_facet_maps(sim, true);
        if (!writes_) return;
        io::write_force_maps(pc_.output.out_dir, barrier_, forces_);
        if (barrier_.mesh) io::write_facet_maps(pc_.output.out_dir, *barrier_.mesh, facets_, true, false);
        io::write_arching(pc_.output.out_dir, arching_, forces_.first_impact_time());
    }

    // The analysis keys of summary.json (docs/outputs.md).
    void summarise(io::JsonObject& js) const {
        js.number("non_retained_fraction", last_non_retained_);
        summarise_bounds(js, pc_.scene.bounds);
        outflow_.summarise(js, mass_);
        js.number("stop_detected_at_s", stopped_at_);
        if (!barrier_.present()) return;
        const double t0 = forces_.first_impact_time();
        js.number("first_impact_time_s", t0);
        js.number("max_global_force_N", forces_.max_global());
        js.number("time_of_max_global_force_s", forces_.map_t3().time);
        // the peak as a pulse: the largest mean of |F_G| over 0.01 s, 0.05 s and 0.1 s windows (window's end
        // time; 0.01 s is the averaging other codes' barrier-force outputs commonly use)
        for (const auto& m : global_means_) {
            const auto ms = static_cast<int>(std::lround(1000.0 * m.window()));
            js.number(fmt::format("max_global_force_mean_{}ms_N", ms), m.max_mean());
            js.number(fmt::format("time_of_max_global_force_mean_{}ms_s", ms), m.time_of_max_mean());
        }
        js.number("max_local_force_N", forces_.max_local());
        js.number("time_of_max_local_force_s", forces_.map_t2().time);
        js.number("max_normal_force_N", forces_.max_normal());
        js.number("time_of_max_normal_force_s", forces_.time_of_max_normal());
        // a run that reached its end time or was interrupted still moves: its end values are only that
        const bool at_rest = deposit_at_rest();
        const auto if_at_rest = [at_rest](double v) { return at_rest ? v : not_a_number; };
        js.boolean("deposit_at_rest", at_rest);
        const double f_end = forces_.resultant();
        const double peak_over_end = f_end > 0.0 ? forces_.max_global() / f_end : not_a_number;
        js.number("end_global_force_N", f_end);
        js.number("end_normal_force_N", forces_.normal());
        js.number("max_over_end_global_force", peak_over_end);
        js.number("static_global_force_N", if_at_rest(f_end));
        js.number("static_normal_force_N", if_at_rest(forces_.normal()));
        js.number("max_over_static_global_force", if_at_rest(peak_over_end));
        // where the retained deposit's down-slope weight goes at the end (docs/analysis.md, "Force balance")
        const double deposit_weight = retained() * mass_ * pc_.scene.gravity.x;
        const double end_x_share = deposit_weight > 0.0 ? forces_.global().x / deposit_weight : not_a_number;
        js.number("deposit_weight_x_N", deposit_weight);
        js.number("end_force_x_over_deposit_weight", end_x_share);
        js.number("static_force_x_over_deposit_weight", if_at_rest(end_x_share));
        js.number("end_bed_force_x_N", walls_.bed_x);
        js.number("end_side_walls_force_x_N", walls_.side_walls_x);
        js.number("end_other_walls_force_x_N", walls_.other_x);
        // design coefficients per metre of barrier width, from the peak normal force
        const double w = pc_.scene.width, rho = pc_.scene.release.density, g = norm(pc_.scene.gravity);
        const double fpw = forces_.max_normal() / w;
        js.number("upstream_flow_height_at_peak_m", peak_flow_.flow.height);
        js.number("upstream_flow_velocity_at_peak_m_s", peak_flow_.flow.velocity);
        js.number("upstream_solid_fraction_at_peak", peak_flow_.flow.solid_fraction);
        // the front as it reaches the barrier (first contact)
        js.number("upstream_flow_height_at_arrival_m", arrival_.flow.height);
        js.number("upstream_flow_velocity_at_arrival_m_s", arrival_.flow.velocity);
        js.number("upstream_solid_fraction_at_arrival", arrival_.flow.solid_fraction);
        js.number("k_st", analysis::k_static(fpw, rho, g, peak_flow_.flow.height));
        js.number("k_dyn", analysis::k_dynamic(fpw, rho, peak_flow_.flow.velocity, peak_flow_.flow.height));
        std::vector<io::JsonObject> piles;
        for (std::size_t k = 0; k < forces_.piles().size(); ++k) {
            const auto& pl = forces_.piles()[k];
            io::JsonObject o;
            o.integer("pile", static_cast<std::int64_t>(k))
                .number("y_lo_m", barrier_.piles[k].lo)
                .number("y_hi_m", barrier_.piles[k].hi)
                .number("max_normal_force_N", pl.max_normal)
                .number("time_of_max_normal_force_s", pl.time_of_max_normal)
                .number("max_basal_moment_N_m", pl.max_moment)
                .number("time_of_max_basal_moment_s", pl.time_of_max_moment)
                .number("end_normal_force_N", pl.normal)
                .number("static_normal_force_N", if_at_rest(pl.normal));
            piles.push_back(o);
        }
        js.objects("piles", piles);
        std::vector<io::JsonObject> outlets;
        std::vector<std::string> labels;
        double best_ratio = 0.0, arch_stop = not_a_number;
        for (const auto& o : arching_.outlets()) {
            const std::string label = analysis::classify_clogging(o, t0, last_non_retained_);
            labels.push_back(label);
            const double ratio = o.arch_height_ratio(barrier_.height), ts = o.arch_stop_time();
            if (ratio > best_ratio) best_ratio = ratio, arch_stop = ts;
            io::JsonObject jo;
            jo.number("y_lo_m", o.outlet.lo)
                .number("y_hi_m", o.outlet.hi)
                .number("arch_height_ratio", ratio)
                .number("t_stop_s", ts >= 0.0 ? ts : not_a_number)
                .number("t_stop_minus_t0_s", ts >= 0.0 ? ts - t0 : not_a_number)
                .integer("halted_intervals", o.halted_count())
                .text("clogging_mechanism", label);
            outlets.push_back(jo);
        }
        js.objects("outlets", outlets);
        js.number("arch_height_ratio", best_ratio);
        js.number("t_stop_minus_t0_s",
                  std::isfinite(arch_stop) && arch_stop >= 0.0 ? arch_stop - t0 : not_a_number);
        js.text("clogging_mechanism",
                barrier_.outlets.empty() ? "closed barrier" : analysis::classify_run(labels));
    }

    // Everything accumulated so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(forces_, arching_, stop_, global_means_[0], global_means_[1], global_means_[2], series_, piles_,
          peak_flow_, arrival_, last_non_retained_, walls_, stopped_at_, mass_, facets_);
        outflow_.transfer(a);  // (by its transfer: a byte copy would carry its reference to the barrier)
    }

  private:
    // A mesh barrier's triangles at the steps the force maps are taken (every rank alike: collective).
    void take_facet_maps(const sim::Simulation& sim, bool end) {
        if (!barrier_.mesh) return;
        facets_.take(forces_, sim.time(), end, [&](std::vector<Vec3>& grains, std::vector<Vec3>&) {
            sim.triangle_forces(*barrier_.mesh, grains);
        });
    }
    [[nodiscard]] PeakFlow upstream_now(const sim::Simulation& sim) const {
        const dem::GrainView grains = sim.grain_view();
        return {grains.time, analysis::upstream_flow(grains.particles, barrier_, pc_.scene.width,
                                                     pc_.analysis.upstream_reach)};
    }
    static double grain_mass(const dem::Particles& p) {
        double m = 0.0;
        for (std::size_t i = 0; i < p.n_mobile; ++i) m += p.m[i];
        return m;
    }
    static std::vector<std::string> series_columns() {
        return {"time_s",
                "kinetic_energy_translational_J",
                "kinetic_energy_rotational_J",
                "elastic_energy_J",
                "max_overlap_over_d",
                "contacts",
                "sliding_fraction",
                "barrier_force_x_N",
                "barrier_force_y_N",
                "barrier_force_z_N",
                "barrier_force_normal_N",
                "barrier_force_tangential_N",
                "barrier_force_resultant_N",
                "barrier_force_resultant_peak_N",
                "non_retained_fraction",
                "downstream_mean_kinetic_energy_J",
                "downstream_grains",
                "bed_force_x_N",
                "side_walls_force_x_N",
                "other_walls_force_x_N",
                "over_crest_fraction"};
    }
    static std::vector<std::string> pile_columns(std::size_t piles) {
        std::vector<std::string> c{"time_s"};
        for (std::size_t k = 0; k < piles; ++k) {
            c.push_back(fmt::format("pile_{}_normal_force_N", k));
            c.push_back(fmt::format("pile_{}_basal_moment_N_m", k));
        }
        return c;
    }

    const PreparedCase& pc_;
    bool writes_;  // this rank writes the files
    const scenario::BarrierInfo& barrier_;
    analysis::BarrierForceMonitor forces_;
    analysis::FacetMaps facets_;  // a mesh barrier's: the grains' force on each triangle at the maps' times
    GrainOutflow outflow_;
    analysis::ArchingMonitor arching_;
    analysis::StopDetector stop_;
    double mass_;  // of the grains so far (released, fed, and those that left), kg, at the last sample
    std::array<analysis::MovingAverage, 3> global_means_;  // |F_G| over 0.01 s, 0.05 s and 0.1 s
    io::CsvSeries series_, piles_;
    PeakFlow peak_flow_;
    PeakFlow arrival_;  // at the first impact
    double last_non_retained_ = 0.0;
    analysis::WallLoads walls_;  // at the last sample
    double stopped_at_ = not_a_number;
    analysis::UpstreamFlow deposit_;  // at the end
};

}  // namespace sabo::cases
