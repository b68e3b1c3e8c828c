// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for sandpile cases (CASES C1): settling with the outlets closed, opening,
// draining to a complete stop, and the angle of repose of the heap left on the plate.
#pragma once
#include <filesystem>

#include "analysis/repose_angle.h"
#include "app/commands.h"
#include "core/config.h"
#include "dem/dem_setup.h"
#include "scenario/sandpile_case.h"

namespace sabo::app {

struct PreparedSandpile {
    scenario::SandpileCase scene;
    dem::DemSettings dem;
    double frame_interval = 0.0, series_interval = 0.0, progress_interval = 0.0;
    double stop_energy_per_grain = 0.0;  // J, mean kinetic energy of the grains above the plate at a stop
    double stop_hold = 0.0;              // s
    bool report = true;
    bool remove_drained = true;  // sandpile.remove_drained
    std::filesystem::path out_dir;
};

[[nodiscard]] PreparedSandpile prepare_sandpile(const CaseRequest& req, const Config& cfg);
void print_derived(const PreparedSandpile& pc);
int run_sandpile(const CaseRequest& req, const Config& cfg);

}  // namespace sabo::app
