// SPDX-License-Identifier: MIT
#include "dem/dem_solver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sabo::dem {

DemSolver::DemSolver(Particles particles, std::vector<Wall> walls, AnyContactLaws laws, const Vec3& gravity,
                     double dt, double skin)
    : p_(std::move(particles)),
      walls_(std::move(walls)),
      laws_(std::move(laws)),
      gravity_(gravity),
      dt_(dt),
      skin_(skin),
      wall_force_(walls_.size()) {
    if (walls_.size() > 65535) throw InputError("more than 65535 walls");
    refresh();
}

void DemSolver::refresh() {
    lists_stale_ = true;
    w_star_.resize(p_.size());
    contact_count_.resize(p_.size());
    compute_forces();
}

void DemSolver::set_wall_active(std::size_t wall, bool active) {
    walls_.at(wall).active = active;
    lists_stale_ = true;  // wall candidates depend on which walls are active
}

std::size_t DemSolver::memory_bytes() const {
    const std::size_t per_particle = 5 * sizeof(Vec3) + 4 * sizeof(double);
    const std::size_t pairs = pair_hist_.capacity() * sizeof(TangentialState) +
                              (pair_force_.capacity() + pair_torque_j_.capacity()) * sizeof(Vec3);
    const std::size_t wall_entries = wall_hist_.capacity() * sizeof(TangentialState) +
                                     wall_entry_force_.capacity() * sizeof(Vec3);
    const std::size_t prev = (prev_offset_.capacity() + prev_partner_.capacity() + prev_wall_offset_.capacity()) *
                                 sizeof(std::uint32_t) +
                             (prev_pair_hist_.capacity() + prev_wall_hist_.capacity()) * sizeof(TangentialState);
    return p_.x.capacity() * per_particle + list_.bytes() + pairs + wall_entries + prev;
}

KineticEnergy DemSolver::kinetic_energy() const {
    KineticEnergy e;
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        e.translational += 0.5 * p_.m[i] * norm2(p_.v[i]);
        e.rotational += 0.5 / p_.inv_j[i] * norm2(p_.w[i]);
    }
    return e;
}

void DemSolver::rebuild_lists() {
    // keep the old lists and histories, then look every new entry up in the old list of the same i
    prev_offset_ = list_.offsets();
    prev_partner_ = list_.partners();
    prev_wall_offset_ = list_.wall_offsets();
    prev_wall_ = list_.walls();
    std::swap(prev_pair_hist_, pair_hist_);
    std::swap(prev_wall_hist_, wall_hist_);
    const bool had_lists = list_.builds() > 0;

    list_.build(p_, walls_, skin_);
    pair_hist_.assign(list_.pair_count(), TangentialState{});
    pair_force_.resize(list_.pair_count());
    pair_torque_j_.resize(list_.pair_count());
    pair_fn_.resize(list_.pair_count());
    list_owner_.resize(list_.pair_count());
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        for (auto k = list_.begin(i); k < list_.end(i); ++k) list_owner_[k] = static_cast<std::uint32_t>(i);
    }
    wall_hist_.assign(list_.walls().size(), TangentialState{});
    wall_entry_force_.resize(list_.walls().size());
    wall_fn_.resize(list_.walls().size());
    if (!had_lists) return;

    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        const auto ob = prev_partner_.begin() + prev_offset_[i], oe = prev_partner_.begin() + prev_offset_[i + 1];
        for (auto k = list_.begin(i); k < list_.end(i); ++k) {
            const auto it = std::lower_bound(ob, oe, list_.partner(k));  // old lists are sorted by partner
            if (it != oe && *it == list_.partner(k)) pair_hist_[k] = prev_pair_hist_[it - prev_partner_.begin()];
        }
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
            for (auto q = prev_wall_offset_[i]; q < prev_wall_offset_[i + 1]; ++q) {
                if (prev_wall_[q] == list_.wall(k)) wall_hist_[k] = prev_wall_hist_[q];
            }
        }
    }
}

void DemSolver::compute_forces() {
    if (lists_stale_ || list_.needs_rebuild(p_)) {
        rebuild_lists();
        lists_stale_ = false;
    }
    std::visit([this](const auto& laws) { compute_forces(laws); }, laws_);
}

