// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for the dam break (case.type = "dam_break", issue 5): the free-surface
// fluid alone, its front compared with Martin & Moyce (1952).
#pragma once
#include <filesystem>

#include "app/commands.h"
#include "core/config.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_setup.h"
#include "scenario/dam_break_case.h"

namespace sabo::app {

struct PreparedDamBreak {
    scenario::DamBreakCase scene;
    lbm::FluidSettings fluid;
    lbm::GridShape shape;
    int column_cells = 0, height_cells = 0;  // the column in cells (a and h rounded to Δx)
    double frame_interval = 0.0, series_interval = 0.0, progress_interval = 0.0;
    bool report = true;
    std::filesystem::path out_dir;
};

[[nodiscard]] PreparedDamBreak prepare_dam_break(const CaseRequest& req, const Config& cfg);
void print_derived(const PreparedDamBreak& pc);
int run_dam_break(const CaseRequest& req, const Config& cfg);

}  // namespace sabo::app
