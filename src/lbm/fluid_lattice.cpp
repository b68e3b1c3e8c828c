// SPDX-License-Identifier: MIT
#include "lbm/fluid_lattice.h"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "core/error.h"
#include "core/prefetch.h"
#include "core/stopwatch.h"
#include "lbm/collision.h"

namespace sabo::lbm {

using detail::Batch;
using detail::collide_batch;
using detail::collide_cell;
using detail::for_each_pair;
using detail::lanes;
using detail::Relaxation;
using detail::returned;
using detail::Solid;
using detail::SolidDrag;
using detail::SolidLanes;

namespace {

// The interior loop's clamp flag: GCC sizes a vectorised loop by its narrowest type, so the flag's width sets
// how many cells an iteration takes — one vector of each value with the flag as wide as Real, two with it
// half as wide.
template <class Real, int VectorsPerValue>
using ClampFlag = std::conditional_t<sizeof(Real) == 8,
                                     std::conditional_t<VectorsPerValue == 2, std::int32_t, std::int64_t>,
                                     std::conditional_t<VectorsPerValue == 2, std::int16_t, std::int32_t>>;

// Cells one apart: a run along x (the other step, std::ptrdiff_t, is a row: a column of row ends)
using Along = std::integral_constant<std::ptrdiff_t, 1>;

// The fused stream-collide of n interior cells (FluidLattice::collide_interior), vectorised: cell l's
// population i read from src[in[i] + l·step] and written to dst[out[i] + l·step] (in[0] = out[0] = 0), its
// τ read from tau_in[l·step] and written to tau_out[l·step]. GCC sizes the loop's vectors by its narrowest
// type, so the type of the clamp flag, Flag, sets how many cells an iteration takes; with KeepFlags each
// cell's flag is also left in flags[l]. S other than none: the cells are wet grain cells (or weight 0),
// grains their weights, v_p and F_h.
template <bool Bingham, bool Les, class Flag, bool KeepFlags, Solid S = Solid::none, class Real,
          class Step = Along>
[[gnu::always_inline]] inline ClampCounts collide_cells(const Real* src, Real* dst, const std::ptrdiff_t* in,
                                                        const std::ptrdiff_t* out, const Real* tau_in,
                                                        Real* tau_out, std::size_t n,
                                                        const Relaxation<Real>& r, Flag* flags,
                                                        Step step = {},
                                                        const SolidLanes<Real>* grains = nullptr) {
    using Count = std::conditional_t<sizeof(Flag) == 8, std::uint64_t, std::uint32_t>;  // a run: < 2^32 cells
    Count at_min = 0, at_max = 0;
#pragma omp simd reduction(+ : at_min, at_max)
    for (std::size_t l = 0; l < n; ++l) {
        const std::ptrdiff_t c = static_cast<std::ptrdiff_t>(l) * step;
        Real p[Q];
        p[0] = src[c];
        for_each_pair([&](auto q) SABO_ALWAYS_INLINE {
            constexpr int i = 2 * q + 1;
            p[i] = src[in[i] + c];
            p[i + 1] = src[in[i + 1] + c];
        });
        Real t = tau_in[c];
        Flag clamped = 0;
        if constexpr (S != Solid::none) {
            SolidDrag<Real> drag{grains->v[0][l], grains->v[1][l], grains->v[2][l], grains->w[l]};
            collide_cell<Bingham, Les, S>(p, t, clamped, r, &drag);
            grains->h[0][l] = drag.hx;
            grains->h[1][l] = drag.hy;
            grains->h[2][l] = drag.hz;
        } else {
            collide_cell<Bingham, Les>(p, t, clamped, r);
        }
        dst[c] = p[0];
        for_each_pair([&](auto q) SABO_ALWAYS_INLINE {
            constexpr int i = 2 * q + 1;
            dst[out[i] + c] = p[i];
            dst[out[i + 1] + c] = p[i + 1];
        });
        if constexpr (Bingham || Les) tau_out[c] = t;
        if constexpr (KeepFlags) flags[l] = clamped;
        at_min += clamped < 0 ? Count(1) : Count(0);
        at_max += clamped > 0 ? Count(1) : Count(0);
    }
    return {at_min, at_max};
}

// The same for m < simd_lanes<Real> cells from f on, as one vector: the lanes read a vector's worth of
// cells (those beyond m are the next cells of the slots, read and dropped: each slot has room for them,
// FluidLattice's constructor), collide into a buffer, and the m cells' results are copied back. GCC's own
// remainder loop takes a cell at a time, several times the time of a vectorised cell.
template <bool Bingham, bool Les, Solid S, class Real>
ClampCounts collide_lanes(Real* f, Real* tau, const std::ptrdiff_t* in, const std::ptrdiff_t* out,
                          std::size_t m, const Relaxation<Real>& r, const SolidLanes<Real>* grains) {
    constexpr std::size_t lanes = detail::simd_lanes<Real>;
    using Flag = ClampFlag<Real, 1>;
    alignas(64) Real post[Q][lanes];
    alignas(64) Real t_in[lanes];
    alignas(64) Real t_out[lanes];
    alignas(64) Flag clamped[lanes];
    alignas(64) Real h[3][lanes];
    std::ptrdiff_t at[Q];
    for (int i = 0; i < Q; ++i) at[i] = i * static_cast<std::ptrdiff_t>(lanes);
    for (std::size_t l = 0; l < lanes; ++l) t_in[l] = tau[std::min(l, m - 1)];  // τ_ has no room beyond
    SolidLanes<Real> to_buffer;
    if constexpr (S != Solid::none)
        to_buffer = {grains->w, {grains->v[0], grains->v[1], grains->v[2]}, {h[0], h[1], h[2]}};
    collide_cells<Bingham, Les, Flag, true, S>(f, &post[0][0], in, at, t_in, t_out, lanes, r, clamped,
                                               Along{}, &to_buffer);
    for (int i = 0; i < Q; ++i)
        for (std::size_t l = 0; l < m; ++l)
            f[out[i] + static_cast<std::ptrdiff_t>(l)] = post[static_cast<std::size_t>(i)][l];
    if constexpr (S != Solid::none)
        for (int a = 0; a < 3; ++a)
            for (std::size_t l = 0; l < m; ++l) grains->h[a][l] = h[a][l];
    ClampCounts counts;
    for (std::size_t l = 0; l < m; ++l) {
        if constexpr (Bingham || Les) tau[l] = t_out[l];
        counts.at_min += clamped[l] < 0 ? 1 : 0;
        counts.at_max += clamped[l] > 0 ? 1 : 0;
    }
    return counts;
}

}  // namespace

template <class Real>
FluidLattice<Real>::FluidLattice(const GridShape& shape, const Rheology& rheology, FluidLattice* storage)
    : shape_(shape),
      rheology_(rheology),
      row_(row_stride(shape.nx)),
      plane_(row_ * static_cast<std::size_t>(std::max(shape.ny, 0))),
      n_(stored_cells(shape)) {
    if (shape.nx < 1 || shape.ny < 1 || shape.nz < 1)
        throw InputError(fmt::format("lattice of {} x {} x {} cells", shape.nx, shape.ny, shape.nz));
    if (!(rheology.tau_min > 0.5) || rheology.tau_max < rheology.tau_min)
        throw InputError(fmt::format("lattice: need 0.5 < tau_min <= tau_max (got {}, {})", rheology.tau_min,
                                     rheology.tau_max));
    if (!rheology.bingham && !(rheology.tau > 0.5))
        throw InputError(fmt::format("lattice: tau = {} must exceed 0.5", rheology.tau));
    // populations of one direction are slot_ cells apart: n_ rounded up so that the 19 streams do not
    // start at the same offset modulo 4 KiB (lattices of 2^k-ish sizes would; loads and stores of
    // different streams then alias in the cache sets and the store buffer): 3 cache lines apart instead
    const std::size_t page = 4096 / sizeof(Real), stagger = 192 / sizeof(Real);
    slot_ = (n_ + page - 1) / page * page + stagger;
    if (storage != nullptr) {
        // a quarter more than this slab needs where the storage is too small: a slab that grows a little
        // at the next moves then fits
        const auto take = [](auto& mine, auto& theirs, std::size_t n) {
            mine = std::move(theirs);
            if (n > mine.capacity()) mine.reserve(n + n / 4);
        };
        take(f_, storage->f_, Q * slot_);
        take(tau_, storage->tau_, n_);
        take(type_, storage->type_, n_);
        take(near_wall_, storage->near_wall_, n_);
        take(solid_links_, storage->solid_links_, n_);
        take(element_, storage->element_, n_);
        take(fill_, storage->fill_, n_);
        take(mass_, storage->mass_, n_);
    }
    f_.assign(Q * slot_, Real(0));
    tau_.assign(n_, static_cast<Real>(rheology.bingham ? rheology.tau_max : rheology.tau));
    type_.assign(n_, CellType::gas);
    near_wall_.assign(n_, 0);
    solid_links_.assign(n_, 0);
    element_.assign(n_, 0);
    fill_.assign(n_, Real(0));
    mass_.assign(n_, 0.0);
    element_velocity_.assign(1, Vec3{});
    element_force_.assign(1, Vec3{});
    slab_.own_end = shape.nx;
}

template <class Real>
void FluidLattice<Real>::set_slab(SlabRole role) {
    // OrphanMass::order packs the pass and the global z, y, x into 20 bits each
    constexpr int limit = 1 << 20;
    if (role.own_begin < 0 || role.own_end > shape_.nx || role.own_begin >= role.own_end ||
        role.first_global_x < 0 || role.first_global_x + shape_.nx > limit || shape_.ny > limit ||
        shape_.nz > limit)
        throw InputError(
            fmt::format("lattice slab: own planes [{}, {}) of {} from global plane {} (at most {} "
                        "cells along an axis)",
                        role.own_begin, role.own_end, shape_.nx, role.first_global_x, limit));
    slab_ = std::move(role);
}

template <class Real>
void FluidLattice<Real>::set_solid_cells(std::span<const SolidCell> cells, SolidExchange exchange) {
    exchange_ = exchange;
    const auto n_old = static_cast<std::ptrdiff_t>(solid_cells_.size());
    const auto n = static_cast<std::ptrdiff_t>(cells.size());
    bool ordered = true;
#pragma omp parallel if (n + n_old > 16384)
    {
#pragma omp for schedule(static) reduction(&& : ordered)
        for (std::ptrdiff_t g = 0; g < n; ++g)
            ordered = ordered && cells[g].cell < n_ && (g == 0 || cells[g - 1].cell < cells[g].cell);
#pragma omp for schedule(static)
        for (std::ptrdiff_t g = 0; g < n_old; ++g)
            near_wall_[solid_cells_[g].cell] &= static_cast<std::uint8_t>(~solid_bit);
    }
    if (!ordered)
        throw std::invalid_argument("set_solid_cells: cells must be lattice cells, ascending, each once");
    solid_cells_.assign(cells.begin(), cells.end());
    solid_force_.assign(solid_cells_.size(), Vec3{});
#pragma omp parallel for schedule(static) if (n > 16384)
    for (std::ptrdiff_t g = 0; g < n; ++g) near_wall_[solid_cells_[g].cell] |= solid_bit;
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
void FluidLattice<Real>::set_outlet(int x, int y, int z, std::size_t outlet) {
    if (outlet >= max_outlets)
        throw InputError(fmt::format("no outlet {} (at most {})", outlet, max_outlets));
    const std::size_t k = index(x, y, z);
    if (type_[k] == CellType::obstacle) throw InputError("an outlet cell must not be an obstacle");
    if (outlet_.empty()) outlet_.assign(n_, 0);
    outlet_[k] = static_cast<std::uint8_t>(outlet + 1);
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
        f_[static_cast<std::size_t>(i) * slot_ + k] =
            static_cast<Real>(detail::equilibrium(i, rho, u) - weight[i]);
}

template <class Real>
double FluidLattice<Real>::density_at(int x, int y, int z) const {
    double f[Q];
    const std::size_t k = index(x, y, z);
    if (steps_ % 2 == 1)
        gather<true>(x, y, z, k, f, 1);
    else
        gather<false>(x, y, z, k, f, 1);
    double rho = 0.0;
    for (const double fi : f) rho += fi;
    return rho;
}

template <class Real>
void FluidLattice<Real>::set_equilibrium(int x, int y, int z, double rho, const Vec3& u) {
    const std::size_t k = index(x, y, z);
    mass_[k] = rho;
    fill_[k] = Real(1);
    for (int i = 0; i < Q; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const double fi = detail::equilibrium(i, rho, u) - weight[i];
        if (steps_ % 2 == 0) {  // its own slot i
            f_[ui * slot_ + k] = static_cast<Real>(fi);
            continue;
        }
        // f_i arrives from x − c_i (slot ī there), or from an obstacle: this cell's own slot i (gather<true>)
        const std::ptrdiff_t src = neighbour(x, y, z, i, -1);
        if (solid(src))
            f_[ui * slot_ + k] = static_cast<Real>(fi);
        else
            f_[static_cast<std::size_t>(opposite(i)) * slot_ + static_cast<std::size_t>(src)] =
                static_cast<Real>(fi);
    }
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
std::ptrdiff_t FluidLattice<Real>::beyond_edge(int x, int y, int z) const {
    int p[3] = {x, y, z};
    const int n[3] = {shape_.nx, shape_.ny, shape_.nz};
    for (int a = 0; a < 3; ++a) {
        if (p[a] >= 0 && p[a] < n[a]) continue;
        if (!shape_.periodic[static_cast<std::size_t>(a)]) return -1;
        p[a] = (p[a] + n[a]) % n[a];
    }
    return static_cast<std::ptrdiff_t>(index(p[0], p[1], p[2]));
}

template <class Real>
void FluidLattice<Real>::relink() {
    for (int z = 0; z < shape_.nz; ++z) {
        for (int y = 0; y < shape_.ny; ++y) {
            for (int x = 0; x < shape_.nx; ++x) {
                const std::size_t k = index(x, y, z);
                // cells with a solid neighbour (an obstacle, or a wall beyond a non-periodic edge) take the
                // general path
                std::uint32_t links = 0;
                for (int i = 1; i < Q; ++i)
                    if (solid(neighbour(x, y, z, i, 1))) links |= 1U << i;
                solid_links_[k] = links;
                near_wall_[k] = static_cast<std::uint8_t>((near_wall_[k] & solid_bit) | (links != 0 ? 1 : 0));
            }
        }
    }
    if (keep_barrier_links_) list_barrier_links();
    tiles_.reserve(most_tiles());
    tile_force_.assign(most_tiles() * element_velocity_.size(), Vec3{});
}

template <class Real>
void FluidLattice<Real>::list_barrier_links() {
    BarrierLinks& b = barrier_links_;
    b.cell.clear();
    b.direction.clear();
    b.element.clear();
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y)
            for (int x = slab_.own_begin; x < slab_.own_end; ++x) {
                const std::size_t k = index(x, y, z);
                if (type_[k] == CellType::obstacle) continue;
                for (std::uint32_t bits = solid_links_[k]; bits != 0; bits &= bits - 1) {
                    const int i = std::countr_zero(bits);
                    const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
                    if (n < 0 || type_[static_cast<std::size_t>(n)] != CellType::obstacle ||
                        element_[static_cast<std::size_t>(n)] == 0)
                        continue;
                    b.cell.push_back(static_cast<std::uint32_t>(k));
                    b.direction.push_back(static_cast<std::uint8_t>(i));
                    b.element.push_back(element_[static_cast<std::size_t>(n)]);
                }
            }
    b.momentum.assign(b.cell.size(), 0.0);
    ++b.version;
}

// A plane holding many interface cells (a flat free surface lies in one or two planes) would be one work item
// of the sweep far larger than the others: with a dam break's surface in a plane, the threads waited for it
// at 16 threads (1 -> 16 threads 5.9x, libgomp's spin half the samples). Such a plane is swept in blocks of
// rows. Which planes are split depends on the lattice's state only, never on the thread count, so the force
// sums (per item, then over the items in order) are the same for any number of threads; a plane not split
// sums its forces as one item, as it did when every item was a plane.
template <class Real>
void FluidLattice<Real>::sweep_tiles() {
    tiles_.clear();
    for (int z = 0; z < shape_.nz; ++z) {
        const auto first = static_cast<std::uint32_t>(index(0, 0, z));
        const auto lo = std::lower_bound(interface_.begin(), interface_.end(), first);
        const auto hi = std::lower_bound(lo, interface_.end(), static_cast<std::uint32_t>(first + plane_));
        if (hi - lo < static_cast<std::ptrdiff_t>(split_plane_interface_cells)) {
            tiles_.push_back({z, 0, shape_.ny});
            continue;
        }
        for (int y = 0; y < shape_.ny; y += sweep_tile_rows)
            tiles_.push_back({z, y, std::min(y + sweep_tile_rows, shape_.ny)});
    }
}

template <class Real>
void FluidLattice<Real>::prepare() {
    relink();
    for (std::size_t k = 0; k < outlet_.size(); ++k)
        if (outlet_[k] != 0 && type_[k] != CellType::gas)
            throw InputError("an outlet cell must be gas at the start (the fluid would never leave it)");
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
    out_known_.assign(ni, 0);               // read from the lattice by prepare_surface()
    for (std::size_t s = 0; s < ni; ++s) {  // the state set_interface() gave them
        const std::size_t k = interface_[s];
        const auto [x, y, z] = coords(k);
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
                static_cast<double>(f_[static_cast<std::size_t>(i) * slot_ + k]) + weight[i];
    } else {
        // f_i(x) arrives from x − c_i, where the even step stored it in slot ī; from an obstacle it is
        // this cell's own f_ī*, bounced back (stored in its own slot i), plus the moving-wall term
        for (int i = 0; i < Q; ++i) {
            const auto ui = static_cast<std::size_t>(i);
            const std::ptrdiff_t src = neighbour(x, y, z, i, -1);
            double& fi = f[ui * stride];
            if (solid(src)) {
                fi = returned(static_cast<double>(f_[ui * slot_ + k]) + weight[i], opposite(i),
                              element_velocity_[element_of(src)]);
            } else {
                fi = static_cast<double>(
                         f_[static_cast<std::size_t>(opposite(i)) * slot_ + static_cast<std::size_t>(src)]) +
                     weight[i];
            }
        }
    }
}

template <class Real>
void FluidLattice<Real>::links(std::size_t k, const std::ptrdiff_t* shift, std::uint32_t solid_bits,
                               std::ptrdiff_t* nb) const {
    for (int i = 0; i < Q; ++i) {
        const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k) + shift[i];
        if ((solid_bits >> i & 1U) == 0) {
            nb[i] = n;
        } else {  // beyond a wall of the domain the shift means nothing (element 0)
            const auto un = static_cast<std::size_t>(n);
            nb[i] = -1 - static_cast<std::ptrdiff_t>(type_[un] == CellType::obstacle ? element_[un] : 0);
        }
    }
}

template <class Real>
void FluidLattice<Real>::return_from_walls(std::size_t row, std::size_t from, std::size_t to,
                                           const std::ptrdiff_t (&shift)[3][Q]) {
    const auto nx = static_cast<std::size_t>(shape_.nx);
    for (std::size_t x = from; x < to; ++x) {
        const std::size_t k = row + x;
        if (near_wall_[k] == 0) continue;
        const std::ptrdiff_t* sh = shift[x == 0 ? 0 : (x + 1 == nx ? 2 : 1)];
        for (std::uint32_t bits = solid_links_[k]; bits != 0; bits &= bits - 1) {
            // f_ō arrives from the solid along c_j = −c_ō: the f_j* in slot ō plus the wall's term (gather)
            const int j = std::countr_zero(bits), o = opposite(j);
            const auto n = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + sh[j]);
            const std::size_t e = type_[n] == CellType::obstacle ? element_[n] : 0;
            Real& slot = f_[static_cast<std::size_t>(o) * slot_ + k];
            slot = static_cast<Real>(
                returned(static_cast<double>(slot) + weight[o], j, element_velocity_[e]) - weight[o]);
        }
    }
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::wall_links(std::size_t row, std::size_t from, std::size_t to,
                                    const std::ptrdiff_t (&shift)[3][Q], bool moving_walls, Vec3* plane) {
    const auto nx = static_cast<std::size_t>(shape_.nx);
    for (std::size_t x = from; x < to; ++x) {
        x = plain_run_end<false, true>(row, x, to);  // past whole groups of eight cells with no wall nearby
        if (x == to) break;
        const std::size_t k = row + x;
        if (near_wall_[k] == 0) continue;
        const std::ptrdiff_t* sh = shift[x == 0 ? 0 : (x + 1 == nx ? 2 : 1)];
        const double counted = own_x(x) ? 1.0 : 0.0;  // a ghost plane's force is its owner's
        for (std::uint32_t bits = solid_links_[k]; bits != 0; bits &= bits - 1) {
            const int i = std::countr_zero(bits);
            // the obstacle's element as links() finds it; f_i*, which the collision left in slot ī, and what
            // the bounce-back returns (the even step stores f_i* and the odd one returns it with the wall's
            // term; an odd step stores the returned population, as the sweep's gathered path does)
            const auto n = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + sh[i]);
            const std::size_t e = type_[n] == CellType::obstacle ? element_[n] : 0;
            Real& slot = f_[static_cast<std::size_t>(opposite(i)) * slot_ + k];
            const double post = static_cast<double>(slot) + weight[i];
            const double back = returned(post, i, element_velocity_[e]);
            if (Odd && moving_walls) slot = static_cast<Real>(back - weight[i]);
            const double m = counted * (post + back - 2.0 * weight[i]);
            plane[e] += Vec3{cx[i] * m, cy[i] * m, cz[i] * m};
            if (keep_barrier_links_ && e != 0) keep_link(k, i, m);
        }
    }
}

