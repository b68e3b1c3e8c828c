// SPDX-License-Identifier: MIT
// What every case type shares when it reads its case file (src/cases/<type>/): the command line's request,
// the [output] keys (read in one place, read_output_settings) and the memory check of its spheres.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "core/config.h"
#include "core/mpi_world.h"

namespace sabo::sim {

// What the command line adds to a case file.
struct RunRequest {
    std::filesystem::path case_file;
    std::optional<std::filesystem::path> out_dir;  // else output.dir, else out/<case name>
    bool resume = false;                           // continue from out_dir/checkpoint.bin
    bool place_grains = true;                      // false: `sabo check` (the derived numbers need none)
    const MpiWorld* world = nullptr;               // the ranks a run is divided among (none: one process)
    bool overwrite = false;                        // a new run may replace another run's outputs in out_dir
};

// The [output] keys of every case type (docs/case_files.md).
struct OutputSettings {
    double frame_interval = 0.0;     // s of simulated time
    double series_interval = 0.0;    // s of simulated time
    double progress_interval = 0.0;  // s of wall time
    bool report = true;
    std::filesystem::path out_dir;
    double checkpoint_wall_s = 600.0;  // wall-clock s between checkpoints (0: none but the end's)
    double checkpoint_sim_s = 0.0;     // simulated s between checkpoints (0: none)
};
// Reads them with the case type's defaults for the frame and series intervals.
[[nodiscard]] OutputSettings read_output_settings(const Config& cfg, const RunRequest& req,
                                                  const std::string& case_name, double frame_default,
                                                  double series_default);

// Refuses a case whose spheres (placed: the exact count) would need more than 80 % of the available memory;
// the case builders refuse far larger requests before placing anything (dem/grain_budget.h).
void check_memory(const Config& cfg, std::size_t spheres);

}  // namespace sabo::sim
