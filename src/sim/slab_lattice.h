// SPDX-License-Identifier: MIT
// A lattice divided into slabs along x among the ranks (docs/scaling.md, "Slabs, as built"): this rank's
// lattice holds its planes and `ghosts` ghost planes toward each neighbour, a wall beyond the outer ghost,
// and is stepped whole by the unchanged kernel; the ghosts are refreshed from the neighbours every
// `refresh_interval` steps (a deep halo: what goes wrong next to the wall beyond the outer ghost spreads a
// few planes per step and is overwritten before it reaches the own planes). Bulk fluid: the 19 populations
// and τ after every odd step of the AA pattern, 2 ghost planes. Free surface: the whole state between steps
// (populations, τ, λ, mass, cell types and the interface cells' surface state), and the excess mass that
// conversions spread over the whole surface goes to every slab's (lbm::OrphanMass). With enough ghost
// planes the own planes then step bit for bit like the undivided lattice (tests/mpi/slab_*_ranks).
#pragma once
#include <algorithm>
#include <chrono>
#include <cstring>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/mpi_world.h"
#include "lbm/fluid_lattice.h"
#include "sim/slab_exchange.h"
#include "sim/slab_partition.h"

namespace sabo::sim {

struct SlabHalo {
    int ghosts = 2;            // ghost planes toward each neighbour
    int refresh_interval = 2;  // steps between refreshes (bulk fluid: 2, after every odd step)
    bool free_surface = false;
    // What a step can carry from the wall beyond the outer ghost inward (docs/scaling.md, "Free surface in
    // slabs"): bulk fluid 2 planes in two steps; a free-surface step up to 6 planes (the streamed populations
    // 2, then emptied → demoted → the shares of their neighbours' excess 3, then the normals 1), refreshed
    // every step.
    static SlabHalo bulk() { return {}; }
    static SlabHalo with_free_surface() { return {7, 1, true}; }
};

template <class Real>
class SlabLattice {
  public:
    // This rank's equal share of `whole` (closed in x: walls at both ends).
    SlabLattice(const MpiWorld& world, const lbm::GridShape& whole, const lbm::Rheology& rheology,
                const SlabHalo& halo = {})
        : SlabLattice(world, whole, rheology, halo, SlabPartition(whole.nx, world.size(), halo.ghosts)) {}
    SlabLattice(const SlabLattice&) = delete;
    SlabLattice& operator=(const SlabLattice&) = delete;

    // The rank's lattice: local planes [0, local_planes()), set up by the caller (global_x() of each), then
    // prepare() before the first step.
    [[nodiscard]] lbm::FluidLattice<Real>& lattice() { return lattice_; }
    [[nodiscard]] const lbm::FluidLattice<Real>& lattice() const { return lattice_; }
    [[nodiscard]] int local_planes() const { return lattice_.shape().nx; }
    [[nodiscard]] int global_x(int local_x) const { return local_x + first_global_; }
    // The rank's own planes, local x in [own_begin(), own_end()).
    [[nodiscard]] int own_begin() const { return exchange_.first_own(); }
    [[nodiscard]] int own_end() const { return exchange_.first_own() + planes_; }

    void prepare() {
        lattice_.prepare();
        if (halo_.free_surface) refresh();  // the outer ghosts' surface state saw the wall beyond them
    }
    void step() {
        lattice_.step();
        if (lattice_.steps() % static_cast<std::uint64_t>(halo_.refresh_interval) == 0) refresh();
    }
    // Wall-clock seconds this rank spent refreshing its ghosts (waiting for a neighbour included).
    [[nodiscard]] double exchange_seconds() const { return exchanging_; }

