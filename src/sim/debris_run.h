// SPDX-License-Identifier: MIT
// `sabo run` and `sabo check` for debris in the channel (case.type = "debris", CASES C5): the block of
// fluid with grains in it released against the barrier — the fluid alone (V_s/V_box = 0), grains and
// fluid coupled, or the same grains dry (debris.dry). The barrier's solid, fluid and total force (history,
// per element) and the solid and fluid non-retained fractions.
#pragma once
#include <filesystem>
#include <optional>
#include <vector>

#include "core/config.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_setup.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_setup.h"
#include "scenario/debris_case.h"
#include "sim/case_setup.h"
#include "sim/simulation.h"

namespace sabo::sim {

struct PreparedDebris {
    scenario::DebrisCase scene;
    lbm::FluidSettings fluid;  // read (and checked) in a dry run too: its twin's
    lbm::GridShape shape;
    std::optional<dem::DemSettings> dem;  // with grains; coupled: Δt = Δt_LBM / n_sub
    coupling::CouplingSettings coupling;  // grains in the fluid
    OutputSettings output;
    GaugeSettings gauge;       // the approaching flow's gauge section
    std::string dry_twin_dir;  // output.dry_twin_dir: a dry run of the same grains, drawn beside this one
    [[nodiscard]] bool grains() const { return scene.grains.count > 0; }
    [[nodiscard]] bool fluid_on() const { return !scene.dry; }
    [[nodiscard]] std::string mode() const { return !grains() ? "fluid" : (fluid_on() ? "coupled" : "dry"); }
};

// The most DEM sub-steps one lattice step may take (a longer lattice step: refused, reduce lattice.dt_s).
inline constexpr int max_substeps = 100;

[[nodiscard]] PreparedDebris prepare_debris(const RunRequest& req, const Config& cfg);
// The simulation of the case's mode: the fluid alone, grains and fluid coupled, or the grains dry;
// `barrier_cells` gets the lattice cells of each barrier element.
// Divided among the ranks of `world` when one is given (the fluid alone).
[[nodiscard]] Simulation debris_simulation(const PreparedDebris& pc, std::vector<std::size_t>& barrier_cells,
                                           const MpiWorld* world = nullptr);
void print_derived(const PreparedDebris& pc);
int run_debris(const RunRequest& req, const Config& cfg);

}  // namespace sabo::sim
