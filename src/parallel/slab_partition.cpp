// SPDX-License-Identifier: MIT
#include "parallel/slab_partition.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace sabo::parallel {

namespace {

void check(int planes, int ranks, int min_planes) {
    if (ranks < 1 || min_planes < 1 || static_cast<long long>(ranks) * min_planes > planes)
        throw InputError(
            fmt::format("{} ranks cannot each have a slab of at least {} planes in a channel of {} planes: "
                        "use at most {} "
                        "ranks",
                        ranks, min_planes, planes, std::max(1, planes / std::max(1, min_planes))));
}

}  // namespace

SlabPartition::SlabPartition(int planes, int ranks, int min_planes) {
    check(planes, ranks, min_planes);
    cuts_.resize(static_cast<std::size_t>(ranks) + 1);
    for (int r = 0; r <= ranks; ++r) cuts_[r] = static_cast<int>(static_cast<long long>(planes) * r / ranks);
}

LocalSlab SlabPartition::local(int rank, int ghosts) const {
    LocalSlab s;
    s.rank = rank;
    s.ranks = ranks();
    const int left = rank > 0 ? ghosts : 0, right = rank + 1 < ranks() ? ghosts : 0;
    s.own_begin = left;
    s.own_end = left + end(rank) - begin(rank);
    s.planes = s.own_end + right;
    s.first_global_x = begin(rank) - left;
    return s;
}

SlabPartition SlabPartition::balanced(std::span<const double> plane_cost, int ranks, int min_planes) {
    const int planes = static_cast<int>(plane_cost.size());
    check(planes, ranks, min_planes);
    const double total = std::accumulate(plane_cost.begin(), plane_cost.end(), 0.0);
    if (!(total > 0.0)) return {planes, ranks, min_planes};
    std::vector<int> cuts(static_cast<std::size_t>(ranks) + 1, planes);
    cuts[0] = 0;
    double running = 0.0;
    int plane = 0;
    for (int r = 1; r < ranks; ++r) {
        const double target = total * r / ranks;
        // the plane whose end brings the running cost closest to the target
        while (plane < planes && running + plane_cost[plane] < target) running += plane_cost[plane++];
        const bool take = plane < planes && (running + plane_cost[plane] - target) < (target - running);
        if (take) running += plane_cost[plane++];
        cuts[r] = plane;
    }
    SlabPartition p(std::move(cuts));
    p.keep_thickness(min_planes);
    return p;
}

void SlabPartition::keep_thickness(int min_planes) {
    const int n = ranks();
    for (int r = 1; r < n; ++r) cuts_[r] = std::max(cuts_[r], cuts_[r - 1] + min_planes);
    for (int r = n - 1; r >= 1; --r) cuts_[r] = std::min(cuts_[r], cuts_[r + 1] - min_planes);
}

int SlabPartition::owner(int plane) const {
    const auto it = std::upper_bound(cuts_.begin() + 1, cuts_.end(), plane);
    return static_cast<int>(it - cuts_.begin()) - 1;
}

std::vector<double> SlabPartition::slab_costs(std::span<const double> plane_cost) const {
    std::vector<double> cost(static_cast<std::size_t>(ranks()), 0.0);
    for (int r = 0; r < ranks(); ++r)
        for (int x = begin(r); x < end(r); ++x) cost[r] += plane_cost[x];
    return cost;
}

double SlabPartition::imbalance(std::span<const double> plane_cost) const {
    const auto cost = slab_costs(plane_cost);
    const double mean = std::accumulate(cost.begin(), cost.end(), 0.0) / ranks();
    return mean > 0.0 ? *std::max_element(cost.begin(), cost.end()) / mean : 1.0;
}

}  // namespace sabo::parallel
