// SPDX-License-Identifier: MIT
// Reading and validating a case file into everything a run needs (scenario, solver settings, analysis
// and output settings), and the start-up printout of the derived numbers (`sabo check`). The output keys
// every case type shares are read in one place (read_output_settings).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "analysis/flow_gauge.h"
#include "core/config.h"
#include "core/mpi_world.h"
#include "dem/dem_setup.h"
#include "scenario/channel_case.h"

namespace sabo::sim {

// What the command line adds to a case file.
struct RunRequest {
    std::filesystem::path case_file;
    std::optional<std::filesystem::path> out_dir;  // else output.dir, else out/<case name>
    bool resume = false;                           // continue from out_dir/checkpoint.bin
    bool place_grains = true;                      // false: `sabo check` (the derived numbers need none)
    const MpiWorld* world = nullptr;               // the ranks a run is divided among (none: one process)
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

// The gauge section upstream of the barrier that measures the approaching flow (docs/design.md, "The
// approaching flow"): analysis.gauge_distance_m, analysis.gauge_length_m, analysis.gauge_arrival_depth_m.
struct GaugeSettings {
    analysis::GaugeSection section;
    double distance = 0.0;       // m, from the section's centre up-slope to the barrier's upstream face
    double arrival_depth = 0.0;  // m: the front has reached the gauge when its depth first reaches this
};
// Reads them for a barrier face at X = face_x across a channel of the given width, with `grain_size` the mean
// grain diameter (the fluid alone: two lattice spacings): the depth map's cells are no smaller and the
// arrival depth defaults to half of it. Refuses a section that reaches the barrier or leaves the channel.
[[nodiscard]] GaugeSettings read_gauge_settings(const Config& cfg, double face_x, double channel_width,
                                                double grain_size);

struct AnalysisSettings {
    double arching_depth = 0.0;  // m (4 r)
    int arching_intervals = 10;
    double arching_threshold = 1e-5;  // J
    double upstream_reach = 1.0;      // m, reach for h and v of k_st, k_dyn
    GaugeSettings gauge;
    bool stop_enabled = true;
    double stop_threshold = 0.0;  // J, total kinetic energy
    double stop_hold = 1.0;       // s
};

struct PreparedCase {
    scenario::ChannelCase scene;
    dem::DemSettings dem;
    AnalysisSettings analysis;
    OutputSettings output;
};

// Refuses a case whose spheres (placed: the exact count) would need more than 80 % of the available memory;
// the case builders refuse far larger requests before placing anything (dem/grain_budget.h).
void check_memory(const Config& cfg, std::size_t spheres);

// case.type: "channel" (CASES C2–C4, the default) or "sandpile" (C1).
[[nodiscard]] std::string case_type(const Config& cfg);
// A channel case.
[[nodiscard]] PreparedCase prepare(const RunRequest& req, const Config& cfg);
void print_derived(const PreparedCase& pc);

}  // namespace sabo::sim
