// SPDX-License-Identifier: MIT
#include "lbm/fluid_lattice.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"

namespace sabo::lbm {

namespace {

// BGK collision with Guo forcing of one cell's populations f (in place), force density F = ρ a.
// Returns the cell's new τ (Bingham: from the strain rate, with the previous τ in S_ab).
double collide(double* f, const Vec3& accel, const Rheology& rh, double tau_prev, int& clamped) {
    double rho = 0.0, jx = 0.0, jy = 0.0, jz = 0.0;
    for (int i = 0; i < Q; ++i) {
        rho += f[i];
        jx += cx[i] * f[i];
        jy += cy[i] * f[i];
        jz += cz[i] * f[i];
    }
    const double Fx = rho * accel.x, Fy = rho * accel.y, Fz = rho * accel.z;
    const double inv_rho = 1.0 / rho;
    const double ux = (jx + 0.5 * Fx) * inv_rho, uy = (jy + 0.5 * Fy) * inv_rho, uz = (jz + 0.5 * Fz) * inv_rho;
    const double uu = ux * ux + uy * uy + uz * uz;
    double feq[Q];
    for (int i = 0; i < Q; ++i) {
        const double cu = cx[i] * ux + cy[i] * uy + cz[i] * uz;
        feq[i] = weight[i] * rho * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * uu);
    }
    double tau = rh.tau;
    clamped = 0;
    if (rh.bingham) {
        // S_ab = −3/(2ρτ) [Σ c_a c_b (f − f^eq) + ½ (F_a u_b + u_a F_b)] (Krüger et al. 2009, Eq. 45)
        double pxx = 0, pyy = 0, pzz = 0, pxy = 0, pxz = 0, pyz = 0;
        for (int i = 0; i < Q; ++i) {
            const double d = f[i] - feq[i];
            pxx += cx[i] * cx[i] * d;
            pyy += cy[i] * cy[i] * d;
            pzz += cz[i] * cz[i] * d;
            pxy += cx[i] * cy[i] * d;
            pxz += cx[i] * cz[i] * d;
            pyz += cy[i] * cz[i] * d;
        }
        pxx += Fx * ux;
        pyy += Fy * uy;
        pzz += Fz * uz;
        pxy += 0.5 * (Fx * uy + ux * Fy);
        pxz += 0.5 * (Fx * uz + ux * Fz);
        pyz += 0.5 * (Fy * uz + uy * Fz);
        const double s = -1.5 / (rho * tau_prev);
        const double ss = pxx * pxx + pyy * pyy + pzz * pzz + 2.0 * (pxy * pxy + pxz * pxz + pyz * pyz);
        const double rate = std::abs(s) * std::sqrt(2.0 * ss);
        tau = rh.bingham_tau(rate, clamped);
    }
    const double omega = 1.0 / tau;
    const double guo = 1.0 - 0.5 * omega;
    for (int i = 0; i < Q; ++i) {
        const double cu = cx[i] * ux + cy[i] * uy + cz[i] * uz;
        const double cF = (3.0 * (cx[i] - ux) + 9.0 * cu * cx[i]) * Fx + (3.0 * (cy[i] - uy) + 9.0 * cu * cy[i]) * Fy +
                          (3.0 * (cz[i] - uz) + 9.0 * cu * cz[i]) * Fz;
        f[i] += -omega * (f[i] - feq[i]) + weight[i] * guo * cF;
    }
    return tau;
}

// Momentum the fluid gives an obstacle through link i (population f_i* leaving toward it), with the
// returning population f_i* − 6 w_i c_i·u_w (moving-wall bounce-back, reference density 1).
inline double returned(double post, int i, const Vec3& uw) {
    return post - 6.0 * weight[i] * (cx[i] * uw.x + cy[i] * uw.y + cz[i] * uw.z);
}

}  // namespace

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
    element_velocity_.assign(1, Vec3{});
    element_force_.assign(1, Vec3{});
    for (int i = 0; i < Q; ++i) {
        offset_[static_cast<std::size_t>(i)] =
            cx[i] + static_cast<std::ptrdiff_t>(shape.nx) * (cy[i] + static_cast<std::ptrdiff_t>(shape.ny) * cz[i]);
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
}

