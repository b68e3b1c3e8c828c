// SPDX-License-Identifier: MIT
// `sabo run` for channel cases: the time loop with the barrier analyses of SPEC §3 computed during
// the run (forces every step, flow measures and arching at every series sample), stop detection,
// and the outputs of docs/outputs.md.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <limits>
#include <numbers>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "analysis/flow_measures.h"
#include "analysis/stop_detector.h"
#include "app/case_setup.h"
#include "app/commands.h"
#include "app/report_script.h"
#include "core/error.h"
#include "core/log.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "sabo/version.h"

namespace sabo::app {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_signal(int sig) {
    g_stop_signal = sig;
}

std::string format_duration(double seconds) {
    const auto s = static_cast<long>(std::max(0.0, seconds));
    return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Flow state in the reach upstream of the barrier at the step of the largest normal force.
struct PeakFlow {
    double time = nan;
    analysis::UpstreamFlow flow;
};

// The per-run analysis state and the series it writes.
class ChannelAnalysis {
  public:
    ChannelAnalysis(const PreparedCase& pc)
        : pc_(pc),
          barrier_(pc.scene.barrier),
          forces_(barrier_),
          arching_(barrier_, pc.analysis.arching_depth, pc.analysis.arching_intervals,
                   pc.analysis.arching_threshold),
          stop_(pc.analysis.stop_threshold, pc.analysis.stop_hold),
          series_(pc.out_dir / "series.csv", series_columns()),
          piles_(pc.out_dir / "barrier_piles.csv", pile_columns(barrier_.piles.size())) {}

    // Every step: barrier forces (peaks are never decimated) and, at a new peak of the normal force,
    // the upstream flow for k_st and k_dyn.
    void after_step(const dem::DemSolver& solver) {
        if (!barrier_.present()) return;
        forces_.record(solver.time(), solver.forces(), solver.wall_forces());
        if (forces_.new_normal_peak()) {
            peak_flow_ = {solver.time(),
                          analysis::upstream_flow(solver.particles(), barrier_, pc_.scene.width,
                                                  pc_.analysis.upstream_reach)};
        }
    }

    // A series sample; returns true when the complete stop is reached.
    bool sample(const dem::DemSolver& solver) {
        const auto ke = solver.kinetic_energy();
        const auto& p = solver.particles();
        const auto& st = solver.stats();
        const double t = solver.time();
        double non_retained = 0.0;
        analysis::DownstreamEnergy down;
        // without a barrier, "downstream" is past the plane X = barrier.face_x_m (the reference run)
        non_retained = analysis::non_retained_fraction(p, barrier_);
        down = analysis::downstream_energy(p, barrier_);
        if (barrier_.present()) arching_.sample(t, p);
        last_non_retained_ = non_retained;
        const Vec3 fg = forces_.global();
        series_.row(
            {t, ke.translational, ke.rotational, solver.elastic_energy(), st.max_overlap_ratio,
             static_cast<double>(st.contacts),
             st.contacts > 0 ? static_cast<double>(st.sliding) / static_cast<double>(st.contacts) : 0.0, fg.x,
             fg.y, fg.z, forces_.normal(), forces_.tangential(), forces_.resultant(),
             forces_.take_interval_peak(), non_retained, down.mean_J, static_cast<double>(down.grains)});
        std::vector<double> row{t};
        for (const auto& pl : forces_.piles()) row.push_back(pl.normal), row.push_back(pl.moment);
        piles_.row(row);
        return pc_.analysis.stop_enabled && stop_.sample(t, ke.translational + ke.rotational);
    }

    void finish(const dem::DemSolver& solver) {
        if (!barrier_.present()) return;
        forces_.finish(solver.time());
        io::write_force_maps(pc_.out_dir, barrier_, forces_);
        io::write_arching(pc_.out_dir, arching_, forces_.first_impact_time());
    }

    // The analysis keys of summary.json (docs/outputs.md).
    void summarise(io::JsonObject& js) const {
        js.number("non_retained_fraction", last_non_retained_);
        js.number("stop_detected_at_s", stopped_at_);
        if (!barrier_.present()) return;
        const double t0 = forces_.first_impact_time();
        js.number("first_impact_time_s", t0);
        js.number("max_global_force_N", forces_.max_global());
        js.number("time_of_max_global_force_s", forces_.map_t3().time);
        js.number("max_local_force_N", forces_.max_local());
        js.number("time_of_max_local_force_s", forces_.map_t2().time);
        js.number("max_normal_force_N", forces_.max_normal());
        js.number("time_of_max_normal_force_s", forces_.time_of_max_normal());
        const double f_static = forces_.resultant();
        js.number("static_global_force_N", f_static);
        js.number("static_normal_force_N", forces_.normal());
        js.number("max_over_static_global_force", f_static > 0.0 ? forces_.max_global() / f_static : nan);
        // design coefficients per metre of barrier width, from the peak normal force
        const double w = pc_.scene.width, rho = pc_.scene.release.density, g = norm(pc_.scene.gravity);
        const double fpw = forces_.max_normal() / w;
        js.number("upstream_flow_height_at_peak_m", peak_flow_.flow.height);
        js.number("upstream_flow_velocity_at_peak_m_s", peak_flow_.flow.velocity);
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
                .number("static_normal_force_N", pl.normal);
            piles.push_back(o);
        }
        js.objects("piles", piles);
        std::vector<io::JsonObject> outlets;
        std::vector<std::string> labels;
        double best_ratio = 0.0, arch_stop = nan;
        for (const auto& o : arching_.outlets()) {
            const std::string label = analysis::classify_clogging(o, t0, last_non_retained_);
            labels.push_back(label);
            const double ratio = o.arch_height_ratio(barrier_.height), ts = o.arch_stop_time();
            if (ratio > best_ratio) best_ratio = ratio, arch_stop = ts;
            io::JsonObject jo;
            jo.number("y_lo_m", o.outlet.lo)
                .number("y_hi_m", o.outlet.hi)
                .number("arch_height_ratio", ratio)
                .number("t_stop_s", ts >= 0.0 ? ts : nan)
                .number("t_stop_minus_t0_s", ts >= 0.0 ? ts - t0 : nan)
                .integer("halted_intervals", o.halted_count())
                .text("clogging_mechanism", label);
            outlets.push_back(jo);
        }
        js.objects("outlets", outlets);
        js.number("arch_height_ratio", best_ratio);
        js.number("t_stop_minus_t0_s", std::isfinite(arch_stop) && arch_stop >= 0.0 ? arch_stop - t0 : nan);
        js.text("clogging_mechanism",
                barrier_.outlets.empty() ? "closed barrier" : analysis::classify_run(labels));
    }

    void set_stopped_at(double t) { stopped_at_ = t; }

  private:
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
                "downstream_grains"};
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
    const scenario::BarrierInfo& barrier_;
    analysis::BarrierForceMonitor forces_;
    analysis::ArchingMonitor arching_;
    analysis::StopDetector stop_;
    io::CsvSeries series_, piles_;
    PeakFlow peak_flow_;
    double last_non_retained_ = 0.0;
    double stopped_at_ = nan;
};

