// SPDX-License-Identifier: MIT
#include "app/commands.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>

#include "core/config.h"
#include "core/error.h"
#include "core/log.h"
#include "dem/dem_setup.h"
#include "io/atomic_file.h"
#include "io/run_output.h"
#include "sabo/version.h"
#include "scenario/channel_case.h"

namespace sabo::app {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_signal(int sig) {
    g_stop_signal = sig;
}

// Everything a run needs, read and validated from the case file.
struct PreparedCase {
    scenario::ChannelCase scene;
    dem::DemSettings dem;
    double frame_interval = 0.0;
    double series_interval = 0.0;
    double progress_interval = 0.0;
    std::filesystem::path out_dir;
};

double available_memory_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    double kb = 0.0;
    std::string unit;
    while (in >> key >> kb >> unit) {
        if (key == "MemAvailable:") return kb * 1024.0;
    }
    return 1e300;
}

// Bytes per mobile grain: state (5 vectors + 4 scalars), ~10 list partners with their history and
// force slots, a few wall candidates, and the previous lists kept for history transfer.
constexpr double bytes_per_grain_estimate =
    5 * 24 + 4 * 8 + 10 * (4 + 4 + 32 + 48) * 2 + 4 * (2 + 32 + 24) * 2;

PreparedCase prepare(const CaseRequest& req, const Config& cfg) {
    PreparedCase pc;
    (void)cfg.choice_or("case.type", "channel", {"channel"});  // more case types come with later issues
    pc.scene = scenario::build_channel_case(cfg);
    const auto& rel = pc.scene.release;
    if (pc.scene.barrier.type != "none" && rel.hi.x > pc.scene.barrier.face_x - 0.01) {
        cfg.fail("release.front_x_m",
                 fmt::format("the released block (front at X = {:.3f} m) reaches the barrier face "
                             "(X = {:.3f} m)",
                             rel.hi.x, pc.scene.barrier.face_x));
    }
    pc.dem = dem::read_dem_settings(cfg, {rel.r_min, rel.r_max, rel.density, pc.scene.velocity_scale});
    const double end = pc.scene.end_time;
    pc.frame_interval = cfg.real_or("output.frame_interval_s", end / 50.0, Range::positive());
    pc.series_interval =
        cfg.real_or("output.series_interval_s", std::min(0.01, end / 100.0), Range::positive());
    pc.progress_interval = cfg.real_or("output.progress_interval_wall_s", 5.0, Range::positive());
    pc.out_dir =
        req.out_dir ? *req.out_dir : std::filesystem::path(cfg.text_or("output.dir", "out/" + pc.scene.name));
    if (pc.series_interval < pc.dem.dt) {
        cfg.fail("output.series_interval_s",
                 fmt::format("must be at least the time step {:.4g} s", pc.dem.dt));
    }
    cfg.record("derived.particles", static_cast<std::int64_t>(rel.count));
    cfg.record("derived.solid_volume_m3", rel.solid_volume);
    cfg.record("derived.barrier_spheres", static_cast<std::int64_t>(pc.scene.barrier.sphere_count));
    cfg.record("derived.velocity_scale_m_s", pc.scene.velocity_scale);
    cfg.finish();

    const double need = bytes_per_grain_estimate * static_cast<double>(pc.scene.particles.size());
    const double have = available_memory_bytes();
    if (need > 0.8 * have) {
        throw InputError(
            fmt::format("{}: the run needs about {:.1f} GiB but only {:.1f} GiB of memory is available",
                        cfg.source(), need / 1073741824.0, have / 1073741824.0));
    }
    return pc;
}

