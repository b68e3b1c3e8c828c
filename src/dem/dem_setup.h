// SPDX-License-Identifier: MIT
// Reads the [contact] and [dem] sections of a case into contact laws and a time step, and derives
// the stability numbers printed by `sabo check` (docs/dem.md, docs/calibration.md; docs/case_files.md).
#pragma once
#include <string>

#include "core/config.h"
#include "dem/dem_solver.h"

namespace sabo::dem {

// What the scenario knows about its grains and their speed, for contact-time estimates.
struct GrainScale {
    double r_min = 0.0;           // m
    double r_max = 0.0;           // m
    double density = 0.0;         // kg/m³
    double velocity_scale = 0.0;  // m/s, largest expected grain speed (v_rel = 2 v_max for impacts)
};

// Largest Verlet skin of a fast grain over its diameter, by default (dem.skin_max_over_d).
inline constexpr double default_skin_max_over_d = 0.5;

struct DemSettings {
    AnyContactLaws laws;
    std::string normal_model;
    double contact_time = 0.0;       // s, shortest over the interaction classes
    double dt = 0.0;                 // s
    double steps_per_contact = 0.0;  // t_c / Δt
    double skin = 0.0;               // m
    double skin_max = 0.0;           // m, largest skin of a fast grain (DemSolver::set_skin_max)
    RollingModel rolling_model = RollingModel::constraint;
    int rolling_sweeps = 1;     // Jacobi sweeps of the rolling impulses per half step
    int reorder_interval = 20;  // list builds between spatial sorts of the grains (0: never)
    double restitution = 0.0;   // input ζ (particle–particle)
    std::string restitution_meaning = "dashpot";  // ζ sets the dashpot, or is the rebound achieved
    double effective_restitution = 0.0;           // with attractive forces clipped (particle–particle)
    double expected_max_overlap_ratio = 0.0;      // δ_max / d_min for a head-on impact at 2 v_max
    double overlap_limit = 0.5;                   // δ / d at which a run stops as failed
};

// A solver with these settings (laws, Δt, skin, rolling sweeps, reorder interval).
[[nodiscard]] DemSolver make_solver(Particles particles, std::vector<Wall> walls, const Vec3& gravity,
                                    const DemSettings& settings);

// One line for the log: normal law, restitution asked and achieved, rolling model.
[[nodiscard]] std::string describe_contact(const DemSettings& settings);

// Throws InputError with the key and range on bad input, or when Δt > t_c/10.
[[nodiscard]] DemSettings read_dem_settings(const Config& cfg, const GrainScale& grains);

}  // namespace sabo::dem
