// SPDX-License-Identifier: MIT
// An inflow boundary of the free-surface lattice: a set of cells held full of fluid at given densities (the
// hydrostatic ones of the inflow's column: at the rest density alone its bottom would draw the fluid back)
// moving at a given velocity. Between steps a fluid cell of the set is put back at equilibrium ρ, u; an
// interface cell is filled (ρ its last collision's, of its fill fraction): to (1 + 2ε) ρ (it converts to
// fluid at the next step and wets its gas neighbours: the inflow's front advances) or, on the set's top
// layer, to ρ (full, with its free surface kept there). Gas cells of the set wait until the fluid reaches
// them. The free surface's normals are then read again from the edited fill (FluidLattice::surface_edited:
// what a restored checkpoint reads). The mass this adds (or, at a cell above the rest density, takes) is
// returned: the lattice's mass grows by exactly the inflow's sum.
#pragma once
#include <span>

#include "core/vec3.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

struct InletCell {
    int x = 0, y = 0, z = 0;
    bool top = false;  // on the set's top layer: filled to ρ, not beyond
    double rho = 1.0;  // the density it is held at: the column's hydrostatic one (its pressure at that depth)
};

// Holds `cells` (lattice coordinates) at their ρ, velocity u (lattice units); returns the mass added, lattice
// units.
template <class Real>
double hold_inlet(FluidLattice<Real>& lattice, std::span<const InletCell> cells, const Vec3& u);

}  // namespace sabo::lbm
