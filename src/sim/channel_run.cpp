// SPDX-License-Identifier: MIT
#include "sim/channel_run.h"

#include <spdlog/spdlog.h>

#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/json_writer.h"
#include "io/report_script.h"
#include "sim/channel_observer.h"
#include "sim/design_inputs.h"
#include "sim/frame_observers.h"
#include "sim/gauge_observer.h"
#include "sim/presettle.h"
#include "sim/run_checkpoint.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/run_summary.h"
#include "sim/simulation.h"

namespace sabo::sim {

int run_channel(const RunRequest& req, const Config& cfg) {
    PreparedCase pc = prepare(req, cfg);
    const auto& out = pc.output;
    const auto& scene = pc.scene;
    Domain grains_domain{.origin = {}, .dx = 0.0, .box = {scene.length, scene.width, scene.height}};
    if (req.world != nullptr) grains_domain.divide_grains(*req.world);
    open_run_folder(out.out_dir, req.case_file, cfg, req.resume, grains_domain);
    print_derived(pc);

    RunControl control(out.progress_interval, scene.release.count);
    // a resumed run's grains come from its checkpoint (settled before it was written)
    const bool settle = scene.release.compaction == "high" && !req.resume;
    const dem::Particles start = settle ? presettle(pc, control) : scene.particles;
    if (control.stop_requested()) {
        spdlog::warn(
            "interrupted while the block settled (release.compaction = \"high\"): no checkpoint is written "
            "before the release; run the case again");
        return 130;
    }
    // divided among ranks, each takes its slab of grains (every rank built the same whole set)
    Simulation sim(dem::make_solver(start, scene.walls, scene.gravity, pc.dem), grains_domain);
    const Domain& domain = sim.domain();
    ParticleFrames frames(out.out_dir);
    ChannelObserver analysis(pc, domain);
    GaugeObserver gauge(pc.analysis.gauge, analysis.forces(), out.out_dir, {}, domain);
    const std::vector<Observer*> observers{&analysis, &gauge, &frames};
    RunCheckpoint checkpoint(out.out_dir, cfg, domain);
    if (req.resume) checkpoint.load(sim, observers);
    Schedule at = make_schedule(pc.dem.dt, scene.end_time, out.series_interval, out.frame_interval);
    at.sample_at_end = true;
    checkpoint.schedule(at, out, sim, observers, control, req.resume);
    const RunEnd end = run(sim, at, observers, control);
    const int exit_code = end.exit_code;
    const GrainView grains = sim.grain_view();  // every grain (divided: collective, as finish and the sums)
    analysis.finish(sim);
    const double wall = checkpoint.wall_before() + control.elapsed_s();
    const double own_work = checkpoint.work_before() + end.work;
    const double rate = domain.sum(own_work) / wall;
    const DivisionSummary division = summarise_division(sim, own_work, control.elapsed_s());
    if (!domain.writes_outputs()) return exit_code;  // the first rank writes the summary and the report
    if (scene.release.mixture == "bidisperse" && scene.barrier.present())
        io::write_deposit_composition(out.out_dir, scene, grains.particles);

    const auto ke = grains.kinetic_energy();
    const std::string status = run_status(exit_code);
    io::JsonObject js = summary_header(scene.name, "channel", end, sim, "particles", scene.release.count);
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
        .number("max_overlap_over_d", grains.max_overlap_seen);
    analysis.summarise(js);
    gauge.summarise(js);
    if (scene.barrier.present()) {
        const auto& f = analysis.forces();
        add_design_comparison(
            js, out.out_dir,
            measured_run(gauge.approach(), {f.max_normal(), f.normal()}, analysis.deposit(), grains.particles,
                         scene.release.density, 0.0, scene.barrier, scene.width, scene.slope_deg,
                         norm(scene.gravity), 1.0 - analysis.non_retained()));
    }
    js.integer("neighbor_list_builds", static_cast<std::int64_t>(grains.list_builds))
        .number("wall_time_s", wall)
        .number("particle_steps_per_s", rate);
    add_division_summary(js, division);
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    spdlog::info("{} ({}): t = {:.4f} s, {} steps in {} ({:.3g} particle-steps/s); max overlap {:.2f} % of d",
                 status, exit_code == 0 ? end.ending : status, sim.time(), sim.steps(), format_duration(wall),
                 rate, 100.0 * grains.max_overlap_seen);
    if (grains.max_overlap_seen > 0.02) {
        spdlog::warn(
            "max overlap {:.2f} % of a diameter exceeded the recommended 2 % (stiffer contacts or smaller "
            "impact speeds)",
            100.0 * grains.max_overlap_seen);
    }
    const double energy = ke.translational + ke.rotational;
    if (exit_code == 0 && end.ending == "end time" && pc.analysis.stop_enabled &&
        energy > pc.analysis.stop_threshold) {
        spdlog::warn(
            "the grains had not stopped by the end time: kinetic energy {:.3g} J, above the complete-stop "
            "threshold {:.3g} J (stop.kinetic_energy_per_grain_J x grains); the barrier's force "
            "at the end is not yet its static load — raise case.end_time_s",
            energy, pc.analysis.stop_threshold);
    }
    if (out.report) io::run_report_script(out.out_dir);
    checkpoint.tell_how_to_resume(exit_code);
    return exit_code;
}

}  // namespace sabo::sim