template <class Normal>
void DemSolver::compute_forces(const ContactLawSet<Normal>& laws) {
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
    const auto n = static_cast<std::ptrdiff_t>(p_.size());
    const double dt = dt_;
    std::uint64_t contacts = 0, sliding = 0;
    double max_ratio = 0.0;
    int bad = 0;

    // Pass 1: each mobile i evaluates its own pairs (j > i) and its wall contacts: normal and
    // tangential forces. The force on i is summed here; the reaction on j is parked in the pair
    // slot for pass 2.
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : contacts, sliding) reduction(max : max_ratio) \
    reduction(max : bad)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        const Vec3 xi = p_.x[i], vi = p_.v[i], wi = p_.w[i];
        const double ri = p_.r[i], inv_mi = p_.inv_m[i];
        Vec3 fi{}, ti{};
        std::uint32_t count = 0;
        for (auto k = list_.begin(i); k < list_.end(i); ++k) {
            const auto j = list_.partner(k);
            const Vec3 d = p_.x[j] - xi;
            const double rj = p_.r[j], rs = ri + rj;
            const double dist2 = norm2(d);
            if (dist2 >= rs * rs) {
                pair_hist_[k] = TangentialState{};
                pair_force_[k] = Vec3{};
                pair_torque_j_[k] = Vec3{};
                pair_fn_[k] = 0.0;
                continue;
            }
            const double dist = std::sqrt(dist2);
            if (!(dist > 1e-9 * rs)) {  // coincident centres, or NaN from a blown-up state
                bad = std::max(bad, std::isnan(dist) ? 2 : 1);
                continue;
            }
            const Vec3 nij = d / dist;
            const double delta = rs - dist;
            const auto& law = static_cast<std::ptrdiff_t>(j) < nm ? laws.particle_particle : laws.particle_barrier;
            const PairForce pf = pair_force(law, pair_hist_[k], nij, delta, vi - p_.v[j],
                                            ri * wi + rj * p_.w[j], 1.0 / (inv_mi + p_.inv_m[j]), ri * rj / rs, dt);
            fi += pf.force;
            ti += ri * pf.n_cross_ft;
            pair_force_[k] = pf.force;
            pair_torque_j_[k] = rj * pf.n_cross_ft;
            pair_fn_[k] = pf.fn;
            ++count;
            sliding += pair_hist_[k].sliding;
            max_ratio = std::max(max_ratio, delta / (2.0 * std::min(ri, rj)));
        }
        const double mi = 1.0 / inv_mi;
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
            const Wall& wall = walls_[list_.wall(k)];
            WallTouch c;
            if (!touches(wall, xi, ri, c)) {
                wall_hist_[k] = TangentialState{};
                wall_entry_force_[k] = Vec3{};
                wall_fn_[k] = 0.0;
                continue;
            }
            const auto& law = wall.barrier ? laws.particle_barrier : laws.particle_wall;
            const PairForce pf = pair_force(law, wall_hist_[k], c.n, c.delta, vi, ri * wi, mi, ri, dt);
            fi += pf.force;
            ti += ri * pf.n_cross_ft;
            wall_entry_force_[k] = pf.force;
            wall_fn_[k] = pf.fn;
            ++count;
            sliding += wall_hist_[k].sliding;
            max_ratio = std::max(max_ratio, c.delta / (2.0 * ri));
        }
        p_.f[i] = fi;
        p_.t[i] = ti;
        contact_count_[i] = static_cast<std::uint16_t>(std::min<std::uint32_t>(count, 65535));
        contacts += count;
    }
    if (bad == 2) throw RunError(fmt::format("t = {:.6g} s: non-finite particle position (the run blew up)", time_));
    if (bad == 1) throw RunError(fmt::format("t = {:.6g} s: two sphere centres coincide", time_));

    // Pass 2: reactions on partners, gathered in the fixed order of the transposed index.
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t j = 0; j < n; ++j) {
        Vec3 fj = j < nm ? p_.f[j] : Vec3{};
        Vec3 tj = j < nm ? p_.t[j] : Vec3{};
        std::uint32_t count = j < nm ? contact_count_[j] : 0;
        for (auto t = list_.t_begin(j); t < list_.t_end(j); ++t) {
            const auto k = list_.t_pair(t);
            fj -= pair_force_[k];
            tj += pair_torque_j_[k];
            count += pair_fn_[k] > 0.0 ? 1 : 0;
        }
        p_.f[j] = fj;
        p_.t[j] = tj;
        contact_count_[j] = static_cast<std::uint16_t>(std::min<std::uint32_t>(count, 65535));
    }

    add_rolling_torques(laws);

    // Wall reactions (serial: a handful of walls, fixed summation order).
    std::fill(wall_force_.begin(), wall_force_.end(), Vec3{});
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) wall_force_[list_.wall(k)] -= wall_entry_force_[k];
    }

    stats_ = {contacts, sliding, max_ratio};
    max_overlap_seen_ = std::max(max_overlap_seen_, max_ratio);
}

