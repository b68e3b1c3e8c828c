// SPDX-License-Identifier: MIT
// A debris case's keys read and checked (case.type = "debris", reference case C5: the fluid alone, grains and
// fluid coupled, or the grains dry) and its derived numbers (`sabo check`).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "cases/common/gauge_settings.h"
#include "core/config.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_setup.h"
#include "lbm/fluid_setup.h"
#include "scenario/debris_case.h"
#include "sim/case_settings.h"

namespace sabo::cases {

struct PreparedDebris {
    scenario::DebrisCase scene;
    lbm::FluidSettings fluid;  // read (and checked) in a dry run too: its twin's
    lbm::GridShape shape;
    std::optional<dem::DemSettings> dem;  // with grains; coupled: Δt = Δt_LBM / n_sub
    coupling::CouplingSettings coupling;  // grains in the fluid
    sim::OutputSettings output;
    GaugeSettings gauge;       // the approaching flow's gauge section
    std::string dry_twin_dir;  // output.dry_twin_dir: a dry run of the same grains, drawn beside this one
    std::vector<std::size_t> mesh_cells;  // a barrier from a mesh: the lattice cells each part holds
    [[nodiscard]] bool grains() const { return scene.grains.count > 0 || scene.fed_grains; }
    [[nodiscard]] bool fluid_on() const { return !scene.dry; }
    [[nodiscard]] std::string mode() const { return !grains() ? "fluid" : (fluid_on() ? "coupled" : "dry"); }
};

[[nodiscard]] PreparedDebris prepare_debris(const sim::RunRequest& req, const Config& cfg);
void print_derived(const PreparedDebris& pc);
}  // namespace sabo::cases
