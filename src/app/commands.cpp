// SPDX-License-Identifier: MIT
#include "app/commands.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "core/config.h"
#include "core/error.h"
#include "sim/case_setup.h"
#include "sim/channel_run.h"
#include "sim/dam_break_run.h"
#include "sim/debris_run.h"
#include "sim/sandpile_run.h"

namespace sabo::app {

namespace {

sim::RunRequest run_request(const CaseRequest& req) {
    return {req.case_file, req.out_dir, req.resume};
}

}  // namespace

int run_case(const CaseRequest& req) {
    if (req.threads > 0) omp_set_num_threads(req.threads);
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    const std::string type = sim::case_type(cfg);
    if (req.resume && type != "debris")
        throw InputError(
            fmt::format("{}: --resume: only debris runs (case.type = \"debris\") write checkpoints",
                        req.case_file.string()));
    const sim::RunRequest run = run_request(req);
    if (type == "sandpile") return sim::run_sandpile(run, cfg);
    if (type == "dam_break") return sim::run_dam_break(run, cfg);
    if (type == "debris") return sim::run_debris(run, cfg);
    return sim::run_channel(run, cfg);
}

int check_case(const CaseRequest& req) {
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    const std::string type = sim::case_type(cfg);
    const sim::RunRequest run = run_request(req);
    if (type == "sandpile") {
        sim::print_derived(sim::prepare_sandpile(run, cfg));
    } else if (type == "dam_break") {
        sim::print_derived(sim::prepare_dam_break(run, cfg));
    } else if (type == "debris") {
        sim::print_derived(sim::prepare_debris(run, cfg));
    } else {
        sim::print_derived(sim::prepare(run, cfg));
    }
    spdlog::info("check passed: {} is valid (nothing was run)", req.case_file.string());
    return 0;
}

}  // namespace sabo::app
