// SPDX-License-Identifier: MIT
// A dam-break case's keys read and checked (case.type = "dam_break": the free-surface fluid alone, its
// front compared with Martin & Moyce 1952) and its derived numbers (`sabo check`).
#pragma once
#include "core/config.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_setup.h"
#include "scenario/dam_break_case.h"
#include "sim/case_settings.h"

namespace sabo::cases {

struct PreparedDamBreak {
    scenario::DamBreakCase scene;
    lbm::FluidSettings fluid;
    lbm::GridShape shape;
    int column_cells = 0, height_cells = 0;  // the column in cells (a and h rounded to Δx)
    sim::OutputSettings output;
};

[[nodiscard]] PreparedDamBreak prepare_dam_break(const sim::RunRequest& req, const Config& cfg);
void print_derived(const PreparedDamBreak& pc);
}  // namespace sabo::cases