// "Highly-compacted" preparation (CASES C4): the block is discharged against a temporary closed
// barrier just in front of it (a plane 5 mm ahead of the block front) and left to settle — until the
// complete-stop criterion holds or release.settle_max_time_s — then that barrier is removed and the
// run starts (t = 0) from the settled state at rest.
dem::Particles presettle(const PreparedCase& pc) {
    const auto& scene = pc.scene;
    std::vector<dem::Wall> walls = scene.walls;
    walls.push_back(dem::Wall::plane("temporary_barrier", {scene.release.hi.x + 0.005, 0, 0}, {-1, 0, 0}));
    dem::DemSolver solver(scene.particles, walls, pc.dem.laws, scene.gravity, pc.dem.dt, pc.dem.skin);
    solver.set_rolling_sweeps(pc.dem.rolling_sweeps);
    solver.set_reorder_interval(pc.dem.reorder_interval);
    analysis::StopDetector stop(pc.analysis.stop_threshold, pc.analysis.stop_hold);
    const auto every = std::max<std::uint64_t>(1, std::llround(pc.series_interval / pc.dem.dt));
    spdlog::info("high compaction: settling the block against a temporary barrier at X = {:.3f} m",
                 scene.release.hi.x + 0.005);
    bool settled = false;
    while (solver.time() < scene.release.settle_max_time && !settled) {
        solver.step();
        if (solver.steps() % every == 0) {
            const auto ke = solver.kinetic_energy();
            settled = stop.sample(solver.time(), ke.translational + ke.rotational);
        }
    }
    dem::Particles p = solver.particles();
    for (std::size_t i = 0; i < p.n_mobile; ++i) p.v[i] = p.w[i] = {};
    double front = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) front = std::max(front, p.x[i].x + p.r[i]);
    if (settled) {
        spdlog::info("high compaction: settled after {:.2f} s; block front at X = {:.3f} m; barrier removed",
                     solver.time(), front);
    } else {
        spdlog::warn(
            "high compaction: not at rest after release.settle_max_time_s = {:.3g} s; starting anyway",
            scene.release.settle_max_time);
    }
    return p;
}