template <class Real>
std::size_t FluidLattice<Real>::next_wet(std::size_t row, std::size_t x, std::size_t nx) const {
    static_assert(static_cast<int>(CellType::fluid) == 0 && static_cast<int>(CellType::interface) == 1);
    const auto* type = reinterpret_cast<const std::uint8_t*>(type_.data() + row);
    // eight cells at a time: a byte of 0 or 1 (fluid, interface) is a zero byte of t = bytes & 0xFE..
    constexpr std::uint64_t ones = 0x0101010101010101ULL, highs = 0x8080808080808080ULL;
    while (x + 8 <= nx) {
        std::uint64_t bytes = 0;
        std::memcpy(&bytes, type + x, 8);
        const std::uint64_t t = bytes & ~ones;
        const std::uint64_t zero = (t - ones) & ~t & highs;  // the lowest set bit marks the first zero byte
        if (zero != 0) return x + static_cast<std::size_t>(std::countr_zero(zero)) / 8;
        x += 8;
    }
    while (x < nx && type[x] > 1) ++x;
    return x;
}

template <class Real>
template <bool Fluid, bool NoWalls>
std::size_t FluidLattice<Real>::plain_run_end(std::size_t row, std::size_t x, std::size_t nx) const {
    static_assert(static_cast<int>(CellType::fluid) == 0);
    const auto* type = reinterpret_cast<const std::uint8_t*>(type_.data() + row);
    const std::uint8_t* wall = near_wall_.data() + row;
    // which bits of the flag bytes end a run: the walls' (a grain cell runs with the others), or none
    constexpr std::uint64_t grain_bits = 0x0101010101010101ULL * solid_bit;
    const std::uint64_t flags = NoWalls ? ~grain_bits : 0;
    while (x + 8 <= nx) {
        std::uint64_t t = 0, w = 0;
        if constexpr (Fluid) std::memcpy(&t, type + x, 8);
        if (flags != 0) std::memcpy(&w, wall + x, 8);
        if ((t | (w & flags)) != 0) break;
        x += 8;
    }
    return x;
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::gather_links(std::size_t k, const std::ptrdiff_t* nb, double* f,
                                      std::size_t stride) const {
    for (int i = 0; i < Q; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        double& fi = f[ui * stride];
        if constexpr (!Odd) {
            fi = static_cast<double>(f_[ui * slot_ + k]) + weight[i];
        } else {  // as gather<true>
            const std::ptrdiff_t src = nb[opposite(i)];
            if (src < 0)
                fi = returned(static_cast<double>(f_[ui * slot_ + k]) + weight[i], opposite(i),
                              element_velocity_[static_cast<std::size_t>(-1 - src)]);
            else
                fi = static_cast<double>(
                         f_[static_cast<std::size_t>(opposite(i)) * slot_ + static_cast<std::size_t>(src)]) +
                     weight[i];
        }
    }
}

template <class Real>
template <bool Odd>
void FluidLattice<Real>::request_row(std::size_t row, std::size_t from, std::size_t to,
                                     const std::ptrdiff_t* shift) const {
    if (row + to > n_) return;
    constexpr std::size_t line = 64 / sizeof(Real), beyond = 64 / sizeof(float);
    const auto size = static_cast<std::ptrdiff_t>(f_.size());
    for (int i = 0; i < Q; ++i) {
        // the slot that the step reads f_i of the row's cells from (and writes f_ī* into): even steps their
        // own slot i, odd steps slot ī of the cells − c_i (the shifts are this row's, so the next row's
        // wrap may be off: a wrong line is only a wasted request, but it must stay inside the array)
        const auto uo = static_cast<std::size_t>(opposite(i));
        const std::ptrdiff_t start =
            Odd ? static_cast<std::ptrdiff_t>(uo * slot_ + row) + shift[uo]
                : static_cast<std::ptrdiff_t>(static_cast<std::size_t>(i) * slot_ + row);
        const auto first = static_cast<std::ptrdiff_t>(from), last = static_cast<std::ptrdiff_t>(to + beyond);
        for (std::ptrdiff_t at = start + first; at < start + last; at += static_cast<std::ptrdiff_t>(line))
            if (at >= 0 && at < size) prefetch_write(f_.data() + at);
    }
}

template <class Real>
template <bool Odd, bool Bingham, bool Les, bool Column, Solid S>
// not inlined: inside the sweep's loop GCC compiles the odd steps' runs ~1.5x slower (fluid-only C5, 2
// threads)
[[gnu::noinline]] ClampCounts FluidLattice<Real>::collide_interior(std::size_t k, std::size_t n,
                                                                   const std::ptrdiff_t* shift,
                                                                   std::uint32_t solid_bits,
                                                                   const Relaxation<Real>& r,
                                                                   const SolidLanes<Real>* grains) {
    // population i of cell c comes from (odd) slot ī of c − c_i and goes to slot i of c + c_i, or (even)
    // stays in the cell's own slots, swapped; each slot is read and written by its own cell only, so the
    // lanes are independent. Across a solid link (bit i of solid_bits: c + c_i is solid, the same for all
    // n cells) the odd step bounces back in the cell's own slots, as the even step always does: f_i
    // arriving from the solid c − c_i is the f_ī* the even step left in slot i (the moving-wall term
    // added before, return_from_walls()), and f_i* toward the solid c + c_i goes into slot ī.
    std::ptrdiff_t in[Q], out[Q];
    for (int i = 0; i < Q; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const auto uo = static_cast<std::size_t>(opposite(i));
        const bool own_in = !Odd || (solid_bits >> uo & 1U) != 0;
        const bool own_out = !Odd || (solid_bits >> ui & 1U) != 0;
        in[i] = own_in ? static_cast<std::ptrdiff_t>(ui * slot_)
                       : static_cast<std::ptrdiff_t>(uo * slot_) + shift[uo];
        out[i] = own_out ? static_cast<std::ptrdiff_t>(uo * slot_)
                         : static_cast<std::ptrdiff_t>(ui * slot_) + shift[ui];
    }
    Real* const f = f_.data() + k;
    Real* const tau = tau_.data() + k;
    if constexpr (Column) {  // n row ends of consecutive rows, a row apart: one vector (gathered) per value
        return collide_cells<Bingham, Les, ClampFlag<Real, 1>, false>(f, f, in, out, tau, tau, n, r, nullptr,
                                                                      static_cast<std::ptrdiff_t>(row_));
    }
    // Even steps one vector of each value per iteration, odd steps two: their loads come from the neighbours'
    // slots, later than the own slots, and two independent chains keep the core busy meanwhile (float32
    // periodic odd steps 15 % faster, float64 odd 25 %; even steps slower so).
    using Flag = ClampFlag<Real, Odd ? 2 : 1>;
    // Whole iterations through the loop (Newtonian: its flag is constant and folded away, one vector per
    // value), the cells after them a vector at a time through collide_lanes where that is cheaper than the
    // loop's own remainder code (a cell at a time): in even steps, and in odd steps of the dearer Bingham and
    // LES collisions; not for a single cell. Measured, float32 periodic 200³, one thread: even steps 30 -> 27
    // ms Newtonian, 53 -> 41 Bingham; Bingham odd steps 80 -> 72; Newtonian odd steps 60 -> 70 (not taken).
    // Runs of grain cells are short (a grain is a few cells across): always.
    constexpr bool lanes_pay = !Odd || Bingham || Les || S != Solid::none;
    constexpr std::size_t per_iteration =
        Bingham || Les ? detail::simd_bytes / sizeof(Flag) : detail::simd_lanes<Real>;
    const std::size_t body = !lanes_pay || n < 2 ? n : n / per_iteration * per_iteration;
    ClampCounts counts;
    if (body > 0)
        counts = collide_cells<Bingham, Les, Flag, false, S>(f, f, in, out, tau, tau, body, r, nullptr,
                                                             Along{}, grains);
    for (std::size_t from = body; from < n; from += detail::simd_lanes<Real>) {
        SolidLanes<Real> rest;
        if constexpr (S != Solid::none) rest = grains->from(from);
        const ClampCounts c = collide_lanes<Bingham, Les, S>(
            f + from, tau + from, in, out, std::min(n - from, detail::simd_lanes<Real>), r, &rest);
        counts.at_min += c.at_min;
        counts.at_max += c.at_max;
    }
    return counts;
}

template <class Real>
template <bool Odd, bool Bingham, bool Les>
void FluidLattice<Real>::stream_collide() {
    const std::size_t n_elem = element_velocity_.size();
    const Relaxation<Real> relax(accel_, rheology_);         // interior cells, in the storage precision
    const Relaxation<double> relax_wall(accel_, rheology_);  // gathered cells, in double
    const bool moving_walls =
        std::any_of(element_velocity_.begin(), element_velocity_.end(),
                    [](const Vec3& u) { return u.x != 0.0 || u.y != 0.0 || u.z != 0.0; });
    std::uint64_t at_min = 0, at_max = 0, updated = 0;
    const auto nx = static_cast<std::size_t>(shape_.nx);
    const bool coupled = !solid_cells_.empty();
    const bool psm = exchange_ == SolidExchange::psm;
    const std::size_t grain_stride = solid_row_stride();
    if (coupled) {  // once: the rows' weights, v_p and F_h for each thread (docs: solid_rows_)
        const std::size_t size = static_cast<std::size_t>(omp_get_max_threads()) * 7 * grain_stride;
        if (solid_rows_.size() < size) solid_rows_.assign(size, Real(0));
    }
    // The neighbour along c_i of every cell of a row but its ends is k + shift[i]; the first and the last
    // cell have their own shifts (the wrap in x). The periodic wraps in y and z are the same for every
    // row with the same place in y and in z (first, inside, last: edge_class): 9 tables, made here.
    // Meaningless toward a wall, where no run goes.
    // Odd steps on a lattice periodic in x: the rows' first and last cells read and write across the wrap,
    // with shifts of their own; otherwise their neighbours toward an edge are walls (solid links, own slots)
    // and the middle cells' shifts hold for them too.
    const bool wrap_x = Odd && shape_.periodic[0];
    const auto edge_class = [](int c, int count) { return c == 0 ? 0 : (c == count - 1 ? 2 : 1); };
    std::ptrdiff_t shifts[3][3][3][Q];  // [z class][y class][first cell, middle, last cell][i]
    for (int cz = 0; cz < 3; ++cz) {
        for (int cy = 0; cy < 3; ++cy) {
            const int z = cz == 0 ? 0 : (cz == 2 ? shape_.nz - 1 : std::min(1, shape_.nz - 1));
            const int y = cy == 0 ? 0 : (cy == 2 ? shape_.ny - 1 : std::min(1, shape_.ny - 1));
            const auto row = static_cast<std::ptrdiff_t>(index(0, y, z));
            const int at[3] = {0, std::min(1, shape_.nx - 1), shape_.nx - 1};
            for (int part = 0; part < 3; ++part) {
                for (int i = 0; i < Q; ++i) {
                    const std::ptrdiff_t n = neighbour(at[part], y, z, i, 1);
                    shifts[cz][cy][part][i] = n < 0 ? 0 : n - row - at[part];
                }
            }
        }
    }
    sweep_tiles();
    const auto n_tiles = static_cast<int>(tiles_.size());
#pragma omp parallel reduction(+ : at_min, at_max, updated) if (n_ >= 16384)  // small lattices: no team
    {
        Batch wall;  // cells next to a wall or on the domain's edge, gathered one by one
        // this thread's weights, v_p (x, y, z) and F_h (x, y, z) along the row being swept
        Real* lane[7] = {};
        if (coupled)
            for (std::size_t a = 0; a < 7; ++a)
                lane[a] = solid_rows_.data() +
                          (static_cast<std::size_t>(omp_get_thread_num()) * 7 + a) * grain_stride;
        const SolidLanes<Real> grain_row{lane[0], {lane[1], lane[2], lane[3]}, {lane[4], lane[5], lane[6]}};
        // planes (or blocks of a plane's rows) one at a time: the fluid may fill only part of the height (a
        // dam break's lower half); each item's work and force sums are its own, so the result does not
        // depend on who took it
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < n_tiles; ++t) {
            const SweepTile tile = tiles_[static_cast<std::size_t>(t)];
            const int z = tile.z;
            Vec3* plane = tile_force_.data() + static_cast<std::size_t>(t) * n_elem;
            for (std::size_t e = 0; e < n_elem; ++e) plane[e] = {};
            const auto flush_wall = [&] {
                if (!coupled)
                    collide_batch<Bingham, Les, Solid::none>(wall, relax_wall);
                else if (psm)
                    collide_batch<Bingham, Les, Solid::psm>(wall, relax_wall);
                else
                    collide_batch<Bingham, Les, Solid::drag>(wall, relax_wall);
                for (int l = 0; l < wall.count; ++l) {
                    at_min += wall.clamped[l] < 0 ? 1 : 0;
                    at_max += wall.clamped[l] > 0 ? 1 : 0;
                    const std::size_t k = wall.k[l];
                    tau_[k] = static_cast<Real>(wall.tau[l]);
                    // the cell's force density besides gravity's (−F_h of a grain cell)
                    Vec3 drag{};
                    if (coupled && wall.grain[l] >= 0) {
                        const Vec3 h{wall.hydro[0][l], wall.hydro[1][l], wall.hydro[2][l]};
                        solid_force_[static_cast<std::size_t>(wall.grain[l])] = h;
                        drag = -1.0 * h;
                    }
                    if (wall.surface[l] >= 0) {  // the density and velocity of the collision
                        const auto s = static_cast<std::size_t>(wall.surface[l]);
                        const double rho = wall.rho[l];
                        Vec3 j{};
                        for (int i = 0; i < Q; ++i)
                            j += Vec3{cx[i] * wall.f[i][l], cy[i] * wall.f[i][l], cz[i] * wall.f[i][l]};
                        surface_rho_[s] = rho;
                        // post-collision momentum is j + F, F = ρ a − F_h; partially saturated cells weigh
                        // only their fluid share 1 − β
                        const double weighed = psm && wall.grain[l] >= 0 ? 1.0 - wall.grain_weight[l] : 1.0;
                        surface_u_[s] = coupled ? (j - 0.5 * (weighed * rho * accel_ + drag)) / rho
                                                : (j - 0.5 * rho * accel_) / rho;
                        // the outgoing populations as the lattice will hold them (rounded to the storage
                        // type), for the reconstruction of the next step
                        double* out = out_.data() + s * Q;
                        for (int i = 0; i < Q; ++i)
                            out[i] =
                                static_cast<double>(static_cast<Real>(wall.f[i][l] - weight[i])) + weight[i];
                        out_known_[s] = 1;
                        std::copy(wall.nb[l], wall.nb[l] + Q, surface_nb_.data() + s * Q);
                    }
                    for (int i = 0; i < Q; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        const auto uo = static_cast<std::size_t>(opposite(i));
                        const double post = wall.f[i][l];
                        const std::ptrdiff_t dst = wall.nb[l][i];
                        if (dst < 0) {  // bounce-back: back into this cell as ī next step
                            const auto e = static_cast<std::size_t>(-1 - dst);
                            const double back = returned(post, i, element_velocity_[e]);
                            // momentum given to the obstacle along c_i, less that of the fluid at rest at
                            // the atmospheric density (2 w_i): the force relative to the atmosphere, which
                            // pushes on the obstacle's dry side (the gauge force; for a fully wetted body the
                            // constant term sums to zero anyway)
                            const double m = wall.counted[l] * (post + back - 2.0 * weight[i]);
                            plane[e] += Vec3{cx[i] * m, cy[i] * m, cz[i] * m};
                            if (keep_barrier_links_ && e != 0) keep_link(k, i, m);
                            // even: stored as f_i*, the odd gather adds the wall term
                            f_[uo * slot_ + k] = static_cast<Real>((Odd ? back : post) - weight[i]);
                        } else if constexpr (Odd) {
                            f_[ui * slot_ + static_cast<std::size_t>(dst)] =
                                static_cast<Real>(post - weight[i]);
                        } else {
                            f_[uo * slot_ + k] = static_cast<Real>(post - weight[i]);
                        }
                    }
                }
                wall.count = 0;
            };
            const std::size_t first_cell = index(0, tile.y_begin, z);
            // the item's first interface cell in the (ascending) list
            std::size_t next_surface =
                static_cast<std::size_t>(std::lower_bound(interface_.begin(), interface_.end(),
                                                          static_cast<std::uint32_t>(first_cell)) -
                                         interface_.begin());
            // the item's first grain cell in the (ascending) list
            std::size_t next_grain = static_cast<std::size_t>(
                std::lower_bound(solid_cells_.begin(), solid_cells_.end(), first_cell,
                                 [](const SolidCell& c, std::size_t k) { return c.cell < k; }) -
                solid_cells_.begin());
            // the interface cells look up the types of their 18 neighbours; the planes above and below were
            // last touched by the other threads (items go round the team): those two rows ahead are asked
            // for
            const bool plane_has_surface =
                next_surface < interface_.size() &&
                interface_[next_surface] <
                    first_cell + static_cast<std::size_t>(tile.y_end - tile.y_begin) * row_;
            // the odd step's row ends waiting to collide down the column: column_rows rows from column_first
            // on
            std::size_t column_first = 0, column_rows = 0;
            const auto collide_columns = [&] {
                if (!Odd || column_rows == 0) return;
                const auto& shift = shifts[edge_class(z, shape_.nz)][1];
                for (const int end : {0, 2}) {
                    const std::size_t k = column_first + (end == 0 ? 0 : nx - 1);
                    const ClampCounts c =
                        collide_interior<Odd, Bingham, Les, true>(k, column_rows, shift[end], 0, relax);
                    at_min += c.at_min;
                    at_max += c.at_max;
                }
                column_rows = 0;
            };
            // the ends of an odd step's rows wrapped in x come after the row: grain cells there go through
            // the batch
            const auto wrapped_end = [&](std::size_t x) { return wrap_x && (x == 0 || x + 1 == nx); };
            std::size_t row_grain = next_grain;
            for (int y = tile.y_begin; y < tile.y_end; ++y) {
                const std::size_t row = index(0, y, z);
                // the row's grain cells, [first_grain, row_grain) of the list: the wet ones (fluid; the
                // interface cells and the wrapped ends go through the batch with their fill as the weight)
                // into the row's lanes
                while (row_grain < solid_cells_.size() && solid_cells_[row_grain].cell < row) ++row_grain;
                const std::size_t first_grain = row_grain;
                for (; row_grain < solid_cells_.size() && solid_cells_[row_grain].cell < row + nx;
                     ++row_grain) {
                    const SolidCell& gc = solid_cells_[row_grain];
                    const std::size_t x = gc.cell - row;
                    if (type_[gc.cell] != CellType::fluid || wrapped_end(x)) continue;
                    lane[0][x] =
                        static_cast<Real>(saturation_weight(gc.fraction, static_cast<double>(tau_[gc.cell])));
                    for (int a = 0; a < 3; ++a) lane[1 + a][x] = static_cast<Real>(gc.velocity[a]);
                }
                // a row with grain cells takes the coupled kernel throughout (cells outside the grains with
                // weight 0), wet or not: the same arithmetic for the row whatever the fill of its grain cells
                const bool row_coupled = row_grain > first_grain;
                if (plane_has_surface && y + 2 < shape_.ny) {
                    for (int dz = -1; dz <= 1; ++dz) {
                        if (z + dz < 0 || z + dz >= shape_.nz) continue;
                        const CellType* ahead = type_.data() + index(0, y + 2, z + dz);
                        for (std::size_t c = 0; c < nx; c += 64) prefetch_read(ahead + c);
                    }
                }
                const auto& shift = shifts[edge_class(z, shape_.nz)][edge_class(y, shape_.ny)];
                std::size_t x = 0;
                while (x < nx) {
                    const std::size_t k = row + x;
                    const CellType type = type_[k];
                    if (type != CellType::fluid && type != CellType::interface) {
                        x = next_wet(row, x + 1, nx);
                        continue;
                    }
                    const bool near_wall = near_wall_[k] != 0;
                    const bool grain_cell = (near_wall_[k] & solid_bit) != 0;
                    if (type == CellType::interface || (grain_cell && wrapped_end(x))) {
                        const int l = wall.count++;
                        ++updated;
                        wall.k[l] = k;
                        wall.counted[l] = own_x(x) ? 1.0 : 0.0;
                        wall.tau[l] = static_cast<double>(tau_[k]);
                        wall.grain[l] = -1;
                        wall.grain_weight[l] = 0.0;
                        if (grain_cell) {  // cells come in ascending order, as the list
                            while (solid_cells_[next_grain].cell < k) ++next_grain;
                            const SolidCell& gc = solid_cells_[next_grain];
                            wall.grain[l] = static_cast<int>(next_grain);
                            wall.grain_v[0][l] = gc.velocity.x;
                            wall.grain_v[1][l] = gc.velocity.y;
                            wall.grain_v[2][l] = gc.velocity.z;
                            wall.grain_weight[l] =
                                coupling_weight(k) *
                                saturation_weight(gc.fraction, static_cast<double>(tau_[k]));
                        }
                        links(k, shift[x == 0 ? 0 : (x + 1 == nx ? 2 : 1)], near_wall ? solid_links_[k] : 0,
                              wall.nb[l]);
                        gather_links<Odd>(k, wall.nb[l], &wall.f[0][l], lanes);
                        wall.surface[l] = -1;
                        if (type == CellType::interface) {
                            const std::size_t s = next_surface++;  // cells come in ascending order
                            wall.surface[l] = static_cast<int>(s);
                            // which neighbours are gas and which fluid: the reconstruction's and the mass
                            // exchange's (the types do not change before convert_cells())
                            NeighbourKinds& kinds = surface_kinds_[s];
                            kinds = {};
                            for (int i = 1; i < Q; ++i) {
                                const std::ptrdiff_t n = wall.nb[l][i];
                                const CellType t =
                                    n < 0 ? CellType::obstacle : type_[static_cast<std::size_t>(n)];
                                kinds.gas |= static_cast<std::uint32_t>(t == CellType::gas) << i;
                                kinds.fluid |= static_cast<std::uint32_t>(t == CellType::fluid) << i;
                            }
                            reconstruct(s, wall.nb[l], kinds.gas, &wall.f[0][l], lanes);
                            double rho = 0.0;
                            for (int i = 0; i < Q; ++i) rho += wall.f[i][l];
                            wall.rho[l] = rho;
                        }
                        if (wall.count == lanes) flush_wall();
                        ++x;
                        continue;
                    }
                    // A run of fluid cells through the vectorised loop: in odd steps cells with the same
                    // solid links (none, or those of a stretch along a wall), in even steps any (they read
                    // and write their own slots only); the walls' share afterwards (bounce-back, force)
                    const std::uint32_t solid_bits = near_wall ? solid_links_[k] : 0;
                    const auto bits_of = [&](std::size_t c) {
                        return near_wall_[c] != 0 ? solid_links_[c] : 0;
                    };
                    // plain cells (fluid, and in odd steps no solid link) eight at a time, then one by one
                    std::size_t end =
                        Odd && solid_bits != 0 ? x + 1 : plain_run_end<true, Odd>(row, x + 1, nx);
                    while (end < nx && type_[row + end] == CellType::fluid &&
                           (!Odd || bits_of(row + end) == solid_bits))
                        ++end;
                    updated += end - x;
                    // a run that is not a whole row (a dam break's rows end at the surface) asks for the next
                    // row's populations of the same stretch now, a row (a microsecond or so) ahead: the
                    // hardware prefetchers lose the 19 streams when rows are used in part (dam break odd
                    // steps 25-30 % faster, even steps 5 %)
                    if (x > 0 || end < nx) request_row<Odd>(row + row_, x, end, shift[1]);
                    if (Odd && moving_walls && solid_bits != 0) return_from_walls(row, x, end, shift);
                    const auto run = [&](std::size_t from, std::size_t to, const std::ptrdiff_t* sh) {
                        if (to <= from) return;
                        const SolidLanes<Real> grains =
                            row_coupled ? grain_row.from(from) : SolidLanes<Real>{};
                        const ClampCounts c =
                            !row_coupled ? collide_interior<Odd, Bingham, Les>(row + from, to - from, sh,
                                                                               solid_bits, relax)
                            : psm        ? collide_interior<Odd, Bingham, Les, false, Solid::psm>(
                                        row + from, to - from, sh, solid_bits, relax, &grains)
                                  : collide_interior<Odd, Bingham, Les, false, Solid::drag>(
                                        row + from, to - from, sh, solid_bits, relax, &grains);
                        at_min += c.at_min;
                        at_max += c.at_max;
                    };
                    // one run, but in the odd steps of a lattice periodic in x less the row's first and last
                    // cell, which have their own shifts (the wrap) and come after the row
                    const std::size_t from = wrap_x ? std::max<std::size_t>(x, 1) : x;
                    const std::size_t to = wrap_x ? std::min(end, nx - 1) : end;
                    run(from, to, shift[1]);
                    if ((!Odd || solid_bits != 0) && from < to)
                        wall_links<Odd>(row, from, to, shift, moving_walls, plane);
                    x = end;
                }
                // The odd step's row ends after the rest of the row: their wrapped neighbours lie at the
                // other end of the row, and going there and back before the row is done costs the hardware
                // prefetchers the 19 streams (float32 periodic 200³, one thread: odd steps 55 -> 32 ms). Each
                // slot is read and written by one cell only, so the order of the cells does not change the
                // result. Plain fluid ends of rows inside the plane wait for a vector's worth of rows and
                // collide down the column (two ends, two vectors; the rows are still in the cache: periodic
                // 200³ one thread, odd steps float32 33 -> 31.5 ms, float64 61 -> 55); any other end alone.
                if (wrap_x) {
                    const bool plain_ends = y > 0 && y + 1 < shape_.ny && nx > 1 &&
                                            type_[row] == CellType::fluid &&
                                            type_[row + nx - 1] == CellType::fluid && near_wall_[row] == 0 &&
                                            near_wall_[row + nx - 1] == 0;
                    if (plain_ends) {
                        if (column_rows == 0) column_first = row;
                        if (++column_rows == detail::simd_lanes<Real>) collide_columns();
                    } else {
                        collide_columns();
                        for (std::size_t e = 0; e < nx; e += std::max<std::size_t>(nx - 1, 1)) {  // 0, nx − 1
                            const std::size_t k = row + e;
                            // interface and grain cells went through the batch
                            if (type_[k] != CellType::fluid || (near_wall_[k] & solid_bit) != 0) continue;
                            const std::uint32_t solid_bits = near_wall_[k] != 0 ? solid_links_[k] : 0;
                            const ClampCounts c = collide_interior<Odd, Bingham, Les>(
                                k, 1, shift[e == 0 ? 0 : 2], solid_bits, relax);
                            at_min += c.at_min;
                            at_max += c.at_max;
                            if (solid_bits != 0) wall_links<Odd>(row, e, e + 1, shift, moving_walls, plane);
                        }
                    }
                }
                // the forces on the row's grain cells that went through the runs, and the lanes back to zero
                for (std::size_t g = first_grain; g < row_grain; ++g) {
                    const std::size_t x = solid_cells_[g].cell - row;
                    if (lane[0][x] == Real(0)) continue;
                    solid_force_[g] = Vec3{static_cast<double>(lane[4][x]), static_cast<double>(lane[5][x]),
                                           static_cast<double>(lane[6][x])};
                    lane[0][x] = Real(0);
                }
            }
            collide_columns();
            if (wall.count > 0) flush_wall();
        }
    }
    clamps_ = {at_min, at_max};
    updated_cells_ = updated;
    for (std::size_t e = 0; e < n_elem; ++e) {
        Vec3 sum{};
        for (std::size_t t = 0; t < tiles_.size(); ++t) sum += tile_force_[t * n_elem + e];
        element_force_[e] = sum;
    }
}

