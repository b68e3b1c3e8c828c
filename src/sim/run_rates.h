// SPDX-License-Identifier: MIT
// This machine's measured speeds, kept between runs, so that `sabo check` can estimate how long a run will
// take here. A run's speed is its work per wall second: node-steps (lattice nodes × lattice steps) for a
// case with a fluid, particle-steps (grains × DEM steps) for one of grains alone; kept per kind of run
// (case type, what it holds, CPU or OpenCL) and thread count in one small TOML file (rates_file()).
#pragma once
#include <filesystem>
#include <string>

#include "core/config.h"

namespace sabo::sim {

// The kind of run and its work per step, from a prepared case's resolved values (`sabo check` and `sabo run`
// compute the same).
struct RunWork {
    std::string kind;       // e.g. "debris/coupled/cpu", "channel/grains/cpu"
    std::string unit;       // "node-steps" or "particle-steps"
    double per_step = 0.0;  // lattice nodes, or grains
    double step_s = 0.0;    // the step the work counts: the lattice's, else the DEM's
};
[[nodiscard]] RunWork run_work(const Config& cfg);

// $SABO_RATES_FILE, else $XDG_CACHE_HOME/sabo/rates.toml, else $HOME/.cache/sabo/rates.toml.
[[nodiscard]] std::filesystem::path rates_file();

// Keeps a finished run's speed (work per wall second on `threads`); a file that cannot be written is left
// alone (said at debug level): the speeds are a convenience, never a reason for a run to fail.
void record_rate(const RunWork& work, int threads, double work_per_s);

// The estimate line `sabo check` prints for a run of `simulated_s` on `threads`: from this machine's last
// run of this kind (the same thread count, else the nearest one scaled by the thread ratio), else for grains
// from a stated reference rate, else none (and how to get one).
[[nodiscard]] std::string wall_time_estimate(const RunWork& work, double simulated_s, int threads,
                                             bool may_stop_early);

}  // namespace sabo::sim
