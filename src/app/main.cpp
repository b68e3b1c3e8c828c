// SPDX-License-Identifier: MIT
// `sabo` command line: parse, call the library, map errors to exit codes.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "core/error.h"
#include "core/log.h"
#include "sabo/version.h"

int main(int argc, char** argv) {
    CLI::App cli{"Sabo — DEM–LBM simulator of debris flows against open barriers"};
    cli.set_version_flag("--version", std::string("sabo ") + sabo::version_string);
    cli.require_subcommand(1);
    bool verbose = false;
    cli.add_flag("-v,--verbose", verbose, "Debug messages");

    sabo::app::CaseRequest req;
    std::string out_dir;
    auto add_case_options = [&](CLI::App* sub) {
        sub->add_option("case", req.case_file, "Case file (TOML)")->required()->check(CLI::ExistingFile);
        sub->add_option("--set", req.overrides, "Override a key: --set key.path=value (repeatable)");
    };
    auto* run = cli.add_subcommand("run", "Run a case and write its outputs");
    add_case_options(run);
    run->add_option("--out", out_dir, "Output folder (default: output.dir or out/<case name>)");
    run->add_option("--threads", req.threads, "OpenMP threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    auto* check = cli.add_subcommand("check", "Validate a case and print its derived numbers; run nothing");
    add_case_options(check);

    sabo::app::SweepRequest sweep_req;
    std::string sweep_out;
    auto* sweep =
        cli.add_subcommand("sweep", "Run a grid of cases (one process each, resumable) and chart them");
    sweep->add_option("sweep", sweep_req.sweep_file, "Sweep file (TOML)")
        ->required()
        ->check(CLI::ExistingFile);
    sweep->add_option("--out", sweep_out, "Output folder (default: out/sweeps/<name>)");
    sweep->add_option("--jobs", sweep_req.jobs, "Cases run at once (default: the sweep file's jobs)")
        ->check(CLI::Range(1, 256));

    CLI11_PARSE(cli, argc, argv);
    sabo::init_logging(verbose);
    if (!out_dir.empty()) req.out_dir = out_dir;
    try {
        if (run->parsed()) return sabo::app::run_case(req);
        if (sweep->parsed()) {
            if (!sweep_out.empty()) sweep_req.out_dir = sweep_out;
            return sabo::app::run_sweep(sweep_req);
        }
        return sabo::app::check_case(req);
    } catch (const sabo::InputError& e) {
        spdlog::error("{}", e.what());
        return 2;
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 3;
    }
}