// Volume fraction of large grains in slabs of the deposit (CASES C4): slabs 25 cm long in X going
// upstream from the barrier face, three height bands over H_bar; retained grains only.
void write_deposit_composition(const std::filesystem::path& dir, const scenario::ChannelCase& scene,
                               const dem::Particles& p) {
    const auto& b = scene.barrier;
    const double split = 0.5 * (scene.release.r_large + scene.release.r_small), slab = 0.25;
    const double band = scene.height / 3.0;
    const int n_slabs = static_cast<int>(std::ceil(b.face_x / slab));
    std::vector<double> large(static_cast<std::size_t>(n_slabs) * 3, 0.0), total(large.size(), 0.0);
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const double d = b.upstream_distance(p.x[i]);
        if (d < 0.0) continue;
        const int k = std::min(n_slabs - 1, static_cast<int>(d / slab));
        const int z = std::clamp(static_cast<int>(p.x[i].z / band), 0, 2);
        const double v = 4.0 / 3.0 * std::numbers::pi * p.r[i] * p.r[i] * p.r[i];
        const auto cell = static_cast<std::size_t>(k) * 3 + static_cast<std::size_t>(z);
        total[cell] += v;
        if (p.r[i] > split) large[cell] += v;
    }
    std::string csv =
        "upstream_from_m,upstream_to_m,z_lo_m,z_hi_m,volume_large_m3,volume_total_m3,large_fraction\n";
    for (int k = 0; k < n_slabs; ++k) {
        for (int z = 0; z < 3; ++z) {
            const auto cell = static_cast<std::size_t>(k) * 3 + static_cast<std::size_t>(z);
            if (total[cell] <= 0.0) continue;
            csv += fmt::format("{:.3f},{:.3f},{:.3f},{:.3f},{:.6g},{:.6g},{:.6g}\n", k * slab, (k + 1) * slab,
                               z * band, (z + 1) * band, large[cell], total[cell], large[cell] / total[cell]);
        }
    }
    io::write_text_atomically(dir / "deposit_composition.csv", csv);
}

}  // namespace

