// SPDX-License-Identifier: MIT
// The relaxation time of a cell (docs/lbm.md), in lattice units. Newtonian: one τ. Bingham plastic:
// ν_app = ν_p + τ0/γ̇ from the local strain rate, τ = ½ + 3 ν_app, γ̇ = 0 ↦ τ_max, clamped to
// [τ_min, τ_max] (regularisation: an unyielded region is a very viscous fluid). The law is evaluated
// per cell in the collision (detail::collide_cell, src/lbm/collision.h).
#pragma once

namespace sabo::lbm {

struct Rheology {
    bool bingham = false;
    double tau = 0.8;         // Newtonian relaxation time
    double nu_plastic = 0.0;  // Bingham: η0/ρ_f in lattice units
    double yield = 0.0;       // Bingham: τ0/ρ_f in lattice units
    double tau_min = 0.501, tau_max = 1.8;
    // Smagorinsky constant of an optional eddy viscosity on top of either rheology (0: off, the reference
    // model's plain BGK); for runs whose thin high-speed sheets BGK cannot hold (docs/lbm.md)
    double smagorinsky = 0.0;
};

}  // namespace sabo::lbm
