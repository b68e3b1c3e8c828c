// SPDX-License-Identifier: MIT
// `sabo run` for channel cases: the time loop with the barrier analyses of SPEC §3 computed during
// the run (forces every step, flow measures and arching at every series sample), stop detection,
// and the outputs of docs/outputs.md.
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "app/case_setup.h"
#include "app/channel_analysis.h"
#include "app/commands.h"
#include "app/dam_break_run.h"
#include "app/debris_run.h"
#include "app/high_compaction.h"
#include "app/report_script.h"
#include "app/run_control.h"
#include "app/sandpile_run.h"
#include "core/error.h"
#include "core/log.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "sabo/version.h"

namespace sabo::app {

int run_case(const CaseRequest& req) {
    if (req.threads > 0) omp_set_num_threads(req.threads);
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    if (req.resume && case_type(cfg) != "debris")
        throw InputError(
            fmt::format("{}: --resume: only debris runs (case.type = \"debris\") write checkpoints",
                        req.case_file.string()));
    if (case_type(cfg) == "sandpile") return run_sandpile(req, cfg);
    if (case_type(cfg) == "dam_break") return run_dam_break(req, cfg);
    if (case_type(cfg) == "debris") return run_debris(req, cfg);
    PreparedCase pc = prepare(req, cfg);
    open_run_folder(pc.out_dir, req.case_file, cfg);
    print_derived(pc);

    const auto& scene = pc.scene;
    const dem::Particles start = scene.release.compaction == "high" ? presettle(pc) : scene.particles;
    dem::DemSolver solver = dem::make_solver(start, scene.walls, scene.gravity, pc.dem);
    io::FrameWriter frames(pc.out_dir);
    ChannelAnalysis analysis(pc);

    RunControl control(pc.progress_interval, scene.release.count);
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
            if (control.interrupted(solver.time())) {
                exit_code = 130;
                break;
            }
            if ((solver.steps() & 63) == 0)
                control.progress(solver.time(), scene.end_time, solver.steps(), total_steps);
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
        io::write_deposit_composition(pc.out_dir, scene, solver.particles());

    const double wall = control.elapsed_s();
    const auto ke = solver.kinetic_energy();
    const std::string status = run_status(exit_code);
    const double rate = static_cast<double>(solver.steps()) * static_cast<double>(scene.release.count) / wall;
    io::JsonObject js =
        summary_header(scene.name, "channel", exit_code, failure, ending, solver, scene.release.count);
    js.number("solid_volume_m3", scene.release.solid_volume)
        .text("mixture", scene.release.mixture)
        .text("compaction", scene.release.compaction)
        .number("phi_small", scene.release.mixture == "bidisperse" ? scene.release.phi_small : not_a_number)
        .number("radius_large_m",
                scene.release.mixture == "bidisperse" ? scene.release.r_large : not_a_number)
        .number("radius_small_m",
                scene.release.mixture == "bidisperse" ? scene.release.r_small : not_a_number)
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
