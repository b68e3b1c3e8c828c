// SPDX-License-Identifier: MIT
// A sandpile case's keys read and checked (case.type = "sandpile", reference case C1) and its derived numbers
// (`sabo check`).
#pragma once
#include "core/config.h"
#include "dem/dem_setup.h"
#include "scenario/sandpile_case.h"
#include "sim/case_settings.h"

namespace sabo::cases {

struct PreparedSandpile {
    scenario::SandpileCase scene;
    dem::DemSettings dem;
    sim::OutputSettings output;
    double stop_energy_per_grain = 0.0;  // J, mean kinetic energy of the grains above the plate at a stop
    double stop_hold = 0.0;              // s
    bool remove_drained = true;          // sandpile.remove_drained
};

[[nodiscard]] PreparedSandpile prepare_sandpile(const sim::RunRequest& req, const Config& cfg);
void print_derived(const PreparedSandpile& pc);
}  // namespace sabo::cases
