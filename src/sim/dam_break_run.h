// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for the dam break (case.type = "dam_break", issue 5): the free-surface
// fluid alone, its front compared with Martin & Moyce (1952).
#pragma once
#include <filesystem>

#include "core/config.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_setup.h"
#include "scenario/dam_break_case.h"
#include "sim/case_setup.h"

namespace sabo::sim {

struct PreparedDamBreak {
    scenario::DamBreakCase scene;
    lbm::FluidSettings fluid;
    lbm::GridShape shape;
    int column_cells = 0, height_cells = 0;  // the column in cells (a and h rounded to Δx)
    OutputSettings output;
};

[[nodiscard]] PreparedDamBreak prepare_dam_break(const RunRequest& req, const Config& cfg);
void print_derived(const PreparedDamBreak& pc);
int run_dam_break(const RunRequest& req, const Config& cfg);

}  // namespace sabo::sim
