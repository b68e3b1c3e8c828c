// SPDX-License-Identifier: MIT
#include "lbm/fluid_lattice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sabo::lbm {

namespace {

// Lanes of one batch: up to `lanes` cells collide together, each population i of the batch a
// contiguous row f[i][0..n) (the compiler vectorises every loop over the lanes).
constexpr int lanes = 16;
struct Batch {
    double f[Q][lanes];
    double tau[lanes];  // in: τ of the previous step; out: the new τ
    int clamped[lanes];
    // cells of a batch gathered one by one (next to walls): where each lane came from
    int x[lanes], y[lanes];
    std::size_t k[lanes];
    int count = 0;
    Batch() {  // every lane starts as a fluid cell at rest
        for (int i = 0; i < Q; ++i)
            for (int l = 0; l < lanes; ++l) f[i][l] = weight[i];
        for (int l = 0; l < lanes; ++l) tau[l] = 1.0;
    }
};

// BGK collision with Guo forcing of the batch (in place), force density F = ρ a. Bingham:
// τ from the strain rate of the non-equilibrium moments, with the previous τ in S_ab (SPEC §2.1).
[[gnu::always_inline]] inline void collide(Batch& b, int used, const Vec3& accel, const Rheology& rh) {
    // whole groups of 4 lanes (unused ones hold finite stale cells): the vector loops need no remainder
    const int n = std::min(lanes, (used + 3) / 4 * 4);
    // every loop runs over the lanes innermost (contiguous, vectorised); sums over i in ascending order
    double rho[lanes], ux[lanes], uy[lanes], uz[lanes], omega[lanes];
#pragma omp simd
    for (int l = 0; l < n; ++l) rho[l] = ux[l] = uy[l] = uz[l] = 0.0;
    for (int i = 0; i < Q; ++i) {
        const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]), static_cast<double>(cz[i])};
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double fi = b.f[i][l];
            rho[l] += fi;
            ux[l] += ci[0] * fi;
            uy[l] += ci[1] * fi;
            uz[l] += ci[2] * fi;
        }
    }
    const double tau_newtonian = rh.tau;
#pragma omp simd
    for (int l = 0; l < n; ++l) {
        const double r = rho[l], inv = 1.0 / r;
        ux[l] = (ux[l] + 0.5 * r * accel.x) * inv;  // u = (Σ f c + F/2)/ρ
        uy[l] = (uy[l] + 0.5 * r * accel.y) * inv;
        uz[l] = (uz[l] + 0.5 * r * accel.z) * inv;
        omega[l] = 1.0 / tau_newtonian;
    }
    if (rh.bingham) {
        // S_ab = −3/(2ρτ) [Σ c_a c_b (f − f^eq) + ½ (F_a u_b + u_a F_b)] (Krüger et al. 2009, Eq. 45)
        double pxx[lanes], pyy[lanes], pzz[lanes], pxy[lanes], pxz[lanes], pyz[lanes];
#pragma omp simd
        for (int l = 0; l < n; ++l) pxx[l] = pyy[l] = pzz[l] = pxy[l] = pxz[l] = pyz[l] = 0.0;
        for (int i = 0; i < Q; ++i) {
            const double w = weight[i];
            const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]), static_cast<double>(cz[i])};