template <class Real>
void FluidLattice<Real>::step() {
    if (tile_force_.size() != most_tiles() * element_velocity_.size()) prepare();
    const bool odd = steps_ % 2 == 1;
    const bool les = rheology_.smagorinsky > 0.0;
    std::fill(solid_force_.begin(), solid_force_.end(), Vec3{});
    std::fill(barrier_links_.momentum.begin(), barrier_links_.momentum.end(), 0.0);
    if (rheology_.bingham) {
        if (les)
            odd ? stream_collide<true, true, true>() : stream_collide<false, true, true>();
        else
            odd ? stream_collide<true, true, false>() : stream_collide<false, true, false>();
    } else if (les) {
        odd ? stream_collide<true, false, true>() : stream_collide<false, false, true>();
    } else {
        odd ? stream_collide<true, false, false>() : stream_collide<false, false, false>();
    }
    ++steps_;
    if (!crossings_.empty()) count_crossings();
    // a slab with no surface of its own still takes part in the spread of the others' orphan mass
    if (steps_surface()) {
        {
            const ScopeSeconds timed(surface_seconds_.exchange);
            exchange_mass();  // the populations just streamed across the interface links
        }
        {
            const ScopeSeconds timed(surface_seconds_.conversions);
            convert_cells();
        }
        const ScopeSeconds timed(surface_seconds_.prepare);
        prepare_surface();
    }
}

