// SPDX-License-Identifier: MIT
#include "parallel/slab_rebalance.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace sabo::parallel {

std::vector<int> rebalanced_cuts(const MpiWorld& world, const std::vector<int>& cuts,
                                 std::span<const double> own_costs, int thinnest, double min_gain) {
    std::vector<std::byte> gathered;
    world.all_gather(std::as_bytes(own_costs), gathered);
    std::vector<double> costs(gathered.size() / sizeof(double));
    std::memcpy(costs.data(), gathered.data(), gathered.size());
    const int ranks = static_cast<int>(cuts.size()) - 1, planes = cuts.back(), thin = thinnest;
    if (static_cast<int>(costs.size()) != planes || planes < thin * ranks) return cuts;
    const SlabPartition target = SlabPartition::balanced(costs, ranks, thin);
    // each face toward its place, but not past the old faces on either side (the planes a rank gains are then
    // all held by the neighbour it gains them from, own or ghost), left to right; then the slabs kept thick
    // enough from the right
    std::vector<int> moved(cuts);
    for (int r = 1; r < ranks; ++r)
        moved[r] = std::max(std::clamp(target.begin(r), cuts[r - 1], cuts[r + 1]), moved[r - 1] + thin);
    for (int r = ranks - 1; r >= 1; --r) moved[r] = std::min(moved[r], moved[r + 1] - thin);
    for (int r = 1; r < ranks; ++r)
        if (moved[r] - moved[r - 1] < thin || moved[r] < cuts[r - 1] || moved[r] > cuts[r + 1]) return cuts;
    const auto slowest = [&](const std::vector<int>& c) {
        const auto slabs = SlabPartition::from_cuts(c).slab_costs(costs);
        return *std::max_element(slabs.begin(), slabs.end());
    };
    return slowest(moved) < (1.0 - min_gain) * slowest(cuts) ? moved : cuts;
}

template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> slab_lattice(const MpiWorld& world,
                                                      const lbm::FluidLattice<Real>& like,
                                                      const std::vector<int>& cuts, int ghosts,
                                                      std::unique_ptr<lbm::FluidLattice<Real>> spare) {
    const LocalSlab slab = SlabPartition::from_cuts(cuts).local(world.rank(), ghosts);
    const auto& sh = like.shape();
    const lbm::GridShape shape{slab.planes, sh.ny, sh.nz, sh.periodic};
    auto fresh = spare ? std::make_unique<lbm::FluidLattice<Real>>(shape, like.rheology(), std::move(*spare))
                       : std::make_unique<lbm::FluidLattice<Real>>(shape, like.rheology());
    fresh->set_slab({slab.own_begin, slab.own_end, slab.first_global_x, {}});
    if (like.keeps_barrier_links()) fresh->keep_barrier_links();
    if (like.pocket_reach() > 0) fresh->set_pocket_reach(like.pocket_reach());
    return fresh;
}

template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> moved_lattice(const MpiWorld& world,
                                                       const lbm::FluidLattice<Real>& old,
                                                       const std::vector<int>& from,
                                                       const std::vector<int>& to, int ghosts,
                                                       std::unique_ptr<lbm::FluidLattice<Real>> spare) {
    const int rank = world.rank(), ranks = world.size();
    const LocalSlab was = SlabPartition::from_cuts(from).local(rank, ghosts);
    auto fresh = slab_lattice(world, old, to, ghosts, std::move(spare));
    const int was_first = was.first_global_x, was_end = was.first_global_x + was.planes;
    const int now_first = to[rank] - (rank > 0 ? ghosts : 0);
    const int now_end = to[rank + 1] + (rank + 1 < ranks ? ghosts : 0);
    const int left = rank > 0 ? rank - 1 : -1, right = rank + 1 < ranks ? rank + 1 : -1;
    // the planes this rank holds for both lattices
    std::vector<std::byte> block, incoming;
    const int keep_first = std::max(was_first, now_first), keep_end = std::min(was_end, now_end);
    fresh->copy_planes(old, keep_first - was_first, keep_first - now_first, keep_end - keep_first);
    // what the left neighbour's grown right end needs from here, while the right neighbour sends what this
    // rank's right end gained; then the mirror
    block.clear();
    if (left >= 0 && to[rank] > from[rank])
        old.export_planes(from[rank] + ghosts - was_first, to[rank] - from[rank], block);
    world.send_receive_block(block, left, incoming, right);
    if (now_end > was_end) fresh->import_planes(was_end - now_first, now_end - was_end, incoming);
    block.clear();
    if (right >= 0 && to[rank + 1] < from[rank + 1])
        old.export_planes(to[rank + 1] - ghosts - was_first, from[rank + 1] - to[rank + 1], block);
    world.send_receive_block(block, right, incoming, left);
    if (now_first < was_first) fresh->import_planes(0, was_first - now_first, incoming);
    fresh->adopt(old);
    fresh->relink();
    return fresh;
}

template std::unique_ptr<lbm::FluidLattice<float>> slab_lattice(const MpiWorld&,
                                                                const lbm::FluidLattice<float>&,
                                                                const std::vector<int>&, int,
                                                                std::unique_ptr<lbm::FluidLattice<float>>);
template std::unique_ptr<lbm::FluidLattice<double>> slab_lattice(const MpiWorld&,
                                                                 const lbm::FluidLattice<double>&,
                                                                 const std::vector<int>&, int,
                                                                 std::unique_ptr<lbm::FluidLattice<double>>);
template std::unique_ptr<lbm::FluidLattice<float>> moved_lattice(const MpiWorld&,
                                                                 const lbm::FluidLattice<float>&,
                                                                 const std::vector<int>&,
                                                                 const std::vector<int>&, int,
                                                                 std::unique_ptr<lbm::FluidLattice<float>>);
template std::unique_ptr<lbm::FluidLattice<double>> moved_lattice(const MpiWorld&,
                                                                  const lbm::FluidLattice<double>&,
                                                                  const std::vector<int>&,
                                                                  const std::vector<int>&, int,
                                                                  std::unique_ptr<lbm::FluidLattice<double>>);

}  // namespace sabo::parallel