void print_derived(const PreparedCase& pc) {
    const auto& s = pc.scene;
    const auto& d = pc.dem;
    spdlog::info("case '{}': channel {:.2f} x {:.2f} x {:.2f} m, slope {:.1f} deg", s.name, s.length, s.width,
                 s.height, s.slope_deg);
    spdlog::info(
        "release: {} grains, V_s = {:.4f} m3, r in [{:.4f}, {:.4f}] m, extents X [{:.3f}, {:.3f}] "
        "Y [{:.3f}, {:.3f}] Z [{:.3f}, {:.3f}] m",
        s.release.count, s.release.solid_volume, s.release.r_min, s.release.r_max, s.release.lo.x,
        s.release.hi.x, s.release.lo.y, s.release.hi.y, s.release.lo.z, s.release.hi.z);
    spdlog::info("release lattice rule: {}", s.release.lattice_rule);
    if (s.barrier.type != "none") {
        spdlog::info(
            "barrier: {} {}, {} model, face X = {:.3f} m, outlet {:.3f} m, {} fixed spheres, {} boxes",
            s.barrier.type, s.barrier.orientation, s.barrier.model, s.barrier.face_x, s.barrier.outlet_width,
            s.barrier.sphere_count, s.barrier.wall_count);
    }
    spdlog::info(
        "contact: {} normal law, restitution zeta = {:.3f}, effective e (attractive force clipped) = {:.4f}",
        d.normal_model, d.restitution, d.effective_restitution);
    spdlog::info("time step: t_c = {:.4e} s, dt = {:.4e} s, dt/t_c = 1/{:.1f}; {:.0f} steps to t = {:.3g} s",
                 d.contact_time, d.dt, d.steps_per_contact, std::ceil(s.end_time / d.dt), s.end_time);
    spdlog::info("expected max overlap (grain at {:.2f} m/s on a fixed one): {:.2f} % of d_min (aim < 2 %)",
                 s.velocity_scale, 100.0 * d.expected_max_overlap_ratio);
    spdlog::info("memory estimate: {:.1f} MiB ({} spheres incl. fixed); neighbour skin {:.4f} m",
                 bytes_per_grain_estimate * static_cast<double>(s.particles.size()) / 1048576.0,
                 s.particles.size(), d.skin);
}

std::string format_duration(double seconds) {
    const auto s = static_cast<long>(std::max(0.0, seconds));
    return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

Vec3 barrier_force(const dem::DemSolver& solver, const scenario::BarrierInfo& b) {
    Vec3 f{};
    for (std::size_t w = b.first_wall; w < b.first_wall + b.wall_count; ++w) f += solver.wall_forces()[w];
    const auto& forces = solver.forces();  // every step: must not synchronise the velocities
    for (std::size_t i = solver.mobile_count(); i < forces.size(); ++i) f += forces[i];
    return f;
}

void configure_threads(int threads) {
    if (threads > 0) omp_set_num_threads(threads);
}

}  // namespace

int check_case(const CaseRequest& req) {
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    const PreparedCase pc = prepare(req, cfg);
    print_derived(pc);
    spdlog::info("check passed: {} is valid (nothing was run)", req.case_file.string());
    return 0;
}

