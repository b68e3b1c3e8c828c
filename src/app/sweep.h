// SPDX-License-Identifier: MIT
// A sweep: one case file run once per combination of overrides, one `sabo run` process per case,
// resumable (a case whose summary.json says "completed" is skipped), then a python report script on
// the sweep folder. `sabo sweep` reads the plan from a sweep file (docs/sweeps.md); `sabo calibrate
// --sweep` builds it from the command line.
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "core/mpi_world.h"

namespace sabo::app {

struct SweepCase {
    std::string id;
    std::vector<std::pair<std::string, std::string>> values;  // grid key → value, as written
    std::vector<std::string> overrides;                       // all --set for this case
};

struct SweepPlan {
    std::string name;  // the report's title: [sweep] name, else the sweep file's stem
    std::filesystem::path case_file, out_dir;
    int threads = 1, jobs = 1;
    int shard = 0, shards = 1;  // this process runs the cases k with k mod shards = shard
    std::vector<std::string> grid_keys;
    std::vector<SweepCase> cases;
};

// Adds the Cartesian product of `axes` (key, values), each case with the `common` overrides first.
void add_grid(SweepPlan& plan, const std::vector<std::pair<std::string, std::vector<std::string>>>& axes,
              const std::vector<std::string>& common);
// Runs the plan's cases (`jobs` at a time; those of its shard, or of this rank when `world` has several),
// keeps sweep_cases.csv up to date, then — once every case of the plan has ended, whichever shard or rank
// ran it — python/<report_script> OUT_DIR. Exit codes as run_sweep.
int execute_sweep(const SweepPlan& plan, const std::string& report_script, const MpiWorld* world = nullptr);

}  // namespace sabo::app
