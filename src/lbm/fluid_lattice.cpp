// SPDX-License-Identifier: MIT
#include "lbm/fluid_lattice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "lbm/collision.h"

namespace sabo::lbm {

using detail::Batch;
using detail::collide;
using detail::lanes;
using detail::returned;

template <class Real>
FluidLattice<Real>::FluidLattice(const GridShape& shape, const Rheology& rheology)
    : shape_(shape), rheology_(rheology), n_(shape.cells()) {
    if (shape.nx < 1 || shape.ny < 1 || shape.nz < 1)
        throw InputError(fmt::format("lattice of {} x {} x {} cells", shape.nx, shape.ny, shape.nz));
    if (!(rheology.tau_min > 0.5) || rheology.tau_max < rheology.tau_min)
        throw InputError(fmt::format("lattice: need 0.5 < tau_min <= tau_max (got {}, {})", rheology.tau_min,
                                     rheology.tau_max));
    if (!rheology.bingham && !(rheology.tau > 0.5))
        throw InputError(fmt::format("lattice: tau = {} must exceed 0.5", rheology.tau));
    f_.assign(Q * n_, Real(0));
    tau_.assign(n_, static_cast<Real>(rheology.bingham ? rheology.tau_max : rheology.tau));
    type_.assign(n_, CellType::gas);
    near_wall_.assign(n_, 0);
    element_.assign(n_, 0);
    fill_.assign(n_, Real(0));
    mass_.assign(n_, 0.0);
    element_velocity_.assign(1, Vec3{});
    element_force_.assign(1, Vec3{});
    for (int i = 0; i < Q; ++i) {
        offset_[static_cast<std::size_t>(i)] =
            cx[i] +
            static_cast<std::ptrdiff_t>(shape.nx) * (cy[i] + static_cast<std::ptrdiff_t>(shape.ny) * cz[i]);
    }
}

template <class Real>
std::uint16_t FluidLattice<Real>::add_element(const Vec3& wall_velocity) {
    if (element_velocity_.size() >= 65535) throw InputError("more than 65535 obstacle elements");
    element_velocity_.push_back(wall_velocity);
    element_force_.push_back({});
    return static_cast<std::uint16_t>(element_velocity_.size() - 1);
}

template <class Real>
void FluidLattice<Real>::set_obstacle(int x, int y, int z, std::uint16_t element) {
    if (element >= element_velocity_.size()) throw InputError(fmt::format("no obstacle element {}", element));
    const std::size_t k = index(x, y, z);
    type_[k] = CellType::obstacle;
    element_[k] = element;
    fill_[k] = Real(0);
    mass_[k] = 0.0;
    interface_.clear();  // rebuilt by prepare()
}

template <class Real>
void FluidLattice<Real>::set_fluid(int x, int y, int z, double rho, const Vec3& u) {
    // the populations are stored in the even steps' layout (own slots)
    if (steps_ % 2 == 1) throw InputError("set_fluid() is only possible after an even number of steps");
    const std::size_t k = index(x, y, z);
    type_[k] = CellType::fluid;
    fill_[k] = Real(1);
    mass_[k] = rho;
    for (int i = 0; i < Q; ++i)
        f_[static_cast<std::size_t>(i) * n_ + k] =
            static_cast<Real>(detail::equilibrium(i, rho, u) - weight[i]);
}

template <class Real>
void FluidLattice<Real>::set_interface(int x, int y, int z, double rho, const Vec3& u, double fill) {
    if (!(fill >= 0.0 && fill <= 1.0))
        throw InputError(fmt::format("interface fill fraction {} outside [0, 1]", fill));
    set_fluid(x, y, z, rho, u);
    const std::size_t k = index(x, y, z);
    type_[k] = CellType::interface;
    fill_[k] = static_cast<Real>(fill);
    mass_[k] = fill * rho;
    interface_.clear();  // rebuilt by prepare()
}

template <class Real>
std::ptrdiff_t FluidLattice<Real>::neighbour(int x, int y, int z, int i, int sign) const {
    int p[3] = {x + sign * cx[i], y + sign * cy[i], z + sign * cz[i]};
    const int n[3] = {shape_.nx, shape_.ny, shape_.nz};
    for (int a = 0; a < 3; ++a) {
        if (p[a] >= 0 && p[a] < n[a]) continue;
        if (!shape_.periodic[static_cast<std::size_t>(a)]) return -1;
        p[a] = (p[a] + n[a]) % n[a];
    }
    return static_cast<std::ptrdiff_t>(index(p[0], p[1], p[2]));
}

template <class Real>
void FluidLattice<Real>::prepare() {
    for (int z = 0; z < shape_.nz; ++z) {
        for (int y = 0; y < shape_.ny; ++y) {
            for (int x = 0; x < shape_.nx; ++x) {
                const std::size_t k = index(x, y, z);
                std::uint8_t near = 0;
                // a cell on the domain's edge always takes the general path (wrap or wall)
                if (x == 0 || y == 0 || z == 0 || x == shape_.nx - 1 || y == shape_.ny - 1 ||
                    z == shape_.nz - 1)
                    near = 1;
                for (int i = 1; i < Q && near == 0; ++i) near = solid(neighbour(x, y, z, i, 1)) ? 1 : 0;
                near_wall_[k] = near;
            }
        }
    }
    plane_force_.assign(static_cast<std::size_t>(shape_.nz) * element_velocity_.size(), Vec3{});
    // fluid must not touch gas: a fluid cell with a gas neighbour becomes a full interface cell
    std::vector<std::size_t> wet;
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y)
            for (int x = 0; x < shape_.nx; ++x) {
                const std::size_t k = index(x, y, z);
                if (type_[k] != CellType::fluid) continue;
                for (int i = 1; i < Q; ++i) {
                    const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
                    if (n >= 0 && type_[static_cast<std::size_t>(n)] == CellType::gas) {
                        wet.push_back(k);
                        break;
                    }
                }
            }
    for (const std::size_t k : wet) {
        double rho = 0.0;
        Vec3 u;
        moments(k, rho, u);
        type_[k] = CellType::interface;
        fill_[k] = Real(1);
        mass_[k] = rho;
    }
    interface_.clear();
    for (std::size_t k = 0; k < n_; ++k)
        if (type_[k] == CellType::interface) interface_.push_back(static_cast<std::uint32_t>(k));
    const std::size_t ni = interface_.size();
    surface_rho_.resize(ni);
    surface_u_.resize(ni);
    for (std::size_t s = 0; s < ni; ++s) {  // the state set_interface() gave them
        const std::size_t k = interface_[s];
        const auto [x, y, z] = shape_.coords(k);
        double rho = 0.0;
        Vec3 j{};
        for (int i = 0; i < Q; ++i) {
            const double fi = incoming(x, y, z, k, i);
            rho += fi;
            j += Vec3{cx[i] * fi, cy[i] * fi, cz[i] * fi};
        }
        surface_rho_[s] = rho;
        surface_u_[s] = (j + 0.5 * rho * accel_) / rho;
    }
    prepare_surface();
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::gather(int x, int y, int z, std::size_t k, double* f, std::size_t stride) const {
    if constexpr (!Odd) {
        for (int i = 0; i < Q; ++i)
            f[static_cast<std::size_t>(i) * stride] =
                static_cast<double>(f_[static_cast<std::size_t>(i) * n_ + k]) + weight[i];
    } else {
        // f_i(x) arrives from x − c_i, where the even step stored it in slot ī; from an obstacle it is
        // this cell's own f_ī*, bounced back (stored in its own slot i), plus the moving-wall term
        for (int i = 0; i < Q; ++i) {
            const auto ui = static_cast<std::size_t>(i);
            const std::ptrdiff_t src = neighbour(x, y, z, i, -1);
            double& fi = f[ui * stride];
            if (solid(src)) {
                fi = returned(static_cast<double>(f_[ui * n_ + k]) + weight[i], opposite(i),
                              element_velocity_[element_of(src)]);
            } else {
                fi = static_cast<double>(
                         f_[static_cast<std::size_t>(opposite(i)) * n_ + static_cast<std::size_t>(src)]) +
                     weight[i];
            }
        }
    }
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::stream_collide() {
    const std::size_t n_elem = element_velocity_.size();
    std::uint64_t at_min = 0, at_max = 0;
    const auto nx = static_cast<std::size_t>(shape_.nx);
#pragma omp parallel reduction(+ : at_min, at_max) if (n_ >= 16384)  // small lattices: not worth a team
    {
        Batch run;   // contiguous interior cells
        Batch wall;  // cells next to a wall or on the domain's edge, gathered one by one
#pragma omp for schedule(static)
        for (int z = 0; z < shape_.nz; ++z) {
            Vec3* plane = plane_force_.data() + static_cast<std::size_t>(z) * n_elem;
            for (std::size_t e = 0; e < n_elem; ++e) plane[e] = {};
            const auto count_clamps = [&](const Batch& b, int n) {
                if (!rheology_.bingham) return;
                for (int l = 0; l < n; ++l) {
                    at_min += b.clamped[l] < 0 ? 1 : 0;
                    at_max += b.clamped[l] > 0 ? 1 : 0;
                }
            };
            const auto flush_wall = [&] {
                collide(wall, wall.count, accel_, rheology_);
                count_clamps(wall, wall.count);
                for (int l = 0; l < wall.count; ++l) {
                    const std::size_t k = wall.k[l];
                    tau_[k] = static_cast<Real>(wall.tau[l]);
                    if (wall.surface[l] >= 0) {  // the density and velocity of the collision
                        const auto s = static_cast<std::size_t>(wall.surface[l]);
                        const double rho = wall.rho[l];
                        Vec3 j{};
                        for (int i = 0; i < Q; ++i)
                            j += Vec3{cx[i] * wall.f[i][l], cy[i] * wall.f[i][l], cz[i] * wall.f[i][l]};
                        surface_rho_[s] = rho;
                        surface_u_[s] = (j - 0.5 * rho * accel_) / rho;  // post-collision momentum is j + F
                    }
                    for (int i = 0; i < Q; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        const auto uo = static_cast<std::size_t>(opposite(i));
                        const double post = wall.f[i][l];
                        const std::ptrdiff_t dst = neighbour(wall.x[l], wall.y[l], z, i, 1);
                        if (solid(dst)) {  // bounce-back: back into this cell as ī next step
                            const std::uint16_t e = element_of(dst);
                            const double back = returned(post, i, element_velocity_[e]);
                            // momentum given to the obstacle along c_i, less that of the fluid at rest at
                            // the atmospheric density (2 w_i): the force relative to the atmosphere, which
                            // pushes on the obstacle's dry side (the gauge force; for a fully wetted body the
                            // constant term sums to zero anyway)
                            const double m = post + back - 2.0 * weight[i];
                            plane[e] += Vec3{cx[i] * m, cy[i] * m, cz[i] * m};
                            // even: stored as f_i*, the odd gather adds the wall term
                            f_[uo * n_ + k] = static_cast<Real>((Odd ? back : post) - weight[i]);
                        } else if constexpr (Odd) {
                            f_[ui * n_ + static_cast<std::size_t>(dst)] = static_cast<Real>(post - weight[i]);
                        } else {
                            f_[uo * n_ + k] = static_cast<Real>(post - weight[i]);
                        }
                    }
                }
                wall.count = 0;
            };
            for (int y = 0; y < shape_.ny; ++y) {
                const std::size_t row = index(0, y, z);
                std::size_t x = 0;
                while (x < nx) {
                    const std::size_t k = row + x;
                    const CellType type = type_[k];
                    if (type != CellType::fluid && type != CellType::interface) {
                        ++x;
                        continue;
                    }
                    if (near_wall_[k] != 0 || type == CellType::interface) {
                        const int l = wall.count++;
                        wall.x[l] = static_cast<int>(x);
                        wall.y[l] = y;
                        wall.k[l] = k;
                        wall.tau[l] = static_cast<double>(tau_[k]);
                        gather<Odd>(static_cast<int>(x), y, z, k, &wall.f[0][l], lanes);
                        wall.surface[l] = -1;
                        if (type == CellType::interface) {
                            const std::size_t s = surface_index(k);
                            wall.surface[l] = static_cast<int>(s);
                            reconstruct(static_cast<int>(x), y, z, s, &wall.f[0][l], lanes);
                            double rho = 0.0;
                            for (int i = 0; i < Q; ++i) rho += wall.f[i][l];
                            wall.rho[l] = rho;
                        }
                        if (wall.count == lanes) flush_wall();
                        ++x;
                        continue;
                    }
                    // a run of interior fluid cells: every neighbour is a fluid cell of the lattice, so
                    // each population's sources and destinations are contiguous
                    std::size_t end = x + 1;
                    while (end < nx && end - x < static_cast<std::size_t>(lanes) &&
                           type_[row + end] == CellType::fluid && near_wall_[row + end] == 0)
                        ++end;
                    const int n = static_cast<int>(end - x);
                    for (int i = 0; i < Q; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        const Real* src =
                            Odd ? f_.data() + static_cast<std::size_t>(opposite(i)) * n_ + k - offset_[ui]
                                : f_.data() + ui * n_ + k;
                        const double w = weight[i];
#pragma omp simd
                        for (int l = 0; l < n; ++l) run.f[i][l] = static_cast<double>(src[l]) + w;
                    }
                    for (int l = 0; l < n; ++l)
                        run.tau[l] = static_cast<double>(tau_[k + static_cast<std::size_t>(l)]);
                    if (n == lanes)
                        collide(run, lanes, accel_, rheology_);  // constant trip counts
                    else
                        collide(run, n, accel_, rheology_);
                    if (rheology_.bingham || rheology_.smagorinsky > 0.0)
                        for (int l = 0; l < n; ++l)
                            tau_[k + static_cast<std::size_t>(l)] = static_cast<Real>(run.tau[l]);
                    count_clamps(run, n);
                    for (int i = 0; i < Q; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        Real* dst = Odd ? f_.data() + ui * n_ + k + offset_[ui]
                                        : f_.data() + static_cast<std::size_t>(opposite(i)) * n_ + k;
                        const double w = weight[i];
#pragma omp simd
                        for (int l = 0; l < n; ++l) dst[l] = static_cast<Real>(run.f[i][l] - w);
                    }
                    x = end;
                }
            }
            if (wall.count > 0) flush_wall();
        }
    }
    clamps_ = {at_min, at_max};
    for (std::size_t e = 0; e < n_elem; ++e) {
        Vec3 sum{};
        for (int z = 0; z < shape_.nz; ++z) sum += plane_force_[static_cast<std::size_t>(z) * n_elem + e];
        element_force_[e] = sum;
    }
}

template <class Real>
void FluidLattice<Real>::step() {
    if (plane_force_.size() != static_cast<std::size_t>(shape_.nz) * element_velocity_.size()) prepare();
    if (steps_ % 2 == 0)
        stream_collide<false>();
    else
        stream_collide<true>();
    ++steps_;
    if (has_surface()) {
        exchange_mass();  // the populations just streamed across the interface links
        convert_cells();
        prepare_surface();
    }
}

template <class Real>
void FluidLattice<Real>::moments(std::size_t k, double& rho, Vec3& u) const {
    const auto [x, y, z] = shape_.coords(k);
    if (type_[k] == CellType::interface) {  // the last collision's (gas-side populations are not physical)
        const std::size_t s = surface_index(k);
        rho = surface_rho_[s];
        u = surface_u_[s];
        return;
    }
    double f[Q];
    if (steps_ % 2 == 0)
        gather<false>(x, y, z, k, f, 1);
    else
        gather<true>(x, y, z, k, f, 1);
    rho = 0.0;
    Vec3 j{};
    for (int i = 0; i < Q; ++i) {
        rho += f[i];
        j += Vec3{cx[i] * f[i], cy[i] * f[i], cz[i] * f[i]};
    }
    u = (j + 0.5 * rho * accel_) / rho;
}

template <class Real>
FluidTotals FluidLattice<Real>::totals() const {
    FluidTotals t;
    for (std::size_t k = 0; k < n_; ++k) {
        if (type_[k] != CellType::fluid && type_[k] != CellType::interface) continue;
        double rho = 0.0;
        Vec3 u;
        moments(k, rho, u);
        t.mass += type_[k] == CellType::interface ? mass_[k] : rho;
        t.max_speed = std::max(t.max_speed, norm(u));
    }
    return t;
}

template class FluidLattice<float>;
template class FluidLattice<double>;

}  // namespace sabo::lbm
