// SPDX-License-Identifier: MIT
// Free surface by mass tracking (docs/lbm.md; Körner et al. 2005, Thürey & Rüde 2009) on the AA-pattern
// lattice. Each step: (1) the sweep collides the interface cells with the populations from the gas
// side reconstructed (reconstruct(), from the outgoing populations and normals kept by (4)); after it,
// (2) exchange_mass() — the mass each interface cell exchanged with its neighbours through the
// populations just streamed (so the tracked mass and the fluid's densities agree after every step),
// λ = m/ρ, and which cells fill or empty; (3) convert_cells() — filled cells become fluid and their
// gas neighbours interface, emptied cells become gas and their fluid neighbours interface (filling
// wins), the excess mass goes to the interface neighbours, the list of interface cells is rebuilt;
// (4) prepare_surface() — outgoing populations and normals of the new list. (2)-(4) work on the
// interface cells only, in ascending cell order: deterministic, and total mass is conserved to
// round-off (docs/lbm.md).
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/error.h"
#include "core/prefetch.h"
#include "core/stopwatch.h"
#include "lbm/collision.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

using detail::equilibrium;
using detail::returned;

namespace {
constexpr double atmosphere = 1.0;  // ρ_A
// Converting cells from which a conversion's per-cell loops (each cell writing only its own entries) run
// on all threads: the same results for any thread count
constexpr std::ptrdiff_t parallel_conversions = 64;
}  // namespace

// f_j(k) before the next collision: steps_ even (the last step was odd, or none): the own slot j;
// steps_ odd: slot j̄ of the neighbour it comes from (own slot j plus the wall term from an obstacle).
template <class Real>
double FluidLattice<Real>::incoming(int x, int y, int z, std::size_t k, int j) const {
    const auto uj = static_cast<std::size_t>(j);
    if (steps_ % 2 == 0) return static_cast<double>(f_[uj * slot_ + k]) + weight[j];
    const std::ptrdiff_t src = neighbour(x, y, z, j, -1);
    if (solid(src))
        return returned(static_cast<double>(f_[uj * slot_ + k]) + weight[j], opposite(j),
                        element_velocity_[element_of(src)]);
    return static_cast<double>(
               f_[static_cast<std::size_t>(opposite(j)) * slot_ + static_cast<std::size_t>(src)]) +
           weight[j];
}

// The same for a link whose neighbour src (along −c_j) is a fluid or interface cell: no neighbour lookup.
template <class Real>
double FluidLattice<Real>::streamed_in(std::size_t k, int j, std::size_t src) const {
    const auto uj = static_cast<std::size_t>(j);
    if (steps_ % 2 == 0) return static_cast<double>(f_[uj * slot_ + k]) + weight[j];
    return static_cast<double>(f_[static_cast<std::size_t>(opposite(j)) * slot_ + src]) + weight[j];
}

// f_i*(k) after the last collision: steps_ odd (the last step was even): own slot ī; steps_ even: slot
// i of the neighbour it streamed to (toward an obstacle: the own slot ī holds the returned one).
template <class Real>
double FluidLattice<Real>::outgoing(int x, int y, int z, std::size_t k, int i) const {
    const auto ui = static_cast<std::size_t>(i);
    const auto uo = static_cast<std::size_t>(opposite(i));
    if (steps_ % 2 == 1) return static_cast<double>(f_[uo * slot_ + k]) + weight[i];
    const std::ptrdiff_t dst = neighbour(x, y, z, i, 1);
    if (solid(dst)) {
        const Vec3& uw = element_velocity_[element_of(dst)];
        return static_cast<double>(f_[uo * slot_ + k]) + weight[i] +
               6.0 * weight[i] * (cx[i] * uw.x + cy[i] * uw.y + cz[i] * uw.z);
    }
    return static_cast<double>(f_[ui * slot_ + static_cast<std::size_t>(dst)]) + weight[i];
}

template <class Real>
void FluidLattice<Real>::set_outgoing(int x, int y, int z, std::size_t k, int i, double value) {
    const auto ui = static_cast<std::size_t>(i);
    const auto uo = static_cast<std::size_t>(opposite(i));
    if (steps_ % 2 == 1) {
        f_[uo * slot_ + k] = static_cast<Real>(value - weight[i]);
        return;
    }
    const std::ptrdiff_t dst = neighbour(x, y, z, i, 1);
    if (solid(dst))
        f_[uo * slot_ + k] =
            static_cast<Real>(returned(value, i, element_velocity_[element_of(dst)]) - weight[i]);
    else
        f_[ui * slot_ + static_cast<std::size_t>(dst)] = static_cast<Real>(value - weight[i]);
}

template <class Real>
std::size_t FluidLattice<Real>::surface_index(std::size_t k) const {
    const auto it = std::lower_bound(interface_.begin(), interface_.end(), static_cast<std::uint32_t>(k));
    return static_cast<std::size_t>(it - interface_.begin());
}

