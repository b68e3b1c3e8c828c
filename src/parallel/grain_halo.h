// SPDX-License-Identifier: MIT
// The grains of a run divided among MPI ranks into slabs along x (docs/scaling.md, "Grains in slabs"). Each
// rank owns the grains whose centre lies in its slab and integrates them; it also holds ghost copies of its
// right neighbour's grains near their common face. A contact between grains of two slabs is evaluated once,
// by the left rank (its own grain's row holds the ghost as a partner), which sends the reactions back; walls
// and fixed spheres (every rank has them all) touch own grains only. Every step:
//   1. drift (rolling sweep, kick, drift) on every rank;
//   2. the ghosts' rolling corrections go back to their owners, then the owners' new states to the ghosts;
//   3. if any rank's grain moved past its half-skin (or the lists are stale), all re-partition: grains whose
//      centre left the slab move to the neighbour with the histories of their contacts (keyed by global
//      ids), every contact's history goes to the rank that evaluates it now, the ghost sets are rebuilt;
//   4. forces; the reactions on ghosts go back to their owners (added to force, torque and ω kick), then
//      the owners' states to the ghosts.
// Ghosts reach 2 r_max + skin_max beyond the face: every pair the lists can hold across a face. Slabs must
// be at least that wide (no contact spans three slabs).
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mpi_world.h"
#include "dem/dem_solver.h"

namespace sabo::parallel {

class GrainHalo {
  public:
    // `faces`: x of the ranks − 1 faces between slabs, m, ascending (rank r owns [faces[r−1], faces[r]), the
    // first and last slabs unbounded outward); none: placed by divide() where the grains' count is equal.
    // `grains` holds every grain of the run, on every rank, as an undivided run would start; call divide()
    // before the first step. `follow_grains`: the faces move toward equal grain counts at re-partitions
    // (otherwise they stay where they are put: a coupled run's follow its lattice's, move_faces()).
    // `largest_radius`: the largest radius a grain of the run may have, m (grains fed later, add(), may be
    // larger than those there at the start); the ghost reach counts it.
    GrainHalo(const MpiWorld& world, dem::DemSolver& grains, std::vector<double> faces,
              bool follow_grains = true, double largest_radius = 0.0);

    // Keeps this rank's grains, their ghosts and the contacts it evaluates (no communication: every rank
    // holds the same whole state). Throws InputError when a slab is thinner than the ghost reach. `reach`
    // > 0 replaces the ghost reach (less than 2 r_max + skin_max loses contacts: only for the test that
    // shows it).
    void divide(double reach = 0.0);
    // One time step of the divided run (see above).
    void step();

    // Puts the faces at `faces` between two steps (every rank at once, each face moved no farther than its
    // neighbours' old faces) and re-partitions the grains at once.
    void move_faces(std::vector<double> faces);
    // The solver's external forces (DemSolver::set_external_forces; ghosts: none), and the ghosts' states
    // refreshed (the forces' half-step kick changes the owners' velocities).
    void set_external_forces(std::span<const Vec3> force, std::span<const Vec3> torque);

    // Takes the own grains i with gone[i] != 0 (one flag per own grain) out of the run at the next step's
    // re-partition, with their contacts (grains that left through an outlet); every rank's call makes all
    // re-partition then.
    void remove(std::span<const std::uint8_t> gone);
    // Adds `batch` to the run between two steps (an inflow's grains, dem::DemSolver::add_mobile): collective,
    // every rank passes the same batch; the grains take the ids that follow the run's, in the batch's order
    // (as one process gives them), each joins the rank whose slab holds its centre, and all re-partition.
    void add(std::vector<dem::GrainRecord> batch);
    // Grains removed so far, over all ranks.
    [[nodiscard]] std::size_t removed() const { return removed_; }

    [[nodiscard]] int owner_of(double x) const;
    [[nodiscard]] const std::vector<double>& faces() const { return faces_; }
    // How often the faces moved to follow the grains (at re-partitions).
    [[nodiscard]] std::size_t face_moves() const { return face_moves_; }
    // Beyond a face, how far ghosts reach, m.
    [[nodiscard]] double ghost_reach() const { return reach_; }
    // Grains in the whole run now (those at the division and those added, less those removed).
    [[nodiscard]] std::size_t total_grains() const { return total_ - removed_; }
    // Re-partitions so far, and grains that changed rank in them (this rank's arrivals).
    [[nodiscard]] std::size_t repartitions() const { return repartitions_; }
    [[nodiscard]] std::size_t arrivals() const { return arrivals_; }
    // Seconds spent in the per-step exchanges (waiting for the neighbours included) and in re-partitions.
    [[nodiscard]] double exchange_seconds() const { return exchanging_; }
    [[nodiscard]] double repartition_seconds() const { return repartitioning_; }

