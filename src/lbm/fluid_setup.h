// SPDX-License-Identifier: MIT
// The fluid part of a case file (docs/case_files.md, [fluid] and [lattice]) turned into lattice
// units: one converter, the rheology in lattice units, the storage type, and the checks of docs/lbm.md
// (refusals with file, key and range; warnings).
#pragma once
#include <string>
#include <vector>

#include "core/config.h"
#include "core/error.h"
#include "lbm/fluid_lattice.h"
#include "lbm/opencl/devices.h"
#include "lbm/rheology.h"
#include "lbm/units.h"

namespace sabo::lbm {

struct FluidSettings {
    UnitConverter units{1.0, 1.0, 1.0};
    Rheology rheology;          // lattice units
    std::string rheology_name;  // "newtonian" | "bingham"
    double viscosity = 0.0;     // Pa·s: η, or η0 (Bingham)
    double yield_stress = 0.0;  // Pa (Bingham)
    bool single_precision = false;
    // lattice.device: the CPU lattice, or the OpenCL one on `opencl_device` (docs/lbm.md, "Backends")
    bool on_opencl = false;
    opencl::DeviceInfo opencl_device;
    std::uint64_t opencl_bytes = 0;  // the device memory the lattice needs (an estimate before its walls)
    double max_mass_drift = 1e-6;    // |M − M0| / M0 at which a run stops as failed
    // lattice.pocket_reach_cells: where an enclosed cell's deficit comes from
    // (FluidLattice::set_pocket_reach; 0: the whole surface); the case key's default
    int pocket_reach = 3;
    LatticeRequest request;
    LatticeNumbers numbers;
};

// What the case knows before reading the fluid keys: its fastest flow and its lattice size.
struct FluidScale {
    double velocity_m_s = 0.0;
    double gravity_m_s2 = 0.0;  // |g|, and the deepest the fluid stands at rest, m (0: the lattice's height):
    double depth_m = 0.0;       // the hydrostatic check
    GridShape shape;            // the lattice (its cells: 0 until the geometry is known)
    double grain_d_mean_m = 0.0, grain_d_min_m = 0.0;
    std::string velocity_key;  // the case key that sets velocity_m_s (empty: derived only), for messages
};

// Reads [fluid] and [lattice] (dx_m, dt_s are the lattice); `nodes` may be 0 and set later with
// finish_fluid_settings() once the geometry (which needs Δx) is known.
[[nodiscard]] FluidSettings read_fluid_settings(const Config& cfg);
// The checks of docs/lbm.md for this scale (throws InputError naming the file); records the derived
// numbers in the resolved case.
void check_fluid_settings(const Config& cfg, FluidSettings& fs, const FluidScale& scale,
                          double memory_available_bytes);
// The start-up printout lines (Δx, Δt, τ, ν_LB, u_LB, Mach, nodes, memory per cell); warnings() apart.
[[nodiscard]] std::vector<std::string> describe(const FluidSettings& fs);
// The checks' warnings for these settings (compressibility, resolution), to be logged as warnings.
[[nodiscard]] const std::vector<std::string>& warnings(const FluidSettings& fs);

// Throws RunError when the fluid has become unstable: mass no longer finite or drifted beyond
// `max_mass_drift` (relative), or a lattice speed above 0.5 (BGK is far beyond its range there).
void check_fluid_stable(double time, double mass_drift, double lattice_speed, double max_mass_drift);

}  // namespace sabo::lbm