// n = −∇λ by central differences; an obstacle (or the outside) neighbour counts with the cell's own λ.
template <class Real>
Vec3 FluidLattice<Real>::surface_normal(int x, int y, int z) const {
    const double own = static_cast<double>(fill_[index(x, y, z)]);
    // (inlined, with neighbour(): out of line they cost the fluid-only debris run 4 %)
    const auto lambda = [&](int i) SABO_ALWAYS_INLINE {
        const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
        return solid(n) ? own : static_cast<double>(fill_[static_cast<std::size_t>(n)]);
    };
    // directions 1..6: +x, −x, +y, −y, +z, −z
    return {-0.5 * (lambda(1) - lambda(2)), -0.5 * (lambda(3) - lambda(4)), -0.5 * (lambda(5) - lambda(6))};
}

template <class Real>
void FluidLattice<Real>::exchange_mass() {
    const std::size_t ni = interface_.size();
    convert_.resize(ni);
    new_fill_.resize(ni);
    const auto sni = static_cast<std::ptrdiff_t>(ni);
    const bool even = steps_ % 2 == 0;
    // The populations read here were written by the sweep, long out of the caches, one line per direction
    // and cell (waiting for them was 3/4 of this loop): those of the cell `ahead` places further on are
    // requested early (the loop took 10 % less time)
    constexpr std::size_t ahead = 4;
    const auto request = [&](std::size_t s) {
        const std::size_t k = interface_[s];
        const std::ptrdiff_t* nb = surface_nb_.data() + s * Q;
        const std::uint32_t gas = surface_kinds_[s].gas;
        for (int i = 1; i < Q; ++i) {
            if (nb[i] < 0 || (gas >> i & 1U) != 0) continue;
            const std::size_t at =
                even ? static_cast<std::size_t>(opposite(i)) * slot_ + k
                     : static_cast<std::size_t>(i) * slot_ + static_cast<std::size_t>(nb[i]);
            prefetch_read(f_.data() + at);
        }
    };
    // every cell reads populations and its neighbours' λ and writes only its own mass: no races (λ is
    // updated in a second loop)
#pragma omp parallel for schedule(static) if (ni >= 1024)
    for (std::ptrdiff_t s = 0; s < sni; ++s) {
        const auto us = static_cast<std::size_t>(s);
        if (us + ahead < ni) request(us + ahead);
        const std::size_t k = interface_[us];
        const double own = static_cast<double>(fill_[k]);
        double dm = 0.0;
        const double* sent = out_.data() + us * Q;
        const std::ptrdiff_t* nb = surface_nb_.data() + us * Q;  // as the sweep found them
        const NeighbourKinds kinds = surface_kinds_[us];
        const bool touches_gas = kinds.gas != 0, touches_fluid = kinds.fluid != 0;
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = nb[i];
            // solid and gas neighbours exchange nothing
            if (n < 0 || (kinds.gas >> i & 1U) != 0) continue;
            const auto un = static_cast<std::size_t>(n);
            const double alpha =
                (kinds.fluid >> i & 1U) != 0 ? 1.0 : 0.5 * (own + static_cast<double>(fill_[un]));
            // Δm_i = α (f_ī arrived from n − f_i* sent toward n), both streamed in the step just done
            // (f_i* as the sweep recorded it, rounded as the lattice holds it)
            dm += alpha * (streamed_in(k, opposite(i), un) - sent[i]);
        }
        const double m = mass_[k] + dm, rho = surface_rho_[us];
        mass_[k] = m;
        new_fill_[us] = static_cast<Real>(m / rho);
        std::int8_t convert = m > (1.0 + surface_epsilon) * rho ? 1 : (m < -surface_epsilon * rho ? -1 : 0);
        // a cell with no gas neighbour (left inside the fluid when a pocket of gas closed) becomes fluid
        // whatever its mass (2: its deficit is spread over the whole surface): kept as interface cell, the
        // gas-side reconstruction would push it toward an atmosphere that is not there, by about
        // (ρ − ρ_A)/3 per step, and it runs away (Thürey & Rüde 2009 fill such cells too)
        if (convert == 0 && !touches_gas) convert = 2;
        // a cell with no fluid neighbour (spray, a drop, the tip of a sheet one cell thick) empties unless it
        // is over-full (-1: its mass goes to its interface neighbours, else over the whole surface): its
        // populations all come from the gas-side reconstruction with its own velocity, so nothing slows it
        // down and gravity accelerates it without bound until the lattice becomes unstable (a coarse C5
        // blew up at 2.1 s, lattice speed 126; OpenLB's free surface empties these cells too, its
        // "lonely threshold" 1)
        if (convert == 0 && !touches_fluid) convert = -1;
        // an outlet cell empties whatever its mass: what reached it leaves the domain (convert_cells)
        if (outlet_of(k) != 0) convert = -1;
        convert_[us] = convert;
    }
