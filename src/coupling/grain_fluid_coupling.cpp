// SPDX-License-Identifier: MIT
#include "coupling/grain_fluid_coupling.h"

#include <algorithm>
#include <numbers>

#include "core/error.h"

namespace sabo::coupling {

GrainFluidCoupling::GrainFluidCoupling(const CouplingSettings& settings, const lbm::UnitConverter& units,
                                       const Vec3& origin)
    : settings_(settings), units_(units), origin_(origin) {
    if (settings_.substeps < 1) throw InputError("coupling: at least one DEM step per lattice step");
}

void GrainFluidCoupling::share_volumes(const LatticeFrame& frame) {
    if (!settings_.buoyancy || settings_.volume != BuoyancyVolume::sphere) return;
    volume_per_cell_.resize(x_.size());
    const auto n = static_cast<std::ptrdiff_t>(x_.size());
    // (each grain its own: the same for any thread count)
#pragma omp parallel for schedule(static) if (n > 256)
    for (std::ptrdiff_t sg = 0; sg < n; ++sg) {
        const auto g = static_cast<std::size_t>(sg);
        const double covered = cells_covered_alone(x_[g], r_[g], frame, settings_.model);
        const double volume = 4.0 / 3.0 * std::numbers::pi * r_[g] * r_[g] * r_[g];
        volume_per_cell_[g] = covered > 0.0 ? volume / covered : 0.0;
    }
}

void GrainFluidCoupling::take_grains(const dem::Particles& p, std::size_t own,
                                     std::span<const VisitingGrain> visitors) {
    const std::size_t n = own + visitors.size();
    x_.resize(n), v_.resize(n), w_.resize(n), r_.resize(n);
    std::copy_n(p.x.begin(), own, x_.begin());
    std::copy_n(p.v.begin(), own, v_.begin());
    std::copy_n(p.w.begin(), own, w_.begin());
    std::copy_n(p.r.begin(), own, r_.begin());
    for (std::size_t k = 0; k < visitors.size(); ++k) {
        const VisitingGrain& g = visitors[k];
        x_[own + k] = g.x, v_[own + k] = g.v, w_[own + k] = g.w, r_[own + k] = g.r;
    }
}

template <class Real>
LatticeFrame GrainFluidCoupling::frame_of(const lbm::FluidLattice<Real>& lattice) const {
    const lbm::GridShape& sh = lattice.shape();
    return {origin_ + Vec3{lattice.first_global_x() * units_.dx(), 0.0, 0.0},
            units_.dx(),
            sh.nx,
            sh.ny,
            sh.nz,
            lattice.index(0, 1, 0) - lattice.index(0, 0, 0),
            lattice.index(0, 0, 1) - lattice.index(0, 0, 0)};
}

template <class Real>
void GrainFluidCoupling::before_fluid_step(const dem::Particles& p, std::size_t own,
                                           std::span<const VisitingGrain> visitors,
                                           lbm::FluidLattice<Real>& lattice) {
    take_grains(p, own, visitors);
    const LatticeFrame frame = frame_of(lattice);
    finder_.find(x_, r_, frame, settings_.model);
    share_volumes(frame);
    const auto& found = finder_.cells();
    const bool partial = settings_.model == CoverRule::psm;
    lattice_cells_.resize(found.size());
    weight_.resize(found.size());
    const auto cells = static_cast<std::ptrdiff_t>(found.size());
#pragma omp parallel for schedule(static) if (cells > 8192)
    for (std::ptrdiff_t g = 0; g < cells; ++g) {
        const CoveredCell& c = found[g];
        // the grain's surface velocity at the cell's centre, v + ω × (x − x_p)
        const Vec3 v = v_[c.grain] + cross(w_[c.grain], c.centre - x_[c.grain]);
        lattice_cells_[g] = {c.cell, Vec3{units_.velocity(v.x), units_.velocity(v.y), units_.velocity(v.z)},
                             c.fraction};
        // the share of the cell's volume whose weight the buoyancy term supplies: λ (1 fluid, the fill in
        // interface cells, 0 gas and obstacle) times the solid fraction, less, with partially saturated
        // cells, the share B whose weight the exchange itself carries (its fluid is not weighed:
        // detail::collide_cell)
        const double carried = partial ? lbm::saturation_weight(c.fraction, lattice.tau(c.cell)) : 0.0;
        weight_[g] = lattice.coupling_weight(c.cell) * (c.fraction - carried);
    }
    lattice.set_solid_cells(lattice_cells_, partial ? lbm::SolidExchange::psm : lbm::SolidExchange::drag);
}

template <class Real>
void GrainFluidCoupling::find_forces(const lbm::FluidLattice<Real>& lattice) {
    const auto& found = finder_.cells();
    const auto& h = lattice.solid_cell_forces();
    force_.assign(x_.size(), Vec3{});
    torque_.assign(x_.size(), Vec3{});
    buoyancy_.assign(x_.size(), Vec3{});
    const double to_newton = units_.force_si(1.0);
    const double cell_volume = units_.dx() * units_.dx() * units_.dx();
    const Vec3 weight_of_volume = settings_.gravity * units_.density();  // ρ_f g, N/m³
    totals_ = {};
    // a slab's ghost planes are stepped with their grain cells too (what streams from them into the own
    // planes must be right), but their forces are the neighbour's, who owns those planes
    const bool slab = lattice.own_begin() > 0 || lattice.own_end() < lattice.shape().nx;
    // cells in ascending order: each grain's sums in a fixed order, whatever the thread count
    for (std::size_t g = 0; g < found.size(); ++g) {
        const CoveredCell& c = found[g];
        if (slab && !lattice.own_plane(c.cell)) continue;
        ++totals_.cells;
        const Vec3 f = h[g] * to_newton;
        force_[c.grain] += f;
        torque_[c.grain] += cross(c.centre - x_[c.grain], f);
        totals_.drag += f;
        if (settings_.buoyancy) {
            const double per_cell =
                settings_.volume == BuoyancyVolume::sphere ? volume_per_cell_[c.grain] : cell_volume;
            const Vec3 b = weight_of_volume * (-weight_[g] * per_cell);
            force_[c.grain] += b;
            buoyancy_[c.grain] += b;
            totals_.buoyancy += b;
        }
    }
}

template <class Real>
void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<Real>& lattice, dem::DemSolver& grains) {
    find_forces(lattice);
    grains.set_external_forces(force_, torque_);
}

