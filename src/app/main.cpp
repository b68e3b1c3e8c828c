// SPDX-License-Identifier: MIT
// `sabo` command line: parse, call the library, map errors to exit codes.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <optional>
#include <string>

#include "app/commands.h"
#include "core/error.h"
#include "core/log.h"
#include "core/mpi_world.h"
#include "core/thread_environment.h"
#include "core/thread_waiting.h"
#include "lbm/opencl/devices.h"
#include "sabo/version.h"

int main(int argc, char** argv) {
    // a file grown past the shell's `ulimit -f` fails its write (the reason said, exit 3, the last checkpoint
    // kept) instead of the signal killing the run without a word
    std::signal(SIGXFSZ, SIG_IGN);
    sabo::wait_politely(argv);  // (may start the program again: first, before threads and MPI)
    const sabo::MpiWorld world(argc, argv);
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
        ->check(CLI::Range(1, sabo::max_threads));
    auto* resume_flag =
        run->add_flag("--resume", req.resume,
                      "Continue from the checkpoint in the output folder (the case may change "
                      "its end time and checkpoint interval only)");
    run->add_flag("--overwrite", req.overwrite,
                  "Replace the outputs of another run in the output folder (else such a folder is refused)")
        ->excludes(resume_flag);
    sabo::app::ResumeRequest resume_req;
    std::string resume_dir;
    auto* resume = cli.add_subcommand(
        "resume",
        "Continue a run from the checkpoint in its output folder, with the case it was started with");
    resume->add_option("outdir", resume_dir, "The run's output folder")
        ->required()
        ->check(CLI::ExistingDirectory);
    resume->add_option("--set", resume_req.overrides,
                       "Override a key as well (case.end_time_s=... to run further; repeatable)");
    resume->add_option("--threads", resume_req.threads, "OpenMP threads (default: all cores)")
        ->check(CLI::Range(1, sabo::max_threads));
    auto* check = cli.add_subcommand("check", "Validate a case and print its derived numbers; run nothing");
    add_case_options(check);
    auto* devices = cli.add_subcommand(
        "devices", "List the OpenCL devices the lattice can run on (platform, name, memory, float64)");

    sabo::app::SweepRequest sweep_req;
    std::string sweep_out;
    auto* sweep =
        cli.add_subcommand("sweep", "Run a grid of cases (one process each, resumable) and chart them");
    sweep->add_option("sweep", sweep_req.sweep_file, "Sweep file (TOML)")
        ->required()
        ->check(CLI::ExistingFile);
    sweep->add_option("--out", sweep_out, "Output folder (default: out/sweeps/<name>)");
    sweep->add_option("--shard", sweep_req.shard,
                      "i/N: run only the cases k with k mod N = i (i from 0), e.g. one Slurm array task");
    sweep->add_option("--jobs", sweep_req.jobs, "Cases run at once (default: the sweep file's jobs)")
        ->check(CLI::Range(1, 256));

    sabo::app::CalibrateRequest cal;
    std::string cal_out, cal_case;
    std::optional<double> cal_angle, cal_mu_s;
    auto* calibrate = cli.add_subcommand(
        "calibrate",
        "Friction coefficients from an angle of repose (docs/calibration.md), checked by a sandpile, or the "
        "calibration sweep that fits the law");
    calibrate->add_option("--angle-deg", cal_angle, "Target angle of repose, degrees")
        ->check(CLI::Range(0.0, 90.0));
    calibrate
        ->add_option("--mu-s", cal_mu_s, "Choose mu_s (default: tan of the angle); mu_r follows from the law")
        ->check(CLI::Range(0.0, 10.0));
    calibrate->add_flag("--verify", cal.verify, "Run a sandpile with the coefficients and report its angle");
    calibrate->add_flag("--sweep", cal.sweep,
                        "Run the (mu_s, mu_r) grid of reference case C1 and fit the law");
    calibrate->add_option("--case", cal_case, "Sandpile case (default cases/calibration_sandpile.toml)");
    calibrate->add_option("--set", cal.overrides, "Override a case key for every run (repeatable)");
    calibrate->add_option("--out", cal_out, "Output folder (default out/calibrate/...)");
    calibrate->add_option("--threads", cal.threads, "OpenMP threads per run")
        ->check(CLI::Range(1, sabo::max_threads));
    calibrate->add_option("--jobs", cal.jobs, "Sweep: sandpiles run at once (default 1)")
        ->check(CLI::Range(1, 256));
    calibrate->add_option("--mu-s-values", cal.mu_s_values, "Sweep: mu_s values, first:last:step or a,b,c")
        ->capture_default_str();
    calibrate->add_option("--mu-r-values", cal.mu_r_values, "Sweep: mu_r values, first:last:step or a,b,c")
        ->capture_default_str();
    calibrate
        ->add_option("--particles", cal.particles, "Sweep/verify: number of spheres (default: the case's)")
        ->check(CLI::Range(1, 100000000));

    sabo::app::DesignRequest design_req;
    auto* design = cli.add_subcommand(
        "design",
        "The guidelines' design formulas (impact force, boulder impact, trapping, slit width, typology) "
        "for a flow and barrier; `design compare RUNDIR` for a finished run");
    design->require_subcommand(0, 1);
    // (CLI::PositiveNumber names the largest double in its message: 300 digits)
    const CLI::Validator positive(
        [](const std::string& text) {
            std::size_t used = 0;
            double v = 0.0;
            try {
                v = std::stod(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != text.size() || !std::isfinite(v) || v <= 0.0)
                return fmt::format("'{}' must be a finite number above 0", text);
            return std::string();
        },
        "POSITIVE");
    design->add_option("--depth", design_req.depth, "Flow depth h, m")->check(positive);
    design->add_option("--velocity", design_req.velocity, "Depth-averaged flow velocity v, m/s")
        ->check(positive);
    design->add_option("--density", design_req.density, "Bulk density of the flow, kg/m3")->check(positive);
    design->add_option("--width", design_req.width, "Barrier width W, m")->check(positive);
    design->add_option("--slope-deg", design_req.slope_deg, "Bed slope, degrees")
        ->check(CLI::Range(0.0, 90.0));
    design->add_option("--barrier-height", design_req.barrier_height, "Barrier height, m")->check(positive);
    design->add_option("--opening", design_req.openings, "An outlet's width S, m (repeatable)")
        ->check(positive);
    design->add_option("--d95", design_req.d95, "Grain diameter D95, m (default D_max)")->check(positive);
    design->add_option("--d-max", design_req.d_max, "Largest grain (boulder) diameter, m")->check(positive);
    design->add_option("--grain-density", design_req.grain_density, "Boulder density, kg/m3")
        ->check(positive);
    design->add_option("--peak-discharge", design_req.peak_discharge, "Q_peak, m3/s (default h v W)")
        ->check(positive);
    design->add_option("--solid-fraction", design_req.solid_fraction, "C_s, volumetric")
        ->check(CLI::Range(0.0, 1.0));
    design
        ->add_option("--boulder-modulus", design_req.boulder_modulus,
                     "Boulder Young's modulus, Pa (granite 60e9)")
        ->check(positive);
    design->add_option("--boulder-poisson", design_req.boulder_poisson, "Boulder Poisson ratio (0.25)")
        ->check(CLI::Range(0.0, 0.5));
    design
        ->add_option("--barrier-modulus", design_req.barrier_modulus,
                     "Barrier Young's modulus, Pa (concrete 30e9)")
        ->check(positive);
    design->add_option("--barrier-poisson", design_req.barrier_poisson, "Barrier Poisson ratio (0.2)")
        ->check(CLI::Range(0.0, 0.5));
    std::string design_run;
    auto* design_compare =
        design->add_subcommand("compare",
                               "A finished channel or debris run beside every formula: table, "
                               "design_comparison.csv and design_comparison.png in the run folder");
    design_compare->add_option("rundir", design_run, "The run's output folder")
        ->required()
        ->check(CLI::ExistingDirectory);
    design_compare->fallthrough();

    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; a bad command line exits 2, as a bad case does (CLI11's own codes,
        // 105 and the like, are not the documented ones)
        return cli.exit(e) == 0 ? 0 : 2;
    }
    sabo::init_logging(verbose,
                       world.size() > 1 ? fmt::format("rank {}/{}", world.rank(), world.size()) : "");
    if (!out_dir.empty()) req.out_dir = out_dir;
    try {
        if (const std::string warning = sabo::check_thread_environment(); !warning.empty())
            spdlog::warn("{}", warning);
        if (sabo::MpiWorld::launcher_size() > 1 && !sabo::MpiWorld::built_with_mpi())
            throw sabo::InputError(
                "started by an MPI launcher with several processes, but this sabo was built without MPI: "
                "rebuild it with MPI (libopenmpi-dev) or split a sweep with `sabo sweep --shard i/N`");
        if (world.size() > 1 && !sweep->parsed() && !run->parsed() && !resume->parsed())
            throw sabo::InputError(fmt::format(
                "{} MPI ranks: only `sabo sweep`, `sabo run` and `sabo resume` run on several ranks; start "
                "this command as one process",
                world.size()));
        req.world = &world;
        resume_req.world = &world;
        if (run->parsed()) return sabo::app::run_case(req);
        if (devices->parsed()) {
            fmt::print("{}", sabo::lbm::opencl::describe_devices());
            return 0;
        }
        if (resume->parsed()) {
            resume_req.out_dir = resume_dir;
            return sabo::app::resume_run(resume_req);
        }
        if (calibrate->parsed()) {
            cal.angle_deg = cal_angle;
            cal.mu_s = cal_mu_s;
            if (!cal_case.empty()) cal.case_file = cal_case;
            if (!cal_out.empty()) cal.out_dir = cal_out;
            return sabo::app::run_calibrate(cal);
        }
        if (design->parsed()) {
            if (design_compare->parsed()) design_req.run_dir = design_run;
            return sabo::app::run_design(design_req);
        }
        if (sweep->parsed()) {
            if (!sweep_out.empty()) sweep_req.out_dir = sweep_out;
            return sabo::app::run_sweep(sweep_req, world);
        }
        return sabo::app::check_case(req);
    } catch (const sabo::InputError& e) {
        // (a divided run refuses its input on every rank alike: the checks read the same case, and the
        // checkpoints' are agreed on)
        spdlog::error("{}", e.what());
        return 2;
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        // an unforeseen failure may be this rank's alone: the others, waiting for it, are stopped too
        if (world.size() > 1 && (run->parsed() || resume->parsed())) world.abort(3);
        return 3;
    }
}