#pragma omp parallel for schedule(static) if (ni >= 1024)
    for (std::ptrdiff_t s = 0; s < sni; ++s)
        fill_[interface_[static_cast<std::size_t>(s)]] = new_fill_[static_cast<std::size_t>(s)];
}

template <class Real>
void FluidLattice<Real>::prepare_surface() {
    const std::size_t ni = interface_.size();
    out_.resize(ni * Q);
    surface_nb_.resize(ni * Q);  // written by the sweep
    surface_kinds_.resize(ni);
    out_known_.resize(ni, 0);
    normal_.resize(ni);
    const auto sni = static_cast<std::ptrdiff_t>(ni);
#pragma omp parallel for schedule(static) if (ni >= 1024)
    for (std::ptrdiff_t s = 0; s < sni; ++s) prepare_surface_cell(static_cast<std::size_t>(s));
}

template <class Real>
void FluidLattice<Real>::prepare_surface_cell(std::size_t s) {
    const std::size_t k = interface_[s];
    const auto [x, y, z] = coords(k);
    // the sweep kept the outgoing populations of the cells that were interface cells in it; the new ones
    // (and all of them before the first step) are read from the lattice
    if (out_known_[s] == 0)
        for (int i = 0; i < Q; ++i) out_[s * Q + static_cast<std::size_t>(i)] = outgoing(x, y, z, k, i);
    normal_[s] = surface_normal(x, y, z);
}

template <class Real>
void FluidLattice<Real>::surface_edited(int planes) {
    for (std::size_t s = 0; s < interface_.size(); ++s)
        if (coords(interface_[s])[0] <= planes) prepare_surface_cell(s);
}

template <class Real>
void FluidLattice<Real>::reconstruct(std::size_t s, const std::ptrdiff_t* nb, std::uint32_t gas_bits,
                                     double* f, std::size_t stride) const {
    const Vec3& u = surface_u_[s];
    const Vec3& n = normal_[s];
    // a direction tangential to the surface (n·c_j = 0 exactly on a flat one) must not flip between
    // reconstructed and kept on the round-off of n: that would make the result depend on how the sum
    // was rounded (a flat surface then grew lateral currents of 1e-4 from 1e-17 within 30 steps)
    const double tangential = 1e-9 * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
    // f_j^eq + f_j̄^eq at (ρ_A, u): the odd parts cancel, 2 w_j ρ_A (1 + 4.5 (c_j·u)² − 1.5 u²)
    const double even = 1.0 - 1.5 * norm2(u);
    for (int j = 1; j < Q; ++j) {
        const std::ptrdiff_t src = nb[opposite(j)];
        if (src < 0) continue;  // bounced back
        const bool from_gas = (gas_bits >> opposite(j) & 1U) != 0;
        const bool gas_side = n.x * cx[j] + n.y * cy[j] + n.z * cz[j] < -tangential;  // against the normal
        if (!from_gas && !gas_side) continue;
        const int o = opposite(j);
        // f_j = f_j^eq(ρ_A, u) + f_j̄^eq(ρ_A, u) − f_j̄*(x), f_j̄* leaving x toward where f_j comes from
        const double cu = cx[j] * u.x + cy[j] * u.y + cz[j] * u.z;
        f[static_cast<std::size_t>(j) * stride] =
            2.0 * weight[j] * atmosphere * (even + 4.5 * cu * cu) - out_[s * Q + static_cast<std::size_t>(o)];
    }
}

