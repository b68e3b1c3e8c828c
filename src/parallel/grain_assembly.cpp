// SPDX-License-Identifier: MIT
#include "parallel/grain_assembly.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <utility>

#include "core/error.h"

namespace sabo::parallel {

dem::ContactForces GrainAssembly::contact_forces(const MpiWorld& world, const dem::DemSolver& grains,
                                                 std::size_t total) {
    const std::vector<Vec3>& f = grains.forces();
    const std::vector<Vec3>& on_walls = grains.wall_forces();
    const std::size_t local = grains.mobile_count(), fixed = f.size() - local, walls = on_walls.size();
    sums_.clear();
    for (std::size_t k = 0; k < fixed; ++k)
        sums_.insert(sums_.end(), {f[local + k].x, f[local + k].y, f[local + k].z});
    for (const Vec3& w : on_walls) sums_.insert(sums_.end(), {w.x, w.y, w.z});
    world.sum_reals(sums_);
    forces_.resize(total + fixed);  // the mobile grains' entries stay zero
    wall_forces_.resize(walls);
    const auto at = [&](std::size_t k) { return Vec3{sums_[3 * k], sums_[3 * k + 1], sums_[3 * k + 2]}; };
    for (std::size_t k = 0; k < fixed; ++k) forces_[total + k] = at(k);
    for (std::size_t w = 0; w < walls; ++w) wall_forces_[w] = at(fixed + w);
    return {forces_, wall_forces_};
}

dem::GrainView GrainAssembly::view(const MpiWorld& world, const dem::DemSolver& grains, std::size_t total) {
    (void)contact_forces(world, grains, total);
    struct Moving {
        Vec3 x, v, w, f, t;
        double r, m, inv_m, inv_j;
        std::uint64_t id;
    };
    const dem::Particles& p = grains.particles();
    const std::size_t own = grains.own_count(), local = p.n_mobile, fixed = p.n_fixed();
    mine_.resize(own * sizeof(Moving));
    for (std::size_t i = 0; i < own; ++i) {
        const Moving g{p.x[i], p.v[i], p.w[i],     p.f[i],     p.t[i],
                       p.r[i], p.m[i], p.inv_m[i], p.inv_j[i], grains.ids()[i]};
        std::memcpy(mine_.data() + i * sizeof(Moving), &g, sizeof(Moving));
    }
    world.all_gather(mine_, all_);
    if (all_.size() != total * sizeof(Moving))
        throw RunError(fmt::format("step {}: the ranks hold {} grains of the run's {}", grains.steps(),
                                   all_.size() / sizeof(Moving), total));
    const std::size_t n = total + fixed;
    for (auto* v : {&whole_.x, &whole_.v, &whole_.w, &whole_.f, &whole_.t}) v->resize(n);
    for (auto* v : {&whole_.r, &whole_.m, &whole_.inv_m, &whole_.inv_j}) v->resize(n);
    whole_.n_mobile = total;
    // in the order of their ids (the release's order; a removed grain's id is skipped)
    id_order_.resize(total);
    for (std::size_t k = 0; k < total; ++k) {
        std::uint64_t id = 0;
        std::memcpy(&id, all_.data() + k * sizeof(Moving) + offsetof(Moving, id), sizeof id);
        id_order_[k] = {id, k};
    }
    std::sort(id_order_.begin(), id_order_.end());
    ids_.resize(total);
    for (std::size_t i = 0; i < total; ++i) {
        Moving g;
        std::memcpy(&g, all_.data() + id_order_[i].second * sizeof(Moving), sizeof(Moving));
        whole_.x[i] = g.x, whole_.v[i] = g.v, whole_.w[i] = g.w, whole_.f[i] = g.f, whole_.t[i] = g.t;
        whole_.r[i] = g.r, whole_.m[i] = g.m, whole_.inv_m[i] = g.inv_m, whole_.inv_j[i] = g.inv_j;
        ids_[i] = static_cast<std::uint32_t>(g.id);
    }
    for (std::size_t k = 0; k < fixed; ++k) {  // the same on every rank, with the forces summed over them
        const std::size_t i = total + k, l = local + k;
        whole_.x[i] = p.x[l], whole_.v[i] = {}, whole_.w[i] = {}, whole_.f[i] = forces_[i], whole_.t[i] = {};
        whole_.r[i] = p.r[l], whole_.m[i] = 0.0, whole_.inv_m[i] = 0.0, whole_.inv_j[i] = 0.0;
    }
    dem::ContactStats stats = grains.stats();
    std::vector<double> sums{static_cast<double>(stats.contacts), static_cast<double>(stats.sliding),
                             grains.elastic_energy()};
    world.sum_reals(sums);
    std::vector<double> maxima{stats.max_overlap_ratio, grains.max_overlap_ratio_seen()};
    world.max_reals(maxima);
    stats = {static_cast<std::uint64_t>(sums[0]), static_cast<std::uint64_t>(sums[1]), maxima[0]};
    return {grains.time(), whole_,  ids_,      grains.walls(),      wall_forces_,
            stats,         sums[2], maxima[1], grains.list_builds()};
}

}  // namespace sabo::parallel
