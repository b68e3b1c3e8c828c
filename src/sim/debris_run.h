// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for debris in the channel (case.type = "debris", CASES C5): the fluid
// block released against the barrier; the fluid force on the barrier (history, per element) and the
// fluid non-retained fraction.
#pragma once
#include <filesystem>

#include "core/config.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_setup.h"
#include "scenario/debris_case.h"
#include "sim/case_setup.h"

namespace sabo::sim {

struct PreparedDebris {
    scenario::DebrisCase scene;
    lbm::FluidSettings fluid;
    lbm::GridShape shape;
    OutputSettings output;
    double checkpoint_interval = 0.0;  // wall-clock s between checkpoints (0: at the end only)
    bool resume = false;               // continue from out_dir/checkpoint.bin
    std::string identity;              // the resolved case but its end time: what a checkpoint must match
};

[[nodiscard]] PreparedDebris prepare_debris(const RunRequest& req, const Config& cfg);
void print_derived(const PreparedDebris& pc);
int run_debris(const RunRequest& req, const Config& cfg);

}  // namespace sabo::sim