template <class Real>
void FluidLattice<Real>::convert_cells() {
    const std::size_t ni = interface_.size();
    surface_stats_ = {};
    // the step's lists live in scratch_ (no allocation once their capacity has grown)
    // (named references, not a structured binding: OpenMP regions cannot capture those before clang 16)
    auto& filled = scratch_.filled;
    auto& emptied = scratch_.emptied;
    auto& born = scratch_.born;
    auto& enclosed = scratch_.enclosed;
    auto& filled_normal = scratch_.filled_normal;
    auto& emptied_normal = scratch_.emptied_normal;
    auto& born_rho = scratch_.born_rho;
    auto& born_u = scratch_.born_u;
    auto& demoted = scratch_.demoted;
    auto& demoted_rho = scratch_.demoted_rho;
    auto& demoted_u = scratch_.demoted_u;
    auto& filled_excess = scratch_.filled_excess;
    auto& emptied_excess = scratch_.emptied_excess;
    auto& next = scratch_.next;
    auto& next_rho = scratch_.next_rho;
    auto& next_out = scratch_.next_out;
    auto& next_u = scratch_.next_u;
    auto& next_known = scratch_.next_known;
    auto& next_from = scratch_.next_from;
    for (auto* list : {&filled, &emptied, &born, &demoted, &next}) list->clear();
    enclosed.clear();
    // filling wins: an emptied cell next to a filled one stays interface (else fluid would touch gas)
    for (std::size_t s = 0; s < ni; ++s) {
        if (convert_[s] > 0) {
            filled.push_back(interface_[s]);
            enclosed.push_back(convert_[s] == 2 ? 1 : 0);
        }
    }
    // the filled cells' neighbours looked up on all threads (an interface neighbour's place in the list is a
    // search), the lists and marks written after in order
    auto& marks = scratch_.marks;
    constexpr std::uint64_t gas_mark = 1ULL << 62, interface_mark = 2ULL << 62, mark_value = gas_mark - 1;
    marks.resize(filled.size() * (Q - 1));
    const auto nf = static_cast<std::ptrdiff_t>(filled.size());
#pragma omp parallel for schedule(static) if (nf >= parallel_conversions)
    for (std::ptrdiff_t a = 0; a < nf; ++a) {
        const auto [x, y, z] = coords(filled[static_cast<std::size_t>(a)]);
        std::uint64_t* mark = marks.data() + a * (Q - 1);
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
            const CellType t = n < 0 ? CellType::obstacle : type_[static_cast<std::size_t>(n)];
            mark[i - 1] =
                t == CellType::gas         ? gas_mark | static_cast<std::uint64_t>(n)
                : t == CellType::interface ? interface_mark | surface_index(static_cast<std::size_t>(n))
                                           : 0;
        }
    }
    for (const std::uint64_t mark : marks) {
        if ((mark & gas_mark) != 0) born.push_back(static_cast<std::uint32_t>(mark & mark_value));
        if ((mark & interface_mark) != 0) {
            std::int8_t& c = convert_[mark & mark_value];
            c = std::max<std::int8_t>(c, 0);
        }
    }
    for (std::size_t s = 0; s < ni; ++s) {
        if (convert_[s] < 0) emptied.push_back(interface_[s]);
    }
    std::sort(born.begin(), born.end());
    born.erase(std::unique(born.begin(), born.end()), born.end());
    // normals of the converting cells from λ before any change
    filled_normal.resize(filled.size());
    emptied_normal.resize(emptied.size());
    const auto ne = static_cast<std::ptrdiff_t>(emptied.size());
#pragma omp parallel for schedule(static) if (nf + ne >= parallel_conversions)
    for (std::ptrdiff_t a = 0; a < nf + ne; ++a) {
        const bool fills = a < nf;
        const auto at = static_cast<std::size_t>(fills ? a : a - nf);
        const auto [x, y, z] = coords(fills ? filled[at] : emptied[at]);
        (fills ? filled_normal : emptied_normal)[at] = surface_normal(x, y, z);
    }
    // gas → interface next to the filled cells: f^eq(ρ̄, ū) of the fluid and interface neighbours, m = 0
    born_rho.resize(born.size());
    born_u.resize(born.size());
    const auto nb = static_cast<std::ptrdiff_t>(born.size());
#pragma omp parallel for schedule(static) if (nb >= parallel_conversions)
    for (std::ptrdiff_t sb = 0; sb < nb; ++sb) {
        const auto b = static_cast<std::size_t>(sb);
        const auto [x, y, z] = coords(born[b]);
        double rho_sum = 0.0;
        Vec3 u_sum{};
        int count = 0;
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
            if (solid_or_gas(n)) continue;
            double rho = 0.0;
            Vec3 u;
            moments(static_cast<std::size_t>(n), rho, u);
            rho_sum += rho;
            u_sum += u;
            ++count;
        }
        born_rho[b] = count > 0 ? rho_sum / count : atmosphere;
        born_u[b] = count > 0 ? u_sum / count : Vec3{};
    }
    // (each born cell writes its own outgoing slots: no two cells share one)
#pragma omp parallel for schedule(static) if (nb >= parallel_conversions)
    for (std::ptrdiff_t sb = 0; sb < nb; ++sb) {
        const auto b = static_cast<std::size_t>(sb);
        const std::size_t k = born[b];
        const auto [x, y, z] = coords(k);
        type_[k] = CellType::interface;
        fill_[k] = Real(0);
        mass_[k] = 0.0;
        tau_[k] = static_cast<Real>(rheology_.bingham ? rheology_.tau_max : rheology_.tau);
        for (int i = 0; i < Q; ++i) set_outgoing(x, y, z, k, i, equilibrium(i, born_rho[b], born_u[b]));
    }
    // fluid → interface next to the emptied cells: keeps its populations, m = ρ
    for (const std::uint32_t k : emptied) {
        const auto [x, y, z] = coords(k);
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
            if (n >= 0 && type_[static_cast<std::size_t>(n)] == CellType::fluid)
                demoted.push_back(static_cast<std::uint32_t>(n));
        }
    }
    std::sort(demoted.begin(), demoted.end());
    demoted.erase(std::unique(demoted.begin(), demoted.end()), demoted.end());
    demoted_rho.resize(demoted.size());
    demoted_u.resize(demoted.size());
    const auto nd = static_cast<std::ptrdiff_t>(demoted.size());
