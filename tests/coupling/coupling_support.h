// SPDX-License-Identifier: MIT
// Builders shared by the coupling tests: a lattice full of fluid at rest, a single grain, the fluid's
// momentum.
#pragma once
#include <memory>

#include "coupling/grain_fluid_coupling.h"
#include "dem/test_support.h"
#include "lbm/fluid_lattice.h"
#include "lbm/units.h"

namespace sabo::test {

// Every cell fluid at rest (lattice density 1).
inline std::unique_ptr<lbm::FluidLattice<double>> full_lattice(const lbm::GridShape& shape, double tau) {
    lbm::Rheology rh;
    rh.tau = tau;
    auto l = std::make_unique<lbm::FluidLattice<double>>(shape, rh);
    for (int z = 0; z < shape.nz; ++z)
        for (int y = 0; y < shape.ny; ++y)
            for (int x = 0; x < shape.nx; ++x) l->set_fluid(x, y, z, 1.0, {});
    l->prepare();
    return l;
}

// One grain, no walls, frictionless law (nothing to touch).
inline dem::DemSolver one_grain(const Vec3& x, double r, double rho, const Vec3& v, const Vec3& gravity,
                                double dt) {
    dem::Particles p;
    p.add_mobile(x, r, rho, v);
    return dem::DemSolver(p, {}, same_everywhere(linear_law({})), gravity, dt, 0.1 * r);
}

// Σ ρ u over the fluid cells, lattice units (u the velocity of the collision: the pre-force momentum plus
// half the body force, which is 0 without gravity).
inline Vec3 fluid_momentum(const lbm::FluidLattice<double>& l) {
    Vec3 sum{};
    (void)l.totals([&](std::size_t, double rho, const Vec3& u) { sum += rho * u; });
    return sum;
}

}  // namespace sabo::test