int run_case(const CaseRequest& req) {
    configure_threads(req.threads);
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    PreparedCase pc = prepare(req, cfg);
    std::filesystem::create_directories(pc.out_dir);
    add_log_file(pc.out_dir / "sabo.log");
    spdlog::info("sabo {} — {} — {} threads — output in {}", version_string, req.case_file.string(),
                 omp_get_max_threads(), pc.out_dir.string());
    print_derived(pc);
    io::write_text_atomically(pc.out_dir / "case_resolved.toml", cfg.resolved_toml());

    const auto& scene = pc.scene;
    dem::DemSolver solver(scene.particles, scene.walls, pc.dem.laws, scene.gravity, pc.dem.dt, pc.dem.skin);
    solver.set_rolling_sweeps(pc.dem.rolling_sweeps);
    io::FrameWriter frames(pc.out_dir);
    io::CsvSeries series(pc.out_dir / "series.csv",
                         {"time_s", "kinetic_energy_translational_J", "kinetic_energy_rotational_J",
                          "elastic_energy_J", "max_overlap_over_d", "contacts", "sliding_fraction",
                          "barrier_force_x_N", "barrier_force_y_N", "barrier_force_z_N"});

    g_stop_signal = 0;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);

    const auto wall_start = std::chrono::steady_clock::now();
    auto last_progress = wall_start;
    const auto total_steps = static_cast<std::uint64_t>(std::ceil(scene.end_time / pc.dem.dt - 1e-9));
    const auto series_every = std::max<std::uint64_t>(1, std::llround(pc.series_interval / pc.dem.dt));
    const auto frame_every = std::max<std::uint64_t>(1, std::llround(pc.frame_interval / pc.dem.dt));
    double max_barrier_force = 0.0, time_of_max_barrier_force = 0.0;

    auto record_series = [&] {
        const auto ke = solver.kinetic_energy();
        const auto& st = solver.stats();
        const Vec3 fb = barrier_force(solver, scene.barrier);
        series.row(
            {solver.time(), ke.translational, ke.rotational, solver.elastic_energy(), st.max_overlap_ratio,
             static_cast<double>(st.contacts),
             st.contacts > 0 ? static_cast<double>(st.sliding) / static_cast<double>(st.contacts) : 0.0, fb.x,
             fb.y, fb.z});
    };
    record_series();
    frames.write(solver);
    int exit_code = 0;
    std::string failure;
    try {
        while (solver.steps() < total_steps) {
            solver.step();
            // the barrier-force peak is tracked every step: output decimation never hides it
            const double fb = norm(barrier_force(solver, scene.barrier));
            if (fb > max_barrier_force) {
                max_barrier_force = fb;
                time_of_max_barrier_force = solver.time();
            }
            if (solver.steps() % series_every == 0) record_series();
            if (solver.steps() % frame_every == 0) frames.write(solver);
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
                        "ETA {}",
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
    if (solver.steps() % series_every != 0) record_series();
    if (solver.steps() % frame_every != 0) frames.write(solver);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    const auto ke = solver.kinetic_energy();
    const std::string status = exit_code == 0 ? "completed" : (exit_code == 130 ? "interrupted" : "failed");
    io::write_text_atomically(
        pc.out_dir / "summary.json",
        fmt::format(R"({{
  "sabo_version": "{}",
  "case": "{}",
  "status": "{}",
  "failure": "{}",
  "simulated_time_s": {:.9g},
  "steps": {},
  "dt_s": {:.9g},
  "threads": {},
  "particles": {},
  "solid_volume_m3": {:.9g},
  "final_kinetic_energy_J": {:.9g},
  "max_overlap_over_d": {:.9g},
  "max_global_force_N": {:.9g},
  "time_of_max_global_force_s": {:.9g},
  "neighbor_list_builds": {},
  "wall_time_s": {:.6g},
  "particle_steps_per_s": {:.6g}
}}
)",
                    version_string, scene.name, status, failure, solver.time(), solver.steps(), pc.dem.dt,
                    omp_get_max_threads(), scene.release.count, scene.release.solid_volume,
                    ke.translational + ke.rotational, solver.max_overlap_ratio_seen(), max_barrier_force,
                    time_of_max_barrier_force, solver.list_builds(), wall,
                    static_cast<double>(solver.steps()) * static_cast<double>(scene.release.count) / wall));
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {} ({:.3g} particle-steps/s); max overlap {:.2f} % of d; "
        "max barrier force {:.4g} N at t = {:.4f} s",
        status, solver.time(), solver.steps(), format_duration(wall),
        static_cast<double>(solver.steps()) * static_cast<double>(scene.release.count) / wall,
        100.0 * solver.max_overlap_ratio_seen(), max_barrier_force, time_of_max_barrier_force);
    if (solver.max_overlap_ratio_seen() > 0.02) {
        spdlog::warn(
            "max overlap {:.2f} % of a diameter exceeded the recommended 2 % (stiffer contacts or smaller "
            "impact speeds)",
            100.0 * solver.max_overlap_ratio_seen());
    }
    return exit_code;
}

}  // namespace sabo::app