int run_case(const CaseRequest& req) {
    if (req.threads > 0) omp_set_num_threads(req.threads);
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    PreparedCase pc = prepare(req, cfg);
    std::filesystem::create_directories(pc.out_dir);
    add_log_file(pc.out_dir / "sabo.log");
    spdlog::info("sabo {} — {} — {} threads — output in {}", version_string, req.case_file.string(),
                 omp_get_max_threads(), pc.out_dir.string());
    print_derived(pc);
    io::write_text_atomically(pc.out_dir / "case_resolved.toml", cfg.resolved_toml());

    const auto& scene = pc.scene;
    const dem::Particles start = scene.release.compaction == "high" ? presettle(pc) : scene.particles;
    dem::DemSolver solver(start, scene.walls, pc.dem.laws, scene.gravity, pc.dem.dt, pc.dem.skin);
    solver.set_rolling_sweeps(pc.dem.rolling_sweeps);
    solver.set_reorder_interval(pc.dem.reorder_interval);
    io::FrameWriter frames(pc.out_dir);
    ChannelAnalysis analysis(pc);

    g_stop_signal = 0;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);

    const auto wall_start = std::chrono::steady_clock::now();
    auto last_progress = wall_start;
    const auto total_steps = static_cast<std::uint64_t>(std::ceil(scene.end_time / pc.dem.dt - 1e-9));
    const auto series_every = std::max<std::uint64_t>(1, std::llround(pc.series_interval / pc.dem.dt));
    const auto frame_every = std::max<std::uint64_t>(1, std::llround(pc.frame_interval / pc.dem.dt));

    analysis.sample(solver);
    frames.write(solver);
    int exit_code = 0;
    std::string failure, ending = "end time";
    try {
        while (solver.steps() < total_steps) {
            solver.step();
            analysis.after_step(solver);
            if (solver.steps() % frame_every == 0) frames.write(solver);
            if (solver.steps() % series_every == 0 && analysis.sample(solver)) {
                analysis.set_stopped_at(solver.time());
                ending = "complete stop";
                spdlog::info("complete stop at t = {:.3f} s (kinetic energy below {:.3g} J for {:.3g} s)",
                             solver.time(), pc.analysis.stop_threshold, pc.analysis.stop_hold);
                break;
            }
            if (g_stop_signal != 0) {
                spdlog::warn("signal {} received at t = {:.4f} s: writing outputs and stopping",
                             int(g_stop_signal), solver.time());
                exit_code = 130;
                break;
            }
            if ((solver.steps() & 63) == 0) {
                const auto now = std::chrono::steady_clock::now();
                if (std::chrono::duration<double>(now - last_progress).count() >= pc.progress_interval) {
                    last_progress = now;
                    const double elapsed = std::chrono::duration<double>(now - wall_start).count();
                    const double rate = static_cast<double>(solver.steps()) / elapsed;
                    spdlog::info(
                        "t = {:.3f} / {:.3f} s ({:4.1f} %)  {:.0f} steps/s  {:.3g} particle-steps/s  "
                        "ETA {} (at most: the run ends at complete stop)",
                        solver.time(), scene.end_time, 100.0 * solver.time() / scene.end_time, rate,
                        rate * static_cast<double>(scene.release.count),
                        format_duration(static_cast<double>(total_steps - solver.steps()) / rate));
                }
            }
        }
    } catch (const RunError& e) {
        failure = e.what();
        spdlog::error("{}", failure);
        exit_code = 3;
    }
    if (solver.steps() % series_every != 0) analysis.sample(solver);
    if (solver.steps() % frame_every != 0) frames.write(solver);
    analysis.finish(solver);
    if (scene.release.mixture == "bidisperse" && scene.barrier.present())
        write_deposit_composition(pc.out_dir, scene, solver.particles());

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const auto ke = solver.kinetic_energy();
    const std::string status = exit_code == 0 ? "completed" : (exit_code == 130 ? "interrupted" : "failed");
    const double rate = static_cast<double>(solver.steps()) * static_cast<double>(scene.release.count) / wall;
    io::JsonObject js;
    js.text("sabo_version", version_string)
        .text("case", scene.name)
        .text("status", status)
        .text("failure", failure)
        .text("ended_by", exit_code == 0 ? ending : status)
        .number("simulated_time_s", solver.time())
        .integer("steps", static_cast<std::int64_t>(solver.steps()))
        .number("dt_s", pc.dem.dt)
        .integer("threads", omp_get_max_threads())
        .integer("particles", static_cast<std::int64_t>(scene.release.count))
        .number("solid_volume_m3", scene.release.solid_volume)
        .text("mixture", scene.release.mixture)
        .text("compaction", scene.release.compaction)
        .number("phi_small", scene.release.mixture == "bidisperse" ? scene.release.phi_small : nan)
        .number("radius_large_m", scene.release.mixture == "bidisperse" ? scene.release.r_large : nan)
        .number("radius_small_m", scene.release.mixture == "bidisperse" ? scene.release.r_small : nan)
        .number("equivalent_radius_m", scene.release.equivalent_radius)
        .number("outlet_width_over_r_star", scene.barrier.outlet_width / scene.release.equivalent_radius)
        .number("slope_deg", scene.slope_deg)
        .text("barrier_type", scene.barrier.present() ? scene.barrier.type : "none")
        .text("barrier_orientation", scene.barrier.orientation)
        .text("barrier_model", scene.barrier.model)
        .text("barrier_configuration", scene.barrier.configuration)
        .number("outlet_width_m", scene.barrier.outlet_width)
        .number("outlet_width_over_r", scene.barrier.outlet_width / scene.release.r_mean)
        .number("pile_width_m", scene.barrier.pile_width)
        .integer("pile_count", static_cast<std::int64_t>(scene.barrier.piles.size()))
        .number("barrier_height_m", scene.barrier.height)
        .number("final_kinetic_energy_J", ke.translational + ke.rotational)
        .number("max_overlap_over_d", solver.max_overlap_ratio_seen());
    analysis.summarise(js);
    js.integer("neighbor_list_builds", static_cast<std::int64_t>(solver.list_builds()))
        .number("wall_time_s", wall)
        .number("particle_steps_per_s", rate);
    io::write_text_atomically(pc.out_dir / "summary.json", js.dump());
    spdlog::info("{} ({}): t = {:.4f} s, {} steps in {} ({:.3g} particle-steps/s); max overlap {:.2f} % of d",
                 status, exit_code == 0 ? ending : status, solver.time(), solver.steps(),
                 format_duration(wall), rate, 100.0 * solver.max_overlap_ratio_seen());
    if (solver.max_overlap_ratio_seen() > 0.02) {
        spdlog::warn(
            "max overlap {:.2f} % of a diameter exceeded the recommended 2 % (stiffer contacts or smaller "
            "impact speeds)",
            100.0 * solver.max_overlap_ratio_seen());
    }
    if (pc.report) run_report_script(pc.out_dir);
    return exit_code;
}

}  // namespace sabo::app