template <class Real>
void FluidLattice<Real>::set_fluid(int x, int y, int z, double rho, const Vec3& u) {
    // the populations are stored in the even steps' layout (own slots)
    if (steps_ % 2 == 1) throw InputError("set_fluid() is only possible after an even number of steps");
    const std::size_t k = index(x, y, z);
    type_[k] = CellType::fluid;
    const double uu = norm2(u);
    for (int i = 0; i < Q; ++i) {
        const double cu = cx[i] * u.x + cy[i] * u.y + cz[i] * u.z;
        const double feq = weight[i] * rho * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * uu);
        f_[static_cast<std::size_t>(i) * n_ + k] = static_cast<Real>(feq - weight[i]);
    }
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
                if (x == 0 || y == 0 || z == 0 || x == shape_.nx - 1 || y == shape_.ny - 1 || z == shape_.nz - 1)
                    near = 1;
                for (int i = 1; i < Q && near == 0; ++i) near = solid(neighbour(x, y, z, i, 1)) ? 1 : 0;
                near_wall_[k] = near;
            }
        }
    }
    plane_force_.assign(static_cast<std::size_t>(shape_.nz) * element_velocity_.size(), Vec3{});
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::gather(int x, int y, int z, std::size_t k, double* f) const {
    if constexpr (!Odd) {
        for (int i = 0; i < Q; ++i) f[i] = static_cast<double>(f_[static_cast<std::size_t>(i) * n_ + k]) + weight[i];
    } else {
        // f_i(x) arrives from x − c_i, where the even step stored it in slot ī; from an obstacle it is
        // this cell's own f_ī*, bounced back (stored in its own slot i), plus the moving-wall term
        const bool general = near_wall_[k] != 0;
        for (int i = 0; i < Q; ++i) {
            const auto ui = static_cast<std::size_t>(i);
            const std::ptrdiff_t src = general ? neighbour(x, y, z, i, -1) : static_cast<std::ptrdiff_t>(k) - offset_[ui];
            if (general && solid(src)) {
                const int o = opposite(i);
                f[i] = returned(static_cast<double>(f_[ui * n_ + k]) + weight[i], o, element_velocity_[element_of(src)]);
            } else {
                f[i] = static_cast<double>(f_[static_cast<std::size_t>(opposite(i)) * n_ + static_cast<std::size_t>(src)]) +
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
#pragma omp parallel for schedule(static) reduction(+ : at_min, at_max)
    for (int z = 0; z < shape_.nz; ++z) {
        Vec3* plane = plane_force_.data() + static_cast<std::size_t>(z) * n_elem;
        for (std::size_t e = 0; e < n_elem; ++e) plane[e] = {};
        double f[Q];
        for (int y = 0; y < shape_.ny; ++y) {
            for (int x = 0; x < shape_.nx; ++x) {
                const std::size_t k = index(x, y, z);
                if (type_[k] != CellType::fluid) continue;
                gather<Odd>(x, y, z, k, f);
                int clamped = 0;
                tau_[k] = static_cast<Real>(collide(f, accel_, rheology_, static_cast<double>(tau_[k]), clamped));
                at_min += clamped < 0 ? 1 : 0;
                at_max += clamped > 0 ? 1 : 0;
                const bool general = near_wall_[k] != 0;
                for (int i = 0; i < Q; ++i) {
                    const auto ui = static_cast<std::size_t>(i);
                    const auto uo = static_cast<std::size_t>(opposite(i));
                    const std::ptrdiff_t dst =
                        general ? neighbour(x, y, z, i, 1) : static_cast<std::ptrdiff_t>(k) + offset_[ui];
                    if (general && solid(dst)) {  // bounce-back: back into this cell as ī next step
                        const std::uint16_t e = element_of(dst);
                        const double back = returned(f[i], i, element_velocity_[e]);
                        const double m = f[i] + back;  // momentum given to the obstacle along c_i
                        plane[e] += Vec3{cx[i] * m, cy[i] * m, cz[i] * m};
                        if constexpr (Odd) f_[uo * n_ + k] = static_cast<Real>(back - weight[i]);
                        else f_[uo * n_ + k] = static_cast<Real>(f[i] - weight[i]);  // gather adds the wall term
                        continue;
                    }
                    if constexpr (Odd) f_[ui * n_ + static_cast<std::size_t>(dst)] = static_cast<Real>(f[i] - weight[i]);
                    else f_[uo * n_ + k] = static_cast<Real>(f[i] - weight[i]);
                }
            }
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
    if (steps_ % 2 == 0) stream_collide<false>();
    else stream_collide<true>();
    ++steps_;
}

template <class Real>
void FluidLattice<Real>::moments(std::size_t k, double& rho, Vec3& u) const {
    const int x = static_cast<int>(k % static_cast<std::size_t>(shape_.nx));
    const int y = static_cast<int>(k / static_cast<std::size_t>(shape_.nx) % static_cast<std::size_t>(shape_.ny));
    const int z = static_cast<int>(k / (static_cast<std::size_t>(shape_.nx) * static_cast<std::size_t>(shape_.ny)));
    double f[Q];
    if (steps_ % 2 == 0) gather<false>(x, y, z, k, f);
    else gather<true>(x, y, z, k, f);
    rho = 0.0;
    Vec3 j{};
    for (int i = 0; i < Q; ++i) {
        rho += f[i];
        j += Vec3{cx[i] * f[i], cy[i] * f[i], cz[i] * f[i]};
    }
    u = (j + 0.5 * rho * accel_) / rho;
}

template <class Real>
double FluidLattice<Real>::total_mass() const {
    double m = 0.0;
    for (std::size_t k = 0; k < n_; ++k) {
        if (type_[k] != CellType::fluid) continue;
        double rho = 0.0;
        Vec3 u;
        moments(k, rho, u);
        m += rho;
    }
    return m;
}

template class FluidLattice<float>;
template class FluidLattice<double>;

}  // namespace sabo::lbm