#pragma omp parallel for schedule(static) if (nd >= parallel_conversions)
    for (std::ptrdiff_t d = 0; d < nd; ++d)
        moments(demoted[static_cast<std::size_t>(d)], demoted_rho[static_cast<std::size_t>(d)],
                demoted_u[static_cast<std::size_t>(d)]);
    // the type changes; the excess mass of the converted cells (the three lists are disjoint: each cell
    // writes its own; the densities are read before any type changes)
    filled_excess.resize(filled.size());
    emptied_excess.resize(emptied.size());
    auto& filled_rho = scratch_.filled_rho;
    filled_rho.resize(filled.size());
#pragma omp parallel for schedule(static) if (nf >= parallel_conversions)
    for (std::ptrdiff_t a = 0; a < nf; ++a) {
        // the density the cell now holds as fluid: its incoming populations (all real: its gas
        // neighbours have just been given theirs), so tracked mass and populations stay in step
        const std::size_t k = filled[static_cast<std::size_t>(a)];
        const auto [x, y, z] = coords(k);
        double rho = 0.0;
        for (int i = 0; i < Q; ++i) rho += incoming(x, y, z, k, i);
        filled_rho[static_cast<std::size_t>(a)] = rho;
        filled_excess[static_cast<std::size_t>(a)] = mass_[k] - rho;
    }
#pragma omp parallel if (nf + ne + nd >= 16 * parallel_conversions)  // little work per cell
    {
#pragma omp for schedule(static) nowait
        for (std::ptrdiff_t a = 0; a < nf; ++a) {
            const std::size_t k = filled[static_cast<std::size_t>(a)];
            type_[k] = CellType::fluid;
            mass_[k] = filled_rho[static_cast<std::size_t>(a)];
            fill_[k] = Real(1);
        }
#pragma omp for schedule(static) nowait
        for (std::ptrdiff_t a = 0; a < ne; ++a) {
            const std::size_t k = emptied[static_cast<std::size_t>(a)];
            emptied_excess[static_cast<std::size_t>(a)] = mass_[k];
            type_[k] = CellType::gas;
            mass_[k] = 0.0;
            fill_[k] = Real(0);
        }
#pragma omp for schedule(static)
        for (std::ptrdiff_t d = 0; d < nd; ++d) {
            const std::size_t k = demoted[static_cast<std::size_t>(d)];
            type_[k] = CellType::interface;
            mass_[k] = demoted_rho[static_cast<std::size_t>(d)];
            fill_[k] = Real(1);
        }
    }
    // the new list of interface cells and their last-collision state: the three ascending lists merged
    // (surviving interface cells, born, demoted), each entry's source recorded; then the entries filled,
    // each writing its own
    constexpr std::uint32_t from_born = 1U << 30, from_demoted = 2U << 30, index_bits = from_born - 1;
    if (ni + born.size() + demoted.size() > index_bits)
        throw InputError("the free surface: more interface cells than its list can index (2^30)");
    next.clear();
    next_from.clear();
    {
        std::size_t a = 0, b = 0, d = 0;
        while (a < ni || b < born.size() || d < demoted.size()) {
            const std::uint32_t ka = a < ni ? interface_[a] : UINT32_MAX;
            const std::uint32_t kb = b < born.size() ? born[b] : UINT32_MAX;
            const std::uint32_t kd = d < demoted.size() ? demoted[d] : UINT32_MAX;
            if (ka <= kb && ka <= kd) {
                if (convert_[a] == 0) {  // neither filled nor emptied: still an interface cell
                    next.push_back(ka);
                    next_from.push_back(static_cast<std::uint32_t>(a));
                }
                ++a;
            } else if (kb <= kd) {
                next.push_back(kb);
                next_from.push_back(from_born | static_cast<std::uint32_t>(b++));
            } else {
                next.push_back(kd);
                next_from.push_back(from_demoted | static_cast<std::uint32_t>(d++));
            }
        }
    }
    const auto nn = static_cast<std::ptrdiff_t>(next.size());
    next_rho.resize(next.size());
    next_u.resize(next.size());
    next_known.resize(next.size());
    next_out.resize(next.size() * Q);
    // a surviving cell keeps the outgoing populations the sweep recorded (`out`); new ones get theirs in
    // prepare_surface()