template <class Real>
void GrainFluidCoupling::before_device_step(const dem::Particles& p, std::size_t own,
                                            std::span<const VisitingGrain> visitors,
                                            const lbm::FluidLattice<Real>& lattice,
                                            opencl::DeviceGrainCells& cells) {
    take_grains(p, own, visitors);
    const LatticeFrame frame = frame_of(lattice);
    cells.find(x_, r_, frame);
    cells.cover(v_, w_, units_.dt());
    share_volumes(frame);
}

void GrainFluidCoupling::find_forces(opencl::DeviceGrainCells& cells) {
    const opencl::DeviceGrainCells::GrainSums& sums = cells.sums();
    const std::size_t n = x_.size();
    force_.assign(n, Vec3{});
    torque_.assign(n, Vec3{});
    buoyancy_.assign(n, Vec3{});
    const double to_newton = units_.force_si(1.0);
    const double cell_volume = units_.dx() * units_.dx() * units_.dx();
    const Vec3 weight_of_volume = settings_.gravity * units_.density();  // ρ_f g, N/m³
    totals_ = {};
    for (std::size_t g = 0; g < n; ++g) {
        force_[g] = sums.force[g] * to_newton;
        torque_[g] = sums.torque[g] * to_newton;
        totals_.drag += force_[g];
        totals_.cells += static_cast<std::size_t>(sums.cells[g]);
        if (!settings_.buoyancy) continue;
        const double per_cell =
            settings_.volume == BuoyancyVolume::sphere ? volume_per_cell_[g] : cell_volume;
        buoyancy_[g] = weight_of_volume * (-sums.buoyancy_weight[g] * per_cell);
        force_[g] += buoyancy_[g];
        totals_.buoyancy += buoyancy_[g];
    }
}

template void GrainFluidCoupling::before_fluid_step(const dem::Particles&, std::size_t,
                                                    std::span<const VisitingGrain>,
                                                    lbm::FluidLattice<float>&);
template void GrainFluidCoupling::before_fluid_step(const dem::Particles&, std::size_t,
                                                    std::span<const VisitingGrain>,
                                                    lbm::FluidLattice<double>&);
template void GrainFluidCoupling::before_device_step(const dem::Particles&, std::size_t,
                                                     std::span<const VisitingGrain>,
                                                     const lbm::FluidLattice<float>&,
                                                     opencl::DeviceGrainCells&);
template void GrainFluidCoupling::before_device_step(const dem::Particles&, std::size_t,
                                                     std::span<const VisitingGrain>,
                                                     const lbm::FluidLattice<double>&,
                                                     opencl::DeviceGrainCells&);
template void GrainFluidCoupling::find_forces(const lbm::FluidLattice<float>&);
template void GrainFluidCoupling::find_forces(const lbm::FluidLattice<double>&);
template void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<float>&, dem::DemSolver&);
template void GrainFluidCoupling::after_fluid_step(const lbm::FluidLattice<double>&, dem::DemSolver&);

}  // namespace sabo::coupling
