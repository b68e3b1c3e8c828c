// SPDX-License-Identifier: MIT
// Builders shared by the coupling tests: a lattice full of fluid at rest, a single grain, grains in the
// fluid as a run steps them (sim::Simulation's coupled step: the tests validate the production path), the
// fluid's momentum.
#pragma once
#include <memory>

#include "coupling/grain_fluid_coupling.h"
#include "dem/test_support.h"
#include "lbm/backends.h"
#include "lbm/fluid_lattice.h"
#include "lbm/units.h"
#include "sim/simulation.h"

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

// `grains` in `fluid` coupled as `sabo run` couples them, on one process: each sim.step() is the coupled
// step of a run (the grains' Δt must be the lattice's u.dt() / cs.substeps), the lattice on `backend`.
inline sim::Simulation coupled_run(dem::DemSolver grains, std::unique_ptr<lbm::FluidLattice<double>> fluid,
                                   const coupling::CouplingSettings& cs, const lbm::UnitConverter& u,
                                   lbm::Backend backend = lbm::Backend::cpu) {
    sim::Simulation run(std::move(grains), std::move(fluid), coupling::GrainFluidCoupling(cs, u, {}), u.dt(),
                        parallel::Domain{});
    if (backend == lbm::Backend::opencl) run.run_fluid_on(lbm::test_device());
    return run;
}

// Σ ρ u over the fluid cells, lattice units (u the velocity of the collision: the pre-force momentum plus
// half the body force, which is 0 without gravity).
template <class Real>
Vec3 fluid_momentum(const lbm::FluidLattice<Real>& l) {
    Vec3 sum{};
    (void)l.totals([&](std::size_t, double rho, const Vec3& u) { sum += rho * u; });
    return sum;
}
// The same of a run's fluid, from the fields it shows (on either backend).
inline Vec3 fluid_momentum(const sim::Simulation& s) {
    const lbm::FluidFields& f = s.fluid_fields();
    Vec3 sum{};
    for (std::size_t c = 0; c < f.type.size(); ++c)
        if (f.type[c] == lbm::CellType::fluid || f.type[c] == lbm::CellType::interface)
            sum += f.density[c] * f.velocity[c];
    return sum;
}

}  // namespace sabo::test