#pragma omp parallel for schedule(static) if (nn >= 1024)
    for (std::ptrdiff_t e = 0; e < nn; ++e) {
        const auto ue = static_cast<std::size_t>(e);
        const std::uint32_t from = next_from[ue], at = from & index_bits;
        if (from < from_born) {
            next_rho[ue] = surface_rho_[at];
            next_u[ue] = surface_u_[at];
            next_known[ue] = out_known_[at] != 0 ? 1 : 0;
            if (out_known_[at] != 0)
                std::copy_n(out_.begin() + static_cast<std::ptrdiff_t>(at) * Q, Q, next_out.begin() + e * Q);
        } else {
            const bool was_born = (from & from_demoted) == 0;
            next_rho[ue] = was_born ? born_rho[at] : demoted_rho[at];
            next_u[ue] = was_born ? born_u[at] : demoted_u[at];
            next_known[ue] = 0;
        }
    }
    next_out.resize(next.size() * Q);
    interface_.swap(next);
    surface_rho_.swap(next_rho);
    surface_u_.swap(next_u);
    out_.swap(next_out);
    out_known_.swap(next_known);
    // excess mass to the interface neighbours, weighted by max(0, ±n·c_i) (uniform if all weights are
    // zero); with no interface neighbour at all it is spread over every interface cell (every slab's)
    auto& orphans = orphans_;
    orphans.clear();
    // its place in the undivided lattice's sum: filled cells (pass 0), then emptied ones, by global cell; a
    // slab's ghost cells' conversions are their owner's
    const auto orphan = [&](std::uint32_t k, std::uint64_t pass, double excess) {
        const auto [x, y, z] = coords(k);
        if (slab_.spread && !own_x(static_cast<std::size_t>(x))) return;
        orphans.push_back({OrphanMass::order_of(pass, x + slab_.first_global_x, y, z), excess});
    };
    // each converted cell's shares found on all threads (the types are final), then added in order: the
    // same sums as one cell after the other. Filled cells come first, then emptied ones.
    auto& share_to = scratch_.share_to;
    auto& share_mass = scratch_.share_mass;
    share_to.resize((filled.size() + emptied.size()) * (Q - 1));
    share_mass.resize(share_to.size());
    constexpr std::int64_t no_share = -1, orphaned = -2;  // share_to's first entry -2: no interface neighbour
    // (where asked, set_pocket_reach: each thread searches near the closed pockets it meets)
    auto& searches = scratch_.pocket_search;
    if (pocket_reach_ > 0) {
        searches.resize(std::max(searches.size(), static_cast<std::size_t>(omp_get_max_threads())));
        for (PocketSearch& search : searches) search.found.clear();
        scratch_.pocket_thread.resize(filled.size());
        scratch_.pocket_first.resize(filled.size());
        scratch_.pocket_receivers.resize(filled.size());
    }
