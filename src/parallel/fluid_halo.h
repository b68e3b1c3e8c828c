// SPDX-License-Identifier: MIT
// The ghost planes of a lattice divided into slabs along x among the ranks (docs/scaling.md, "How a step
// crosses a slab face"): each rank's lattice holds its own planes and `ghosts` ghost planes toward each
// neighbour, a wall beyond the outer ghost, and is stepped whole by the unchanged kernel; the ghosts are
// refreshed from the neighbours every `refresh_interval` steps (a deep halo: what goes wrong next to the
// wall beyond the outer ghost spreads a few planes per step and is overwritten before it reaches the own
// planes). Bulk fluid: the 19 populations and τ after every odd step of the AA pattern, 2 ghost planes.
// Free surface: the state between steps (populations, τ, λ, mass, cell types and the interface cells'
// surface state; the first four only in the rows a step reads, "Only the rows a step reads"), and the
// excess mass that conversions spread over the whole surface goes to every slab's (lbm::OrphanMass). With
// enough ghost planes the own planes then step bit for bit like the undivided lattice
// (tests/mpi/slab_*_ranks).
#pragma once
#include <algorithm>
#include <chrono>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/mpi_world.h"
#include "core/stopwatch.h"
#include "lbm/fluid_lattice.h"
#include "parallel/slab_exchange.h"
#include "parallel/slab_partition.h"

namespace sabo::parallel {

struct HaloSettings {
    int ghosts = 2;            // ghost planes toward each neighbour
    int refresh_interval = 2;  // steps between refreshes (bulk fluid: 2, after every odd step)
    bool free_surface = false;
    // What a step can carry from the wall beyond the outer ghost inward (docs/scaling.md, "Free surface, as
    // built"): bulk fluid 2 planes in two steps; a free-surface step up to 6 planes (the streamed populations
    // 2, then emptied → demoted → the shares of their neighbours' excess 3, then the normals 1), refreshed
    // every step. A closed pocket's deficit taken within `pocket_reach` steps of it
    // (lbm::FluidLattice::set_pocket_reach) adds 2 × pocket_reach: a cell takes the deficit of pockets that
    // many planes away, whose shares count the surface cells that many planes further.
    static HaloSettings bulk() { return {}; }
    static HaloSettings with_free_surface(int pocket_reach = 0) { return {7 + 2 * pocket_reach, 1, true}; }
};

// This rank's equal share of `planes` planes, stored with the halo's ghost planes.
[[nodiscard]] inline LocalSlab equal_slab(const MpiWorld& world, int planes, const HaloSettings& halo) {
    return SlabPartition(planes, world.size(), halo.ghosts).local(world.rank(), halo.ghosts);
}

// The rank's lattice of the `whole` one (closed in x: walls at both ends) for its slab.
[[nodiscard]] inline lbm::GridShape slab_shape(const lbm::GridShape& whole, const LocalSlab& slab) {
    if (whole.periodic[0] && slab.divided())
        throw InputError("a lattice divided into slabs along x must be closed in x (walls at both ends)");
    return {slab.planes, whole.ny, whole.nz, whole.periodic};
}

// Replaces each slab's `forces` on the obstacles (its own planes' links) by their sums over the ranks
// (`scratch`: x y z per element); returns the seconds it took, waiting for the others included. Not wanted
// of the domain's walls alone (element 0: no observer reads them).
inline double sum_forces_over_ranks(const MpiWorld& world, std::span<Vec3> forces,
                                    std::vector<double>& scratch) {
    if (forces.size() < 2) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    world.sum_vectors(forces, scratch);
    return seconds_since(start);
}

// What the simulation calls around the lattice's steps, whatever the lattice's precision.
class FluidHalo {
  public:
    virtual ~FluidHalo() = default;
    // After the lattice's prepare(): the outer ghosts' surface state saw the wall beyond them.
    virtual void prepare() = 0;
    virtual void after_step() = 0;
    // Every ghost cell's state as the neighbour holds it (after_step() leaves out the rows no step reads:
    // before the faces move, the planes a rank gains from its ghosts must be whole).
    virtual void refresh_whole() = 0;
    // Wall-clock seconds this rank spent refreshing its ghosts (waiting for a neighbour included).
    [[nodiscard]] virtual double exchange_seconds() const = 0;
    // Carries those of a halo this one replaces (the slab faces moved).
    virtual void add_exchange_seconds(double seconds) = 0;
};

template <class Real>
class LatticeHalo final : public FluidHalo {
  public:
    // `lattice`, of slab_shape(), holds `slab` of the whole; it must outlive the halo.
    LatticeHalo(const MpiWorld& world, lbm::FluidLattice<Real>& lattice, const LocalSlab& slab,
                const HaloSettings& halo)
        : world_(world),
          slab_(slab),
          halo_(halo),
          lattice_(lattice),
          exchange_(world, layout(lattice, slab, halo), cell_bytes(halo)) {
        if (halo.ghosts < 1 || halo.refresh_interval < 1 ||
            (!halo.free_surface && halo.refresh_interval != 2))
            throw InputError(
                "slab lattice: at least 1 ghost plane and a refresh every step or (bulk fluid) 2");
        if (exchange_.first_own() != slab.own_begin || exchange_.local_planes() != lattice.shape().nx)
            throw std::logic_error("LatticeHalo: the lattice does not hold the slab with these ghosts");
        // the populations and τ; with a free surface λ too (one message per face)
        for (int i = 0; i < lbm::Q; ++i) state_.push_back(lattice_.population_slots(i));
        state_.push_back(lattice_.relaxation_times());
        marks_.assign(
            static_cast<std::size_t>(lattice.shape().ny) * static_cast<std::size_t>(lattice.shape().nz), 1);
        typename lbm::FluidLattice<Real>::SpreadOrphans spread_orphans;
        if (halo.free_surface) {
            state_.push_back(lattice_.fill_fractions());
            spread_orphans = [this](std::vector<lbm::OrphanMass>& orphans, std::uint64_t& surface_cells) {
                spread(orphans, surface_cells);
            };
        }
        lattice_.set_slab({slab.own_begin, slab.own_end, slab.first_global_x, std::move(spread_orphans)});
    }
    LatticeHalo(const LatticeHalo&) = delete;
    LatticeHalo& operator=(const LatticeHalo&) = delete;

