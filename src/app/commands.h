// SPDX-License-Identifier: MIT
// The `sabo run`, `sabo resume`, `sabo check` and `sabo sweep` commands. Exit codes: 0 ok, 2 bad input, 3 run
// failure, 130 interrupted (outputs written up to the interruption).
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/mpi_world.h"

namespace sabo::app {

struct CaseRequest {
    std::filesystem::path case_file;
    std::vector<std::string> overrides;  // "key.path=value"
    std::optional<std::filesystem::path> out_dir;
    int threads = 0;                  // 0: OpenMP default
    bool resume = false;              // continue from the output folder's checkpoint
    bool overwrite = false;           // replace another run's outputs in the output folder
    const MpiWorld* world = nullptr;  // the ranks the run is divided among (none: one process)
};

// `sabo resume OUTDIR`: the run in OUTDIR continued from its checkpoint with the case it was started with
// (OUTDIR/resume.toml) and these further overrides (case.end_time_s to run further).
struct ResumeRequest {
    std::filesystem::path out_dir;
    std::vector<std::string> overrides;
    int threads = 0;
    const MpiWorld* world = nullptr;
};

struct SweepRequest {
    std::filesystem::path sweep_file;
    std::optional<std::filesystem::path> out_dir;
    int jobs = 0;       // 0: the sweep file's
    std::string shard;  // "i/N": run only the cases k with k mod N = i (empty: all)
};

struct CalibrateRequest {
    std::optional<double> angle_deg;  // target angle of repose
    std::optional<double> mu_s;       // chosen μ_s (else μ_s = tan φ)
    bool verify = false;              // run a sandpile with the result
    bool sweep = false;               // run the (μ_s, μ_r) grid and fit the law
    std::filesystem::path case_file = "cases/calibration_sandpile.toml";
    std::vector<std::string> overrides;
    std::optional<std::filesystem::path> out_dir;
    int threads = 0, jobs = 1;
    std::string mu_s_values = "0.1:1.0:0.05", mu_r_values = "0:0.2:0.02";  // "first:last:step" or "a,b,c"
    int particles = 0;                                                     // 0: the case file's
};

// `sabo design`: the design formulas for a flow and barrier given on the command line, or (`compare`) for
// a finished run beside its simulated forces.
struct DesignRequest {
    std::optional<std::filesystem::path> run_dir;                    // compare: the run's output folder
    double depth = 0.0, velocity = 0.0, density = 0.0, width = 0.0;  // the flow and the barrier width
    double slope_deg = 0.0, barrier_height = 0.0;
    std::vector<double> openings;  // outlet widths S, m
    double d95 = 0.0, d_max = 0.0, grain_density = 2650.0;
    double peak_discharge = 0.0, solid_fraction = 0.0;
    double boulder_modulus = 60e9, boulder_poisson = 0.25, barrier_modulus = 30e9, barrier_poisson = 0.2;
};
// Exit codes: 0 ok, 2 bad input (a missing flow value, a folder without a run's summary).
int run_design(const DesignRequest& request);

int run_case(const CaseRequest& request);
int resume_run(const ResumeRequest& request);
// Exit codes: 0 ok, 2 bad input (an angle outside the law's range), 3 a run failed.
int run_calibrate(const CalibrateRequest& request);
// Exit codes: 0 all cases completed, 2 bad sweep file, 3 some case failed, 130 interrupted.
// Under an MPI launcher each rank runs its share of the cases (`world`).
int run_sweep(const SweepRequest& request, const MpiWorld& world);
int check_case(const CaseRequest& request);

}  // namespace sabo::app
