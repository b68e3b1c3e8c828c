// SPDX-License-Identifier: MIT
// A fluid box's keys read and checked (case.type = "fluid_box": grains at given places in a closed box full
// of fluid — settling, sedimentation, buoyancy) and its derived numbers (`sabo check`).
#pragma once
#include "core/config.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_setup.h"
#include "lbm/fluid_setup.h"
#include "scenario/fluid_box_case.h"
#include "sim/case_settings.h"

namespace sabo::cases {

struct PreparedFluidBox {
    scenario::FluidBoxCase scene;
    lbm::FluidSettings fluid;
    lbm::GridShape shape;
    dem::DemSettings dem;
    coupling::CouplingSettings coupling;
    sim::OutputSettings output;
    double average_from =
        0.0;  // s: the grains' velocities are averaged from here to the end (the last fifth)
};

[[nodiscard]] PreparedFluidBox prepare_fluid_box(const sim::RunRequest& req, const Config& cfg);
void print_derived(const PreparedFluidBox& pc);

}  // namespace sabo::cases
