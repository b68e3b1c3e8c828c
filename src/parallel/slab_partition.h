// SPDX-License-Identifier: MIT
// The channel cut into slabs along X, one per rank (docs/scaling.md): slab boundaries lie on lattice
// planes (or, for grains alone, on planes of the contact grid), each slab at least `min_planes` thick (the
// reach of its ghost layers), placed to equalise a cost measured per plane: a released mass fills a few
// metres of a long channel, and equal slabs would leave most ranks idle.
#pragma once
#include <span>
#include <vector>

namespace sabo::parallel {

// One rank's slab as the rank stores it: `ghosts` ghost planes mirroring the left neighbour's last planes
// (none at the domain's start), its own planes, then ghosts mirroring the right neighbour's first ones. The
// whole domain undivided is one slab with no ghosts.
struct LocalSlab {
    int rank = 0, ranks = 1;
    int planes = 1;                  // local planes, ghosts included
    int own_begin = 0, own_end = 1;  // local x of the own planes
    int first_global_x = 0;          // global x of local plane 0
    [[nodiscard]] int ghosts_left() const { return own_begin; }
    [[nodiscard]] int ghosts_right() const { return planes - own_end; }
    [[nodiscard]] bool divided() const { return ranks > 1; }
    [[nodiscard]] static LocalSlab whole(int planes) { return {0, 1, planes, 0, planes, 0}; }
};

class SlabPartition {
  public:
    // Equal slabs (to one plane) of `planes` planes among `ranks`.
    SlabPartition(int planes, int ranks, int min_planes);
    // Slabs whose costs are as equal as the planes allow: the cut after rank r's slab is the first plane
    // at which the running cost reaches (r + 1)/ranks of the total, moved as little as the thinnest slab
    // needs. The largest slab then costs at most the mean plus the dearest plane (thin slabs aside).
    static SlabPartition balanced(std::span<const double> plane_cost, int ranks, int min_planes);

    [[nodiscard]] int ranks() const { return static_cast<int>(cuts_.size()) - 1; }
    [[nodiscard]] int planes() const { return cuts_.back(); }
    // Rank r owns the planes [begin(r), end(r)).
    [[nodiscard]] int begin(int rank) const { return cuts_[rank]; }
    [[nodiscard]] int end(int rank) const { return cuts_[rank + 1]; }
    [[nodiscard]] int owner(int plane) const;
    // ranks + 1 planes: rank r owns [cuts()[r], cuts()[r + 1])
    [[nodiscard]] const std::vector<int>& cuts() const { return cuts_; }
    // Each slab's cost, and the largest over the mean (1: perfect balance; the parallel efficiency that the
    // balance allows is its inverse).
    [[nodiscard]] std::vector<double> slab_costs(std::span<const double> plane_cost) const;
    [[nodiscard]] double imbalance(std::span<const double> plane_cost) const;
    // The partition of these cuts (0 first, increasing, the last the plane count).
    [[nodiscard]] static SlabPartition from_cuts(std::vector<int> cuts) {
        return SlabPartition(std::move(cuts));
    }
    // How rank r stores its slab with `ghosts` ghost planes toward each neighbour.
    [[nodiscard]] LocalSlab local(int rank, int ghosts) const;

  private:
    explicit SlabPartition(std::vector<int> cuts) : cuts_(std::move(cuts)) {}
    // Moves the inner cuts as little as needed for every slab to be at least `min_planes` thick.
    void keep_thickness(int min_planes);

    std::vector<int> cuts_;  // ranks + 1 plane indices, 0 first, `planes` last
};

}  // namespace sabo::parallel
