// SPDX-License-Identifier: MIT
#include "coupling/grain_fluid_coupling.h"

#include <algorithm>

#include "core/error.h"

namespace sabo::coupling {

GrainFluidCoupling::GrainFluidCoupling(const CouplingSettings& settings, const lbm::UnitConverter& units,
                                       const Vec3& origin)
    : settings_(settings), units_(units), origin_(origin) {
    if (settings_.substeps < 1) throw InputError("coupling: at least one DEM step per lattice step");
}

template <class Real>
void GrainFluidCoupling::before_fluid_step(const dem::Particles& p, lbm::FluidLattice<Real>& lattice) {
    const lbm::GridShape& sh = lattice.shape();
    const LatticeFrame frame{origin_,
                             units_.dx(),
                             sh.nx,
                             sh.ny,
                             sh.nz,
                             lattice.index(0, 1, 0) - lattice.index(0, 0, 0),
                             lattice.index(0, 0, 1) - lattice.index(0, 0, 0)};
    finder_.find(p, frame);
    const auto& found = finder_.cells();
    lattice_cells_.resize(found.size());
    weight_.resize(found.size());
    const auto n = static_cast<std::ptrdiff_t>(found.size());
#pragma omp parallel for schedule(static) if (n > 8192)
    for (std::ptrdiff_t g = 0; g < n; ++g) {
        const CoveredCell& c = found[g];
        // the grain's surface velocity at the cell's centre, v + ω × (x − x_p)
        const Vec3 v = p.v[c.grain] + cross(p.w[c.grain], c.centre - p.x[c.grain]);
        lattice_cells_[g] = {c.cell, Vec3{units_.velocity(v.x), units_.velocity(v.y), units_.velocity(v.z)}};
        // 1 fluid, λ interface, 0 gas and obstacle: the lattice's drag weight
        weight_[g] = lattice.coupling_weight(c.cell);
    }
    lattice.set_grain_cells(lattice_cells_);
}

template <class Real>
void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<Real>& lattice, dem::DemSolver& grains) {
    const auto& found = finder_.cells();
    const auto& h = lattice.grain_cell_forces();
    const dem::Particles& p = grains.particles();
    std::vector<Vec3>&force = force_, &torque = torque_;
    force.assign(p.n_mobile, Vec3{});
    torque.assign(p.n_mobile, Vec3{});
    const double to_newton = units_.force_si(1.0);
    const double cell_volume = units_.dx() * units_.dx() * units_.dx();
    const Vec3 weight_of_volume = settings_.gravity * units_.density();  // ρ_f g, N/m³
    totals_ = {};
    totals_.cells = found.size();
    // cells in ascending order: each grain's sums in a fixed order, whatever the thread count
    for (std::size_t g = 0; g < found.size(); ++g) {
        const CoveredCell& c = found[g];
        const Vec3 f = h[g] * to_newton;
        force[c.grain] += f;
        torque[c.grain] += cross(c.centre - p.x[c.grain], f);
        totals_.drag += f;
        if (settings_.buoyancy) {
            const Vec3 b = weight_of_volume * (-weight_[g] * cell_volume);
            force[c.grain] += b;
            totals_.buoyancy += b;
        }
    }
    grains.set_external_forces(force, torque);
}

template <class Real>
void GrainFluidCoupling::step(lbm::FluidLattice<Real>& lattice, dem::DemSolver& grains) {
    before_fluid_step(grains.particles(), lattice);
    lattice.step();
    after_fluid_step(lattice, grains);
    for (int k = 0; k < settings_.substeps; ++k) grains.step();
}

template void GrainFluidCoupling::before_fluid_step(const dem::Particles&, lbm::FluidLattice<float>&);
template void GrainFluidCoupling::before_fluid_step(const dem::Particles&, lbm::FluidLattice<double>&);
template void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<float>&, dem::DemSolver&);
template void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<double>&, dem::DemSolver&);
template void GrainFluidCoupling::step(lbm::FluidLattice<float>&, dem::DemSolver&);
template void GrainFluidCoupling::step(lbm::FluidLattice<double>&, dem::DemSolver&);

}  // namespace sabo::coupling