#pragma omp parallel for schedule(static) if (nf + ne >= parallel_conversions)
    for (std::ptrdiff_t c = 0; c < nf + ne; ++c) {
        const bool fills = c < nf;
        const auto at = static_cast<std::size_t>(fills ? c : c - nf);
        const std::uint32_t k = fills ? filled[at] : emptied[at];
        std::int64_t* to = share_to.data() + c * (Q - 1);
        double* mass = share_mass.data() + c * (Q - 1);
        std::fill_n(to, Q - 1, no_share);
        if (fills && enclosed[at] != 0) {  // the volume of a closed gas pocket: taken from the whole surface,
            to[0] = orphaned;              // not from the few cells around it (those emptied in a cascade)
            if (pocket_reach_ > 0) {       // or from the surface near it
                const int thread = omp_get_thread_num();
                PocketSearch& search = searches[static_cast<std::size_t>(thread)];
                const std::size_t first = search.found.size();
                find_pocket_receivers(k, search);
                scratch_.pocket_thread[at] = static_cast<std::uint32_t>(thread);
                scratch_.pocket_first[at] = static_cast<std::uint32_t>(first);
                scratch_.pocket_receivers[at] = static_cast<std::uint32_t>(search.found.size() - first);
            }
            continue;
        }
        if (!fills && outlet_of(k) != 0) continue;  // left the domain
        const Vec3& normal = fills ? filled_normal[at] : emptied_normal[at];
        const double sign = fills ? 1.0 : -1.0, excess = fills ? filled_excess[at] : emptied_excess[at];
        // excess mass to the interface neighbours, weighted by max(0, ±n·c_i) (uniform if all weights are
        // zero)
        const auto [x, y, z] = coords(k);
        double weights[Q] = {};
        std::ptrdiff_t receiver[Q] = {};
        double total = 0.0;
        int count = 0;
        for (int i = 1; i < Q; ++i) {
            const std::ptrdiff_t n = neighbour(x, y, z, i, 1);
            receiver[i] = n < 0 || type_[static_cast<std::size_t>(n)] != CellType::interface ? -1 : n;
            if (receiver[i] < 0) continue;
            weights[i] = std::max(0.0, sign * (normal.x * cx[i] + normal.y * cy[i] + normal.z * cz[i]));
            total += weights[i];
            ++count;
        }
        if (count == 0) {
            to[0] = orphaned;
            continue;
        }
        for (int i = 1; i < Q; ++i) {
            if (receiver[i] < 0) continue;
            const double share = total > 0.0 ? weights[i] / total : 1.0 / count;
            to[i - 1] = receiver[i];
            mass[i - 1] = share * excess;
        }
    }
    for (std::ptrdiff_t c = 0; c < nf + ne; ++c) {
        const bool fills = c < nf;
        const auto at = static_cast<std::size_t>(fills ? c : c - nf);
        const std::uint32_t k = fills ? filled[at] : emptied[at];
        const std::int64_t* to = share_to.data() + c * (Q - 1);
        const double* mass = share_mass.data() + c * (Q - 1);
        if (!fills && outlet_of(k) != 0) {
            if (!slab_.spread || own_plane(k))  // left the domain (a ghost's: its owner's)
                drained_[outlet_of(k) - 1] += emptied_excess[at];
            continue;
        }
        // with no interface neighbour at all the excess is spread over every interface cell (every slab's);
        // an enclosed cell's deficit over those near it, where asked (set_pocket_reach)
        if (to[0] == orphaned) {
            if (fills && enclosed[at] != 0 && pocket_reach_ > 0 && scratch_.pocket_receivers[at] > 0) {
                const auto& found = searches[scratch_.pocket_thread[at]].found;
                spread_pocket(
                    k, filled_excess[at],
                    std::span(found).subspan(scratch_.pocket_first[at], scratch_.pocket_receivers[at]));
                continue;
            }
            orphan(k, fills ? 0 : 1, fills ? filled_excess[at] : emptied_excess[at]);
            continue;
        }
        for (int i = 0; i < Q - 1; ++i)
            if (to[i] >= 0) mass_[static_cast<std::size_t>(to[i])] += mass[i];
    }
    std::uint64_t surface_cells = slab_.spread ? interface_count() : interface_.size();
    surface_stats_.orphan_excess_cells = orphans.size();
    // (the region's own orphans: the list holds this slab's alone until the spread)
    const double region_orphans = region_.empty() ? 0.0 : region_orphan_excess(orphans);
    // every slab's, in order, and their whole surface
    if (slab_.spread) {
        // (the wait for the other ranks' orphan mass is theirs to explain, and the halo counts it among the
        // exchanges: not this pass's time)
        const auto start = std::chrono::steady_clock::now();
        slab_.spread(orphans, surface_cells);
        surface_seconds_.conversions -= seconds_since(start);
    }
    double orphan_total = 0.0, share = 0.0;
    for (const OrphanMass& o : orphans) orphan_total += o.mass;
    if (orphan_total != 0.0 && surface_cells > 0) {
        share = orphan_total / static_cast<double>(surface_cells);
        const auto nn = static_cast<std::ptrdiff_t>(interface_.size());
#pragma omp parallel for schedule(static) if (nn >= 1024)
        for (std::ptrdiff_t s = 0; s < nn; ++s) mass_[interface_[static_cast<std::size_t>(s)]] += share;
    }
    if (!region_.empty()) count_region_conversions(share, region_orphans);
    for (std::size_t s = 0; s < interface_.size(); ++s) {  // λ after the excess
        const std::size_t k = interface_[s];
        fill_[k] = static_cast<Real>(mass_[k] / surface_rho_[s]);
    }
    surface_stats_.filled = filled.size();
    surface_stats_.emptied = emptied.size();
}

template <class Real>
void FluidLattice<Real>::pack_surface(int x0, int planes, std::vector<double>& records) const {
    // row by row: the planes' cells of a row are consecutive in the ascending list
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y) {
            const std::size_t begin = index(x0, y, z), end = begin + static_cast<std::size_t>(planes);
            for (std::size_t s = surface_index(begin); s < interface_.size() && interface_[s] < end; ++s) {
                const Vec3 &u = surface_u_[s], &n = normal_[s];
                records.insert(records.end(), {surface_rho_[s], u.x, u.y, u.z, n.x, n.y, n.z});
                records.insert(records.end(), out_.begin() + static_cast<std::ptrdiff_t>(s * Q),
                               out_.begin() + static_cast<std::ptrdiff_t>((s + 1) * Q));
                records.push_back(out_known_[s]);
            }
        }
}

template <class Real>
bool FluidLattice<Real>::overwrite_surface(int x0, int planes, std::span<const double> records) {
    // the planes' interface cells as the list holds them, row by row, must be those the types name
    std::size_t r = 0;
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y) {
            const std::size_t begin = index(x0, y, z), end = begin + static_cast<std::size_t>(planes);
            std::size_t s = surface_index(begin);
            for (std::size_t k = begin; k < end; ++k) {
                if (type_[k] != CellType::interface) continue;
                if (s >= interface_.size() || interface_[s] != k) return false;
                if ((r + 1) * surface_record > records.size()) return false;
                const double* rec = records.data() + r++ * surface_record;
                surface_rho_[s] = rec[0];
                surface_u_[s] = {rec[1], rec[2], rec[3]};
                normal_[s] = {rec[4], rec[5], rec[6]};
                std::copy(rec + 7, rec + 7 + Q, out_.begin() + static_cast<std::ptrdiff_t>(s * Q));
                out_known_[s] = rec[7 + Q] != 0.0 ? 1 : 0;
                ++s;
            }
            if (s < interface_.size() && interface_[s] < end) return false;  // a cell that is no longer one
        }
    return r * surface_record == records.size();
}

