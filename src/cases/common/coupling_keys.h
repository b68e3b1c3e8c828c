// SPDX-License-Identifier: MIT
// The [coupling] keys of a case with grains in the fluid (docs/case_files.md): the DEM sub-steps of one
// lattice step (at least as many as the contact's step needs, at most max_substeps; the DEM step becomes
// Δt_LBM / n_sub), which cells a grain covers (the model), buoyancy and its volume. One physics once: the
// coupling's gravity is the case's.
#pragma once
#include "core/config.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_setup.h"
#include "lbm/fluid_setup.h"

namespace sabo::cases {

// The most DEM sub-steps one lattice step may take (a longer lattice step: refused, reduce lattice.dt_s).
inline constexpr int max_substeps = 100;

// Reads the keys, sets dem.dt (and steps_per_contact) to the sub-step, records the derived numbers, and warns
// (into fluid.numbers.warnings) of grains no denser than the fluid.
[[nodiscard]] coupling::CouplingSettings read_coupling_settings(const Config& cfg, lbm::FluidSettings& fluid,
                                                                dem::DemSettings& dem, const Vec3& gravity,
                                                                double grain_density);
// "cells whose centre a grain holds" or "partially saturated cells (solid fraction per cell)", for the log.
[[nodiscard]] const char* describe_model(const coupling::CouplingSettings& c);
// "off", "on (the sphere's volume)" or "on (the covered cells' volume)", for the log.
[[nodiscard]] const char* describe_buoyancy(const coupling::CouplingSettings& c);
// A case without the coupling (the fluid alone, or grains dry): its keys may stay in the file.
void accept_unused_coupling_keys(const Config& cfg);

}  // namespace sabo::cases
