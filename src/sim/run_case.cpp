// SPDX-License-Identifier: MIT
#include "sim/run_case.h"

#include <omp.h>
#include <spdlog/spdlog.h>

#include "io/atomic_file.h"
#include "io/report_script.h"
#include "sim/run_checkpoint.h"
#include "sim/run_rates.h"
#include "sim/run_summary.h"

namespace sabo::sim {

int run_case(CaseType& type, const RunRequest& req, const Config& cfg) {
    type.prepare(req, cfg);
    const OutputSettings& out = type.output();
    const parallel::Domain whole = type.domain(req.world);
    const FolderUse use = req.resume      ? FolderUse::resume
                          : req.overwrite ? FolderUse::overwrite
                                          : FolderUse::new_run;
    open_run_folder(out.out_dir, req.case_file, cfg, use, whole);
    type.print_derived();
    const ProgressLine line = type.progress();
    RunControl control(out.progress_interval, line.grains);
    if (line.ends_at_end_time) control.set_ends_at_end_time();
    std::optional<Simulation> built = type.build(whole, control, req.resume);
    if (!built) return 130;  // (the case type said why)
    Simulation& sim = *built;
    const parallel::Domain& domain = sim.domain();
    const std::vector<Observer*> observers = type.observers(sim);
    RunCheckpoint checkpoint(out.out_dir, cfg, domain);
    if (req.resume) checkpoint.load(sim, observers);
    const double simulated_from = sim.time();
    Schedule at = make_schedule(sim.dt(), type.end_time(), out.series_interval, out.frame_interval);
    at.sample_at_end = type.sample_at_end();
    if (sim.has_fluid()) at.progress_every = 16;  // a lattice step is slower than a DEM step
    checkpoint.schedule(at, out, sim, observers, control, req.resume);
    const RunEnd end = run(sim, at, observers, control);

    type.finish(sim, end);
    log_timing(sim, control.elapsed_s());
    const double own_work = checkpoint.work_before() + end.work;
    const RunTotals totals{checkpoint.wall_before() + control.elapsed_s(), domain.sum(own_work)};
    const DivisionSummary division = summarise_division(sim, own_work, control.elapsed_s());
    // this machine's speed for `sabo check`'s estimates: a whole run in one process, long enough to count
    if (end.exit_code == 0 && !domain.divided() && control.elapsed_s() > 1.0) {
        const RunWork work = run_work(cfg);
        const double steps = work.step_s > 0.0 ? (sim.time() - simulated_from) / work.step_s : 0.0;
        record_rate(work, omp_get_max_threads(), work.per_step * steps / control.elapsed_s());
    }
    if (!domain.writes_outputs()) return end.exit_code;  // the first rank writes the run's files

    type.write_end_files(sim, end);
    const SummaryHead head = type.summary_head(sim);
    io::JsonObject js = summary_header(head.case_name, head.type, end, sim, head.count_key, head.count);
    const int exit_code = type.summarise(js, sim, end);
    add_division_summary(js, division);
    type.summarise_rate(js, totals);
    add_timing(js, sim, control.elapsed_s());
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    type.log_end(sim, end, totals);
    if (out.report) io::run_report_script(out.out_dir, type.report_script());
    checkpoint.tell_how_to_resume(exit_code);
    return exit_code;
}

void check_case(CaseType& type, RunRequest req, const Config& cfg) {
    req.place_grains = false;
    type.prepare(req, cfg);
    type.print_derived();
    const std::string estimate = wall_time_estimate(run_work(cfg), type.end_time(), omp_get_max_threads(),
                                                    !type.progress().ends_at_end_time);
    if (!estimate.empty()) spdlog::info("{}", estimate);
}

}  // namespace sabo::sim