    // Checkpoints (io/checkpoint.h), with the solver's: the faces, the ghost reach, which own grains are the
    // left neighbour's ghosts and the ghosts' states as last set, the counters. A halo made like the one
    // written (same ranks, the solver read back first) continues bit for bit. Throws InputError if what it
    // read does not fit the solver.
    template <class Archive>
    void transfer(Archive& a) {
        a(faces_, reach_, total_, removed_, leaving_, repartitions_, arrivals_, face_moves_, exchanging_,
          repartitioning_, lent_, ghost_state_);
        if constexpr (Archive::reading) restored();
    }

  private:
    void restored() const;
    [[nodiscard]] int left() const { return world_.rank() - 1; }
    [[nodiscard]] int right() const { return world_.rank() + 1 < world_.size() ? world_.rank() + 1 : -1; }
    // Grains are named by global ids below total_, the count at the division and of those added since (fixed
    // spheres and walls above; removed grains leave gaps).
    [[nodiscard]] bool is_grain(std::uint32_t key) const { return key < total_; }
    // After the drift: ghosts' rolling corrections to their owners.
    void return_spins();
    // After the forces: ghosts' reactions to their owners.
    void return_reactions();
    // Owners' states to the ghosts.
    void refresh_ghosts();
    // `joining`: grains added to this rank's own (add()).
    void repartition(std::vector<dem::GrainRecord> joining = {});
    // At a re-partition, when the most loaded slab holds more than (1 + min_imbalance) times the mean count
    // of grains: the faces move toward equal counts (SlabPartition::balanced over bins of half a reach).
    void follow_grains();
    // Faces where the running count of the grains `p` (every grain of the run) reaches (r+1)/N of them.
    [[nodiscard]] std::vector<double> equal_count_faces(const dem::Particles& p) const;
    // The first `n` grains of `p` counted in bins of half a ghost reach along x from lo to hi.
    [[nodiscard]] std::vector<double> count_in_bins(const dem::Particles& p, std::size_t n, double lo,
                                                    double hi) const;
    // Faces where the running count of `count` (bins from lo) reaches (r+1)/N (SlabPartition::balanced).
    [[nodiscard]] std::vector<double> equal_count_cuts(std::span<const double> count, double lo) const;
    static constexpr double min_imbalance = 0.05;
    // Own grains in the order of their cells (dem/spatial_order.h): the pair loops stay cache-friendly as
    // the flow mixes them (an undivided run sorts every few list builds for the same reason).
    void sort_spatially(std::vector<dem::GrainRecord>& grains);
    // `own` then `ghosts` into the solver with the histories of the contacts evaluated here; notes which own
    // grains are the left neighbour's ghosts (x before its face + reach, in own order).
    void install(std::vector<dem::GrainRecord> own, std::vector<dem::GrainRecord> ghosts,
                 std::vector<dem::ContactRecord> contacts);

    const MpiWorld& world_;
    dem::DemSolver& grains_;
    std::vector<double> faces_;
    bool follow_grains_ = true;
    double largest_radius_ = 0.0;
    double reach_ = 0.0;
    std::size_t total_ = 0, removed_ = 0;
    std::vector<std::uint8_t> leaving_;  // own grains to remove at the next re-partition (empty: none)
    std::size_t repartitions_ = 0, arrivals_ = 0, face_moves_ = 0;
    double exchanging_ = 0.0, repartitioning_ = 0.0;
    std::vector<std::uint32_t> lent_;           // own grains that the left neighbour holds as ghosts
    std::vector<dem::GhostState> ghost_state_;  // the ghosts' states as last set (their ω before the sweep)
    std::vector<std::byte> send_, receive_;     // message scratch
    // the per-step messages (reused: no allocation in the time loop)
    struct Reaction {
        Vec3 force, torque;
        std::uint64_t count;
    };
    std::vector<Vec3> spins_out_, spins_in_;
    std::vector<Reaction> reactions_out_, reactions_in_;
    std::vector<dem::GhostState> lent_state_;
    std::vector<Vec3> positions_;  // sort scratch
    std::vector<std::uint32_t> order_, order_start_, order_histogram_;
    std::vector<dem::GrainRecord> sorted_;
    std::vector<int> owner_by_id_;  // re-partition scratch: one entry per grain of the run
};

}  // namespace sabo::parallel