template <class Real>
void FluidLattice<Real>::replace_surface(int x0, int planes, std::span<const double> records) {
    // the same cells as before (the surface moved within them or not at all): their state in place; else
    // the list is merged anew (a cell checked before the mismatch was found is rewritten below)
    if (overwrite_surface(x0, planes, records)) return;
    auto& next = scratch_.next;
    auto &next_rho = scratch_.next_rho, &next_out = scratch_.next_out;
    auto &next_u = scratch_.next_u, &next_normal = next_normal_;
    auto& next_known = scratch_.next_known;
    for (auto* list : {&next_rho, &next_out}) list->clear();
    for (auto* list : {&next_u, &next_normal}) list->clear();
    next.clear();
    next_known.clear();
    const auto take = [&](std::uint32_t k, double rho, const Vec3& u, const Vec3& normal, const double* out,
                          double known) {
        next.push_back(k);
        next_rho.push_back(rho);
        next_u.push_back(u);
        next_normal.push_back(normal);
        next_out.insert(next_out.end(), out, out + Q);
        next_known.push_back(known != 0.0 ? 1 : 0);
    };
    const auto keep = [&](std::size_t s) {
        take(interface_[s], surface_rho_[s], surface_u_[s], normal_[s], out_.data() + s * Q, out_known_[s]);
    };
    // merge, row by row, the cells kept (outside the planes) and the planes' interface cells (ascending)
    const std::size_t ni = interface_.size();
    std::size_t s = 0, r = 0;
    for (int z = 0; z < shape_.nz; ++z)
        for (int y = 0; y < shape_.ny; ++y) {
            const std::size_t begin = index(x0, y, z), end = begin + static_cast<std::size_t>(planes);
            for (; s < ni && interface_[s] < begin; ++s) keep(s);
            while (s < ni && interface_[s] < end) ++s;  // the planes' old cells: replaced
            for (std::size_t k = begin; k < end; ++k) {
                if (type_[k] != CellType::interface) continue;
                if ((r + 1) * surface_record > records.size())
                    throw std::logic_error("replace_surface: fewer records than interface cells");
                const double* rec = records.data() + r++ * surface_record;
                take(static_cast<std::uint32_t>(k), rec[0], {rec[1], rec[2], rec[3]},
                     {rec[4], rec[5], rec[6]}, rec + 7, rec[7 + Q]);
            }
        }
    for (; s < ni; ++s) keep(s);
    if (r * surface_record != records.size())
        throw std::logic_error("replace_surface: more records than interface cells");
    interface_.swap(next);
    surface_rho_.swap(next_rho);
    surface_u_.swap(next_u);
    normal_.swap(next_normal);
    out_.swap(next_out);
    out_known_.swap(next_known);
    surface_nb_.resize(interface_.size() * Q);  // written by the sweep
    surface_kinds_.resize(interface_.size());
}

#define SABO_FREE_SURFACE(R)                                                                               \
    template double FluidLattice<R>::incoming(int, int, int, std::size_t, int) const;                      \
    template double FluidLattice<R>::outgoing(int, int, int, std::size_t, int) const;                      \
    template double FluidLattice<R>::streamed_in(std::size_t, int, std::size_t) const;                     \
    template void FluidLattice<R>::set_outgoing(int, int, int, std::size_t, int, double);                  \
    template std::size_t FluidLattice<R>::surface_index(std::size_t) const;                                \
    template Vec3 FluidLattice<R>::surface_normal(int, int, int) const;                                    \
    template void FluidLattice<R>::exchange_mass();                                                        \
    template void FluidLattice<R>::reconstruct(std::size_t, const std::ptrdiff_t*, std::uint32_t, double*, \
                                               std::size_t) const;                                         \
    template void FluidLattice<R>::convert_cells();                                                        \
    template void FluidLattice<R>::prepare_surface();                                                      \
    template void FluidLattice<R>::prepare_surface_cell(std::size_t);                                      \
    template void FluidLattice<R>::surface_edited(int);                                                    \
    template void FluidLattice<R>::pack_surface(int, int, std::vector<double>&) const;                     \
    template void FluidLattice<R>::replace_surface(int, int, std::span<const double>);                     \
    template bool FluidLattice<R>::overwrite_surface(int, int, std::span<const double>);
SABO_FREE_SURFACE(float)
SABO_FREE_SURFACE(double)
#undef SABO_FREE_SURFACE

}  // namespace sabo::lbm
