// SPDX-License-Identifier: MIT
#include "lbm/inlet.h"

#include <algorithm>
#include <utility>

namespace sabo::lbm {

template <class Real>
double hold_inlet(FluidLattice<Real>& l, std::span<const InletCell> cells, const Vec3& u) {
    const std::span<const CellType> types = std::as_const(l).cell_types();
    const std::span<double> mass = l.masses();
    const std::span<Real> fill = l.fill_fractions();
    constexpr double eps = FluidLattice<Real>::surface_epsilon;
    double added = 0.0;
    for (const InletCell& c : cells) {
        const std::size_t k = l.index(c.x, c.y, c.z);
        if (types[k] != CellType::fluid && types[k] != CellType::interface) continue;
        if (types[k] == CellType::fluid) {  // a fluid cell's mass is its density
            const double rho = l.density_at(c.x, c.y, c.z);
            added += c.rho - rho;
            l.set_equilibrium(c.x, c.y, c.z, c.rho, u);
            continue;
        }
        const double rho = l.surface_density(k);  // (the ρ of its λ)
        const double target = (c.top ? 1.0 : 1.0 + 2.0 * eps) * rho;
        if (target > mass[k]) {
            added += target - mass[k];
            mass[k] = target;
            fill[k] = static_cast<Real>(target / rho);
        }
    }
    int planes = 0;
    for (const InletCell& c : cells) planes = std::max(planes, c.x + 1);
    l.surface_edited(planes);
    return added;
}

template double hold_inlet(FluidLattice<float>&, std::span<const InletCell>, const Vec3&);
template double hold_inlet(FluidLattice<double>&, std::span<const InletCell>, const Vec3&);

}  // namespace sabo::lbm