template <class Real>
void FluidLattice<Real>::restored() {
    const std::size_t ni = interface_.size();
    if (f_.size() != Q * slot_ || tau_.size() != n_ || type_.size() != n_ || element_.size() != n_ ||
        fill_.size() != n_ || mass_.size() != n_ || surface_rho_.size() != ni || surface_u_.size() != ni ||
        out_.size() != ni * Q || out_known_.size() != ni || (!outlet_.empty() && outlet_.size() != n_))
        throw InputError("checkpoint: the lattice it holds does not match this case's lattice");
    for (const std::uint8_t o : outlet_)
        if (o > max_outlets)
            throw InputError("checkpoint: a lattice cell of no known outlet (corrupt checkpoint)");
    // every cell of a known type, and the interface list exactly the interface cells, ascending
    std::size_t typed_interface = 0;
    for (const CellType t : type_) {
        if (static_cast<std::uint8_t>(t) > static_cast<std::uint8_t>(CellType::obstacle))
            throw InputError("checkpoint: a lattice cell of no known type (corrupt checkpoint)");
        typed_interface += t == CellType::interface ? 1 : 0;
    }
    for (std::size_t s = 0; s < ni; ++s)
        if (interface_[s] >= n_ || type_[interface_[s]] != CellType::interface ||
            (s > 0 && interface_[s] <= interface_[s - 1]))
            throw InputError(
                "checkpoint: the interface list does not fit the cell types (corrupt checkpoint)");
    if (typed_interface != ni)
        throw InputError("checkpoint: the interface list does not fit the cell types (corrupt checkpoint)");
    if (element_force_.size() > 1 && element_force_.size() != element_velocity_.size())
        throw InputError("checkpoint: the lattice it holds does not match this case's lattice");
    for (const std::uint16_t e : element_)
        if (e >= element_velocity_.size())
            throw InputError(
                "checkpoint: a lattice cell of an element the case does not have (corrupt checkpoint)");
    element_force_.resize(element_velocity_.size());
    relink();
    prepare_surface();  // the normals; new interface cells' outgoing populations
}