// Pass 3: rolling torques. Each contact's torque is computed from the relative angular velocity
// predicted at the end of the step with this step's friction torques (ω* = ω + Δt T/J), so the
// no-reversal cap can hold a static torque exactly; each side of a pair evaluates the same
// expression, so no reaction slot is needed and the result is independent of the thread count.
template <class Normal>
void DemSolver::add_rolling_torques(const ContactLawSet<Normal>& laws) {
    if (laws.particle_particle.rolling.mu_r == 0.0 && laws.particle_wall.rolling.mu_r == 0.0 &&
        laws.particle_barrier.rolling.mu_r == 0.0) {
        return;
    }
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
    const double dt = dt_;
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < nm; ++i) w_star_[i] = p_.w[i] + dt * p_.inv_j[i] * p_.t[i];

    auto pair_roll = [&](std::uint32_t k, std::size_t i, std::size_t j) {
        const auto& law = static_cast<std::ptrdiff_t>(j) < nm ? laws.particle_particle : laws.particle_barrier;
        const double share = std::max(contact_count_[i], contact_count_[j]);
        const double a_r = p_.r[i] * p_.r[j] / (p_.r[i] + p_.r[j]);
        return law.rolling.torque(w_star_[i] - w_star_[j], pair_fn_[k], a_r, p_.inv_j[i] + p_.inv_j[j], dt, share);
    };
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        Vec3 ti = p_.t[i];
        for (auto k = list_.begin(ui); k < list_.end(ui); ++k) {
            if (pair_fn_[k] > 0.0) ti += pair_roll(k, ui, list_.partner(k));
        }
        for (auto t = list_.t_begin(ui); t < list_.t_end(ui); ++t) {
            const auto k = list_.t_pair(t);
            if (pair_fn_[k] > 0.0) ti -= pair_roll(k, list_owner_[k], ui);
        }
        for (auto k = list_.wall_begin(ui); k < list_.wall_end(ui); ++k) {
            if (wall_fn_[k] <= 0.0) continue;
            const auto& law = walls_[list_.wall(k)].barrier ? laws.particle_barrier : laws.particle_wall;
            ti += law.rolling.torque(w_star_[i], wall_fn_[k], p_.r[i], p_.inv_j[i], dt, contact_count_[i]);
        }
        p_.t[i] = ti;
    }
}

void DemSolver::step() {
    const double h = 0.5 * dt_;
    const Vec3 g = gravity_;
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        p_.v[i] += h * (p_.f[i] * p_.inv_m[i] + g);
        p_.w[i] += h * p_.inv_j[i] * p_.t[i];
        p_.x[i] += dt_ * p_.v[i];
    }
    compute_forces();
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        p_.v[i] += h * (p_.f[i] * p_.inv_m[i] + g);
        p_.w[i] += h * p_.inv_j[i] * p_.t[i];
    }
    ++steps_;
    time_ = static_cast<double>(steps_) * dt_;  // no drift from summing dt
    if (stats_.max_overlap_ratio > 0.5 || !std::isfinite(stats_.max_overlap_ratio)) {
        throw RunError(fmt::format("t = {:.6g} s: overlap reached {:.0f} % of a diameter — the time step is too large "
                                   "for the contact stiffness, or grains were generated overlapping",
                                   time_, 100.0 * stats_.max_overlap_ratio));
    }
}

}  // namespace sabo::dem