    void prepare() override {
        if (halo_.free_surface) refresh(true);
    }
    void after_step() override {
        if (lattice_.steps() % static_cast<std::uint64_t>(halo_.refresh_interval) == 0) refresh(false);
        // each rank's lattice counted its own planes' forces on the obstacles: the whole's are their sum
        exchanging_ += sum_forces_over_ranks(world_, lattice_.element_forces_to_sum(), force_sums_);
    }
    void refresh_whole() override { refresh(true); }
    [[nodiscard]] double exchange_seconds() const override { return exchanging_; }
    void add_exchange_seconds(double seconds) override { exchanging_ += seconds; }

  private:
    static SlabLayout layout(const lbm::FluidLattice<Real>& lattice, const LocalSlab& slab,
                             const HaloSettings& halo) {
        const lbm::GridShape& sh = lattice.shape();
        const std::size_t row = lbm::FluidLattice<Real>::row_stride(sh.nx);
        return {slab.own_end - slab.own_begin,        halo.ghosts, sh.ny, sh.nz, row,
                row * static_cast<std::size_t>(sh.ny)};
    }

    // One message per face: the ghost planes' populations and τ (and with a free surface λ, mass, cell type
    // and the interface cells' surface records: as many as the types name interface cells). With a free
    // surface and not `whole`, all but the types and records travel only in the rows a step reads
    // (mark_wet_rows).
    void refresh(bool whole) {
        const ScopeSeconds timed(exchanging_);
        const std::span<const std::span<Real>> state(state_);
        if (!halo_.free_surface) {
            exchange_.pack_edges(state);
        } else {
            for (const Side side : {Side::left, Side::right}) {
                if (exchange_.neighbour(side) < 0) continue;
                if (whole)
                    marks_.assign(marks_.size(), 1);
                else
                    mark_wet_rows(side == Side::left ? slab_.own_begin : slab_.own_end - halo_.ghosts);
                exchange_.pack_rows(side, marks_);
            }
            exchange_.pack_marked_edges(state);
            const std::span<double> masses = lattice_.masses();
            exchange_.pack_marked_edges(std::span<const std::span<double>>(&masses, 1));
            exchange_.pack_edges(lattice_.cell_types());
            const int g = halo_.ghosts, own = slab_.own_begin, end = slab_.own_end;
            for (const Side side : {Side::left, Side::right}) {
                records_.clear();
                if (exchange_.neighbour(side) >= 0)
                    lattice_.pack_surface(side == Side::left ? own : end - g, g, records_);
                exchange_.pack_records(side, records_);
            }
        }
        exchange_.send();
        if (!halo_.free_surface) {
            exchange_.unpack_ghosts(state);
        } else {
            exchange_.unpack_rows();
            exchange_.unpack_marked_ghosts(state);
            const std::span<double> masses = lattice_.masses();
            exchange_.unpack_marked_ghosts(std::span<const std::span<double>>(&masses, 1));
            exchange_.unpack_ghosts(lattice_.cell_types());
            if (exchange_.left() >= 0)
                lattice_.replace_surface(0, halo_.ghosts, exchange_.unpack_records(Side::left));
            if (exchange_.right() >= 0)
                lattice_.replace_surface(slab_.own_end, halo_.ghosts, exchange_.unpack_records(Side::right));
        }
    }
    // The rows (y + ny·z) of the `ghosts` planes from local x `x0` on whose state the neighbour's next step
    // may read, into marks_: those with a fluid or interface cell within one cell (x from x0 − 1 to
    // x0 + ghosts, y and z ±1). A step reads the populations, τ, λ and mass only of its fluid and interface
    // cells and of their neighbours (an obstacle's link reads the fluid cell's own slot); a cell that turns
    // wet in a step writes its state before any of it is read (docs/scaling.md, "Only the rows a step
    // reads").
    // The plane x0 − 1 of the left face and x0 + ghosts of the right face are this rank's inner ghost planes,
    // exact after a step (a step's error reaches 6 of the 7 ghost planes).
    void mark_wet_rows(int x0) {
        const lbm::GridShape& sh = lattice_.shape();
        const std::span<const lbm::CellType> types = std::as_const(lattice_).cell_types();
        const std::size_t row = lbm::FluidLattice<Real>::row_stride(sh.nx);
        const int x_begin = std::max(x0 - 1, 0), x_end = std::min(x0 + halo_.ghosts + 1, sh.nx);
        wet_.assign(static_cast<std::size_t>(sh.ny) * static_cast<std::size_t>(sh.nz), 0);
        for (int z = 0, r = 0; z < sh.nz; ++z)
            for (int y = 0; y < sh.ny; ++y, ++r) {
                const std::size_t k = row * (static_cast<std::size_t>(y) +
                                             static_cast<std::size_t>(sh.ny) * static_cast<std::size_t>(z));
                for (int x = x_begin; x < x_end && wet_[r] == 0; ++x) {
                    const lbm::CellType t = types[k + static_cast<std::size_t>(x)];
                    wet_[r] = t == lbm::CellType::fluid || t == lbm::CellType::interface ? 1 : 0;
                }
            }
        marks_.assign(wet_.size(), 0);
        for (int z = 0, r = 0; z < sh.nz; ++z)
            for (int y = 0; y < sh.ny; ++y, ++r)
                for (int dz = std::max(z - 1, 0); dz <= std::min(z + 1, sh.nz - 1) && marks_[r] == 0; ++dz)
                    for (int dy = std::max(y - 1, 0); dy <= std::min(y + 1, sh.ny - 1); ++dy)
                        marks_[r] |= wet_[static_cast<std::size_t>(dy + sh.ny * dz)];
    }
    // The most bytes a refresh sends per ghost cell: the populations and τ, and with a free surface λ, the
    // mass, the type, (if every ghost cell were an interface cell) a surface record and a row's mark.
    static std::size_t cell_bytes(const HaloSettings& halo) {
        const std::size_t state = (lbm::Q + (halo.free_surface ? 2 : 1)) * sizeof(Real);
        return state + (halo.free_surface ? sizeof(double) + sizeof(lbm::CellType) +
                                                lbm::FluidLattice<Real>::surface_record * sizeof(double) + 1
                                          : 0);
    }
    // Every rank's orphan mass in the undivided lattice's order, and the whole surface's interface cells.
    void spread(std::vector<lbm::OrphanMass>& orphans, std::uint64_t& surface_cells) {
        const ScopeSeconds timed(exchanging_);  // (waiting for the slowest rank included)
        if (world_.sum(static_cast<std::int64_t>(orphans.size())) == 0) return;  // nothing to spread
        surface_cells = static_cast<std::uint64_t>(world_.sum(static_cast<std::int64_t>(surface_cells)));
        world_.all_gather(std::as_bytes(std::span(orphans)), gathered_);
        orphans.resize(gathered_.size() / sizeof(lbm::OrphanMass));
        std::memcpy(orphans.data(), gathered_.data(), gathered_.size());
        std::sort(orphans.begin(), orphans.end(),
                  [](const lbm::OrphanMass& a, const lbm::OrphanMass& b) { return a.order < b.order; });
    }

    const MpiWorld& world_;
    LocalSlab slab_;
    HaloSettings halo_;
    lbm::FluidLattice<Real>& lattice_;
    SlabExchange exchange_;
    std::vector<std::span<Real>> state_;     // the Q populations' slots, τ, with a free surface λ
    std::vector<std::uint8_t> wet_, marks_;  // mark_wet_rows()
    std::vector<double> records_;            // the interface cells' surface records of one face
    std::vector<std::byte> gathered_;        // every rank's orphan mass
    std::vector<double> force_sums_;         // the obstacles' forces, x y z per element
    double exchanging_ = 0.0;
};

}  // namespace sabo::parallel