namespace {

template <class T>
void append(std::vector<std::byte>& out, const T& value) {
    const auto* bytes = reinterpret_cast<const std::byte*>(&value);
    out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <class T>
T take(std::span<const std::byte> in, std::size_t& at) {
    if (at + sizeof(T) > in.size()) throw std::logic_error("import_planes: the block ends early");
    T value;
    std::memcpy(&value, in.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
}

}  // namespace

// Field by field, each row's run of the planes' cells in one copy (a cell at a time, a face move took
// ~30 ms on a slab of 200 planes of 576 cells, as long as a hundred steps' halo exchanges).
template <class Real>
template <class T, bool Export>
void FluidLattice<Real>::plane_rows(
    int x0, int planes, std::conditional_t<Export, const T*, T*> field,
    std::conditional_t<Export, std::vector<std::byte>&, std::span<const std::byte>> io,
    std::size_t& at) const {
    const std::size_t run = sizeof(T) * static_cast<std::size_t>(planes);
    const std::size_t bytes = run * static_cast<std::size_t>(shape_.ny) * static_cast<std::size_t>(shape_.nz);
    if constexpr (Export) {
        io.resize(at + bytes);
    } else if (at + bytes > io.size()) {
        throw std::logic_error("import_planes: the block ends early");
    }
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y, at += run) {
            if constexpr (Export)
                std::memcpy(io.data() + at, field + index(x0, y, z), run);
            else
                std::memcpy(field + index(x0, y, z), io.data() + at, run);
        }
}

template <class Real>
void FluidLattice<Real>::export_planes(int x0, int planes, std::vector<std::byte>& out) const {
    std::size_t at = out.size();
    // (grown once: a block grown field by field was copied over and over, 20 ms a face move)
    const std::size_t cells = static_cast<std::size_t>(planes) * static_cast<std::size_t>(shape_.ny) *
                              static_cast<std::size_t>(shape_.nz);
    out.reserve(at +
                cells *
                    ((Q + 2) * sizeof(Real) + sizeof(CellType) + sizeof(std::uint16_t) + sizeof(double) + 1) +
                16);
    moving_fields(*this, *this, [&](const auto* field, const auto*) {
        plane_rows<std::remove_cvref_t<decltype(*field)>, true>(x0, planes, field, out, at);
    });
    append(out, static_cast<std::uint8_t>(outlet_.empty() ? 0 : 1));
    at = out.size();
    if (!outlet_.empty()) plane_rows<std::uint8_t, true>(x0, planes, outlet_.data(), out, at);
    std::vector<double> records;
    pack_surface(x0, planes, records);
    append(out, static_cast<std::uint64_t>(records.size()));
    for (const double r : records) append(out, r);
}

template <class Real>
void FluidLattice<Real>::copy_planes(const FluidLattice& from, int from_x0, int x0, int planes) {
    if (from.shape_.ny != shape_.ny || from.shape_.nz != shape_.nz)
        throw std::logic_error("copy_planes: a lattice of another cross-section");
    const auto rows = [&](auto* to, const auto* source) {
        const std::size_t run = sizeof(*source) * static_cast<std::size_t>(planes);
        for (int z = 0; z < shape_.nz; ++z)
            for (int y = 0; y < shape_.ny; ++y)
                std::memcpy(to + index(x0, y, z), source + from.index(from_x0, y, z), run);
    };
    moving_fields(*this, from, rows);
    if (!from.outlet_.empty()) {
        if (outlet_.empty()) outlet_.assign(n_, 0);
        rows(outlet_.data(), from.outlet_.data());
    } else if (!outlet_.empty()) {
        for_planes(x0, planes, [&](std::size_t k) { outlet_[k] = 0; });
    }
    std::vector<double> records;
    from.pack_surface(from_x0, planes, records);
    replace_surface(x0, planes, records);
}

template <class Real>
std::size_t FluidLattice<Real>::import_planes(int x0, int planes, std::span<const std::byte> in) {
    std::size_t at = 0;
    moving_fields(*this, *this, [&](auto* field, const auto*) {
        plane_rows<std::remove_cvref_t<decltype(*field)>, false>(x0, planes, field, in, at);
    });
    if (take<std::uint8_t>(in, at) != 0) {
        if (outlet_.empty()) outlet_.assign(n_, 0);
        plane_rows<std::uint8_t, false>(x0, planes, outlet_.data(), in, at);
    } else if (!outlet_.empty()) {
        for_planes(x0, planes, [&](std::size_t k) { outlet_[k] = 0; });
    }
    std::vector<double> records(take<std::uint64_t>(in, at));
    for (double& r : records) r = take<double>(in, at);
    replace_surface(x0, planes, records);
    return at;
}

template <class Real>
void FluidLattice<Real>::record_steps(std::uint64_t steps, std::span<const Vec3> element_forces,
                                      ClampCounts clamps, std::uint64_t updated_cells,
                                      const SurfaceStats& surface,
                                      const std::array<double, max_outlets>& drained,
                                      const std::array<double, 3>& region_inflow) {
    steps_ = steps;
    element_force_.assign(element_forces.begin(), element_forces.end());
    clamps_ = clamps;
    updated_cells_ = updated_cells;
    surface_stats_ = surface;
    drained_ = drained;
    region_inflow_ = region_inflow;
}

template <class Real>
void FluidLattice<Real>::adopt(const FluidLattice& from) {
    steps_ = from.steps_;
    accel_ = from.accel_;
    element_velocity_ = from.element_velocity_;
    // and what the last step measured, as the observers of that step read it
    element_force_ = from.element_force_;
    clamps_ = from.clamps_;
    updated_cells_ = from.updated_cells_;
    surface_stats_ = from.surface_stats_;
    // the rank's own planes' drained mass and the region's inflow so far (their sums over the ranks are kept)
    drained_ = from.drained_;
    region_inflow_ = from.region_inflow_;
}

template <class Real>
void FluidLattice<Real>::moments(std::size_t k, double& rho, Vec3& u) const {
    const auto [x, y, z] = coords(k);
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
void FluidLattice<Real>::snapshot(FluidFields& out) const {
    out.shape(slab_.own_end - slab_.own_begin, shape_.ny, shape_.nz, slab_.own_begin);
    // the cells' fields on all threads (each row its own), then the sums in the order of totals(): the
    // same sums
    const int planes = slab_.own_end - slab_.own_begin;
    const auto rows = static_cast<std::ptrdiff_t>(shape_.ny) * shape_.nz;
#pragma omp parallel for schedule(static) if (rows * planes >= 16384)
    for (std::ptrdiff_t row = 0; row < rows; ++row) {
        const int y = static_cast<int>(row % shape_.ny), z = static_cast<int>(row / shape_.ny);
        std::size_t c = static_cast<std::size_t>(row) * static_cast<std::size_t>(planes);
        for (int x = slab_.own_begin; x < slab_.own_end; ++x, ++c) {
            const std::size_t k = index(x, y, z);
            out.type[c] = type_[k];
            out.covered[c] = covered_by_solid(k) ? 1 : 0;
            out.fill[c] = fill(k);
            out.tau[c] = tau(k);
            out.density[c] = 0.0;
            out.velocity[c] = {};
            if (type_[k] == CellType::fluid || type_[k] == CellType::interface)
                moments(k, out.density[c], out.velocity[c]);
        }
    }
    FluidTotals t;
    std::size_t c = 0;
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y)
            for (int x = slab_.own_begin; x < slab_.own_end; ++x, ++c) {
                if (out.type[c] != CellType::fluid && out.type[c] != CellType::interface) continue;
                t.mass += out.type[c] == CellType::interface ? mass_[index(x, y, z)] : out.density[c];
                t.max_speed = std::max(t.max_speed, norm(out.velocity[c]));
            }
    out.drained = drained_;
    out.region_inflow = region_inflow_;
    out.totals = t;
    out.interface_cells = interface_count();
    out.clamps = clamps_;
}

template class FluidLattice<float>;
template class FluidLattice<double>;

}  // namespace sabo::lbm