  private:
    SlabLattice(const MpiWorld& world, const lbm::GridShape& whole, const lbm::Rheology& rheology,
                const SlabHalo& halo, const SlabPartition& slabs)
        : world_(world),
          halo_(halo),
          planes_(slabs.end(world.rank()) - slabs.begin(world.rank())),
          lattice_(local_shape(world, whole, halo, planes_), rheology),
          exchange_(
              world,
              {planes_, halo.ghosts, whole.ny, whole.nz, row(), row() * static_cast<std::size_t>(whole.ny)},
              lbm::Q + 2),
          first_global_(slabs.begin(world.rank()) - exchange_.first_own()) {
        // the populations and τ; with a free surface λ too (one message per face)
        for (int i = 0; i < lbm::Q; ++i) state_.push_back(lattice_.population_slots(i));
        state_.push_back(lattice_.relaxation_times());
        if (!halo.free_surface) return;
        state_.push_back(lattice_.fill_fractions());
        lattice_.set_slab({own_begin(), own_end(), first_global_,
                           [this](std::vector<lbm::OrphanMass>& orphans, std::uint64_t& surface_cells) {
                               spread(orphans, surface_cells);
                           }});
    }
    static lbm::GridShape local_shape(const MpiWorld& world, const lbm::GridShape& whole,
                                      const SlabHalo& halo, int planes) {
        if (whole.periodic[0])
            throw InputError("a lattice divided into slabs along x must be closed in x (walls at both ends)");
        if (halo.ghosts < 1 || halo.refresh_interval < 1 ||
            (!halo.free_surface && halo.refresh_interval != 2))
            throw InputError(
                "slab lattice: at least 1 ghost plane and a refresh every step or (bulk fluid) 2");
        const int toward_neighbours = (world.rank() > 0 ? 1 : 0) + (world.rank() + 1 < world.size() ? 1 : 0);
        return {planes + halo.ghosts * toward_neighbours,
                whole.ny,
                whole.nz,
                {false, whole.periodic[1], whole.periodic[2]}};
    }
    [[nodiscard]] std::size_t row() const { return lbm::FluidLattice<Real>::row_stride(lattice_.shape().nx); }

    void refresh() {
        const auto start = std::chrono::steady_clock::now();
        exchange_.fill_ghosts(std::span<const std::span<Real>>(state_));
        if (halo_.free_surface) {
            exchange_.fill_ghosts(lattice_.masses());
            exchange_.fill_ghosts(lattice_.cell_types());
            const int g = halo_.ghosts, own = own_begin(), end = own_end();
            // the interface cells' state: the first own planes to the left, the right neighbour's into the
            // right ghosts; then the mirror
            shift_surface(own, exchange_.left(), end, exchange_.right());
            shift_surface(end - g, exchange_.right(), 0, exchange_.left());
        }
        exchanging_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    // Sends the surface records of the interface cells of the ghost-deep planes from local x `from_x` on to
    // rank `to` while those from `into_x` on receive rank `from`'s: as many as the ghosts' (already
    // refreshed) cell types name interface cells.
    void shift_surface(int from_x, int to, int into_x, int from) {
        send_.clear();
        if (to >= 0) lattice_.pack_surface(from_x, halo_.ghosts, send_);
        std::size_t cells = 0;
        if (from >= 0) {
            const std::span<lbm::CellType> types = lattice_.cell_types();
            for (int z = 0; z < lattice_.shape().nz; ++z)
                for (int y = 0; y < lattice_.shape().ny; ++y) {
                    const auto row_begin =
                        types.begin() + static_cast<std::ptrdiff_t>(lattice_.index(into_x, y, z));
                    cells += static_cast<std::size_t>(
                        std::count(row_begin, row_begin + halo_.ghosts, lbm::CellType::interface));
                }
        }
        receive_.resize(cells * lbm::FluidLattice<Real>::surface_record);
        world_.send_receive(std::as_bytes(std::span(send_)), to, std::as_writable_bytes(std::span(receive_)),
                            from);
        if (from >= 0) lattice_.replace_surface(into_x, halo_.ghosts, receive_);
    }
    // Every rank's orphan mass in the undivided lattice's order, and the whole surface's interface cells.
    void spread(std::vector<lbm::OrphanMass>& orphans, std::uint64_t& surface_cells) {
        if (world_.sum(static_cast<std::int64_t>(orphans.size())) == 0) return;  // nothing to spread
        surface_cells = static_cast<std::uint64_t>(world_.sum(static_cast<std::int64_t>(surface_cells)));
        world_.all_gather(std::as_bytes(std::span(orphans)), gathered_);
        orphans.resize(gathered_.size() / sizeof(lbm::OrphanMass));
        std::memcpy(orphans.data(), gathered_.data(), gathered_.size());
        std::sort(orphans.begin(), orphans.end(),
                  [](const lbm::OrphanMass& a, const lbm::OrphanMass& b) { return a.order < b.order; });
    }

    const MpiWorld& world_;
    SlabHalo halo_;
    int planes_;
    lbm::FluidLattice<Real> lattice_;
    SlabExchange exchange_;
    int first_global_;
    std::vector<std::span<Real>> state_;
    std::vector<double> send_, receive_;  // surface records
    std::vector<std::byte> gathered_;     // every rank's orphan mass
    double exchanging_ = 0.0;
};

}  // namespace sabo::sim