#pragma omp simd
            for (int l = 0; l < n; ++l) {
                const double vx = ux[l], vy = uy[l], vz = uz[l];
                const double uu = vx * vx + vy * vy + vz * vz;
                const double cu = ci[0] * vx + ci[1] * vy + ci[2] * vz;
                const double d = b.f[i][l] - w * rho[l] * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * uu);
                pxx[l] += ci[0] * ci[0] * d;
                pyy[l] += ci[1] * ci[1] * d;
                pzz[l] += ci[2] * ci[2] * d;
                pxy[l] += ci[0] * ci[1] * d;
                pxz[l] += ci[0] * ci[2] * d;
                pyz[l] += ci[1] * ci[2] * d;
            }
        }
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double r = rho[l], vx = ux[l], vy = uy[l], vz = uz[l];
            const double Fx = r * accel.x, Fy = r * accel.y, Fz = r * accel.z;
            const double sxx = pxx[l] + Fx * vx, syy = pyy[l] + Fy * vy, szz = pzz[l] + Fz * vz;
            const double sxy = pxy[l] + 0.5 * (Fx * vy + vx * Fy);
            const double sxz = pxz[l] + 0.5 * (Fx * vz + vx * Fz);
            const double syz = pyz[l] + 0.5 * (Fy * vz + vy * Fz);
            const double ss = sxx * sxx + syy * syy + szz * szz + 2.0 * (sxy * sxy + sxz * sxz + syz * syz);
            const double rate = 1.5 / (r * b.tau[l]) * std::sqrt(2.0 * ss);
            b.tau[l] = rh.bingham_tau(rate, b.clamped[l]);
            omega[l] = 1.0 / b.tau[l];
        }
    }
    for (int i = 0; i < Q; ++i) {
        const double w = weight[i];
        const double ci[3] = {static_cast<double>(cx[i]), static_cast<double>(cy[i]), static_cast<double>(cz[i])};
#pragma omp simd
        for (int l = 0; l < n; ++l) {
            const double r = rho[l], vx = ux[l], vy = uy[l], vz = uz[l];
            const double uu = vx * vx + vy * vy + vz * vz;
            const double cu = ci[0] * vx + ci[1] * vy + ci[2] * vz;
            const double feq = w * r * (1.0 + 3.0 * cu + 4.5 * cu * cu - 1.5 * uu);
            const double Fx = r * accel.x, Fy = r * accel.y, Fz = r * accel.z;
            const double cF = (3.0 * (ci[0] - vx) + 9.0 * cu * ci[0]) * Fx + (3.0 * (ci[1] - vy) + 9.0 * cu * ci[1]) * Fy +
                              (3.0 * (ci[2] - vz) + 9.0 * cu * ci[2]) * Fz;
            const double fi = b.f[i][l];
            b.f[i][l] = fi - omega[l] * (fi - feq) + w * (1.0 - 0.5 * omega[l]) * cF;
        }
    }
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
void FluidLattice<Real>::gather(int x, int y, int z, std::size_t k, double* f, std::size_t stride) const {
    if constexpr (!Odd) {
        for (int i = 0; i < Q; ++i)
            f[static_cast<std::size_t>(i) * stride] = static_cast<double>(f_[static_cast<std::size_t>(i) * n_ + k]) + weight[i];
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
                fi = static_cast<double>(f_[static_cast<std::size_t>(opposite(i)) * n_ + static_cast<std::size_t>(src)]) +
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
                for (int i = 0; i < Q; ++i) {
                    const auto ui = static_cast<std::size_t>(i);
                    const auto uo = static_cast<std::size_t>(opposite(i));
                    const double post = wall.f[i][l];
                    const std::ptrdiff_t dst = neighbour(wall.x[l], wall.y[l], z, i, 1);
                    if (solid(dst)) {  // bounce-back: back into this cell as ī next step
                        const std::uint16_t e = element_of(dst);
                        const double back = returned(post, i, element_velocity_[e]);
                        const double m = post + back;  // momentum given to the obstacle along c_i
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
                if (type_[k] != CellType::fluid) {
                    ++x;
                    continue;
                }
                if (near_wall_[k] != 0) {
                    const int l = wall.count++;
                    wall.x[l] = static_cast<int>(x);
                    wall.y[l] = y;
                    wall.k[l] = k;
                    wall.tau[l] = static_cast<double>(tau_[k]);
                    gather<Odd>(static_cast<int>(x), y, z, k, &wall.f[0][l], lanes);
                    if (wall.count == lanes) flush_wall();
                    ++x;
                    continue;
                }
                // a run of interior fluid cells: every neighbour is a fluid cell of the lattice, so
                // each population's sources and destinations are contiguous
                std::size_t end = x + 1;
                while (end < nx && end - x < static_cast<std::size_t>(lanes) && type_[row + end] == CellType::fluid &&
                       near_wall_[row + end] == 0)
                    ++end;
                const int n = static_cast<int>(end - x);
                for (int i = 0; i < Q; ++i) {
                    const auto ui = static_cast<std::size_t>(i);
                    const Real* src = Odd ? f_.data() + static_cast<std::size_t>(opposite(i)) * n_ + k - offset_[ui]
                                          : f_.data() + ui * n_ + k;
                    const double w = weight[i];
#pragma omp simd
                    for (int l = 0; l < n; ++l) run.f[i][l] = static_cast<double>(src[l]) + w;
                }
                for (int l = 0; l < n; ++l) run.tau[l] = static_cast<double>(tau_[k + static_cast<std::size_t>(l)]);
                if (n == lanes) collide(run, lanes, accel_, rheology_);  // constant trip counts
                else collide(run, n, accel_, rheology_);
                if (rheology_.bingham)
                    for (int l = 0; l < n; ++l) tau_[k + static_cast<std::size_t>(l)] = static_cast<Real>(run.tau[l]);
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
    if (steps_ % 2 == 0) gather<false>(x, y, z, k, f, 1);
    else gather<true>(x, y, z, k, f, 1);
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
