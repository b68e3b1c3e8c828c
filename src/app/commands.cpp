// SPDX-License-Identifier: MIT
#include "app/commands.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>

#include "cases/registry.h"
#include "core/config.h"
#include "core/error.h"
#include "core/memory.h"
#include "parallel/split_advice.h"
#include "sim/run_case.h"
#include "sim/run_summary.h"

namespace sabo::app {

namespace {

sim::RunRequest run_request(const CaseRequest& req) {
    return {req.case_file, req.out_dir, req.resume, true, req.world, req.overwrite};
}

int run_type(const sim::RunRequest& run, const Config& cfg) {
    return sim::run_case(*cases::make_case_type(cfg), run, cfg);
}

}  // namespace

int run_case(const CaseRequest& req) {
    if (req.threads > 0) omp_set_num_threads(req.threads);
    return run_type(run_request(req), Config::from_file(req.case_file, req.overrides));
}

int resume_run(const ResumeRequest& req) {
    if (req.threads > 0) omp_set_num_threads(req.threads);
    const std::filesystem::path file = req.out_dir / sim::resume_file_name;
    toml::table started;
    try {
        started = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw InputError(fmt::format("{}: not a sabo run folder, or one from before `sabo resume` ({}): {}",
                                     req.out_dir.string(), file.string(), e.description()));
    }
    const auto* case_file = started["case_file"].as_string();
    const auto* text = started["case"].as_string();
    const auto* stored = started["overrides"].as_array();
    if (case_file == nullptr || text == nullptr || stored == nullptr)
        throw InputError(fmt::format("{}: damaged (case_file, case and overrides expected)", file.string()));
    std::vector<std::string> overrides;
    for (const auto& o : *stored)
        if (const auto* s = o.as_string()) overrides.push_back(s->get());
    overrides.insert(overrides.end(), req.overrides.begin(), req.overrides.end());
    const Config cfg = Config::from_string(text->get(), case_file->get(), overrides);
    return run_type({case_file->get(), req.out_dir, true, true, req.world}, cfg);
}

int check_case(const CaseRequest& req) {
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    sim::check_case(*cases::make_case_type(cfg), run_request(req), cfg);
    const double lattice_bytes = 1048576.0 * cfg.recorded_number("derived.lattice_memory_MiB");
    const double run_bytes = lattice_bytes + 1048576.0 * cfg.recorded_number("derived.grains_memory_MiB");
    spdlog::info("{}", parallel::advise_split(run_bytes, lattice_bytes,
                                              static_cast<int>(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN))),
                                              available_memory_bytes())
                           .text);
    spdlog::info("check passed: {} is valid (nothing was run)", req.case_file.string());
    return 0;
}

}  // namespace sabo::app
