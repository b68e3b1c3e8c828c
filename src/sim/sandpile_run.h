// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for sandpile cases (CASES C1): settling with the outlets closed, opening,
// draining to a complete stop, and the angle of repose of the heap left on the plate.
#pragma once
#include <filesystem>

#include "analysis/repose_angle.h"
#include "core/config.h"
#include "dem/dem_setup.h"
#include "scenario/sandpile_case.h"
#include "sim/case_setup.h"

namespace sabo::sim {

struct PreparedSandpile {
    scenario::SandpileCase scene;
    dem::DemSettings dem;
    OutputSettings output;
    double stop_energy_per_grain = 0.0;  // J, mean kinetic energy of the grains above the plate at a stop
    double stop_hold = 0.0;              // s
    bool remove_drained = true;          // sandpile.remove_drained
};

[[nodiscard]] PreparedSandpile prepare_sandpile(const RunRequest& req, const Config& cfg);
void print_derived(const PreparedSandpile& pc);
int run_sandpile(const RunRequest& req, const Config& cfg);

}  // namespace sabo::sim
