// SPDX-License-Identifier: MIT
// The DEM time loop (docs/dem.md): velocity Verlet in its leapfrog form (docs/dem.md), contact forces from
// the Verlet list and the wall candidates, per-contact tangential history that survives list rebuilds, and
// per-element force accounting for walls and fixed spheres. No allocation happens in step() once the lists
// have reached their working size.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "core/vec3.h"
#include "dem/contact_law.h"
#include "dem/grain_records.h"
#include "dem/mesh_contacts.h"
#include "dem/neighbor_list.h"
#include "dem/particles.h"
#include "dem/walls.h"

namespace sabo::dem {

using AnyContactLaws = std::variant<ContactLawSet<LinearNormal>, ContactLawSet<HertzNormal>>;

struct ContactStats {
    std::uint64_t contacts = 0;      // active (overlapping) particle–particle + particle–wall contacts
    std::uint64_t sliding = 0;       // of which in the slip state
    double max_overlap_ratio = 0.0;  // max δ / d (smaller sphere's diameter) in the last step
};

class DemSolver {
  public:
    DemSolver(Particles particles, std::vector<Wall> walls, AnyContactLaws laws, const Vec3& gravity,
              double dt, double skin);

    // Advances one time step: drift(), then finish_step() with the lists rebuilt when a grain moved more
    // than its half-skin.
    void step();
    // The two halves of a step, for a caller that exchanges ghost grains between them
    // (parallel/grain_halo.h): the rolling sweep(s), kick of v and drift of x; returns how far the own grain
    // farthest past its half-skin is (> 0: the lists must be rebuilt before the forces).
    [[nodiscard]] double drift();
    // Forces at the new positions (the lists rebuilt first if `rebuild` or something made them stale),
    // ω kicked to the next half step, the clock advanced; the overlap and blow-up checks.
    void finish_step(bool rebuild);

    [[nodiscard]] double time() const { return time_; }
    [[nodiscard]] std::uint64_t steps() const { return steps_; }
    [[nodiscard]] double dt() const { return dt_; }
    [[nodiscard]] const Vec3& gravity() const { return gravity_; }
    // The particles with synchronous velocities v(t), ω(t) (computed on first access after a step).
    [[nodiscard]] const Particles& particles() const {
        synchronize();
        return p_;
    }
    [[nodiscard]] Particles& particles() {
        synchronize();
        return p_;
    }
    [[nodiscard]] const std::vector<Wall>& walls() const { return walls_; }
    // Contact force on each particle (fixed spheres included) in the last step, N; no synchronisation
    // of the velocities (cheap to call every step).
    [[nodiscard]] const std::vector<Vec3>& forces() const { return p_.f; }
    [[nodiscard]] std::size_t mobile_count() const { return p_.n_mobile; }
    // Contact force received by each wall in the last step, N.
    [[nodiscard]] const std::vector<Vec3>& wall_forces() const { return wall_force_; }
    // Adds the force the own grains' contacts of the last step put on each triangle of `mesh` (N; indexed
    // as its triangles) to `per_triangle`: a contact on an edge or a corner counts on the triangle that
    // reported it (docs/geometry.md, "Force maps on the mesh"). Grains in their order: the same sums on every
    // thread count.
    void add_triangle_forces(const geometry::TriangleMesh& mesh, std::span<Vec3> per_triangle) const;
    [[nodiscard]] const ContactStats& stats() const { return stats_; }
    [[nodiscard]] double max_overlap_ratio_seen() const { return max_overlap_seen_; }
    [[nodiscard]] KineticEnergy kinetic_energy() const;
    // Energy stored in the contacts, J: normal springs (law potential at the current overlap) and
    // tangential springs (k_t |ξ|²/2 sticking, (μ_d F_n)²/(2 k_t) slipping; k_t at the current overlap).
    [[nodiscard]] double elastic_energy() const;
    [[nodiscard]] std::size_t list_builds() const { return list_.builds(); }
    // Wall-clock seconds this process spent building them (for the run's timing, not part of the state).
    [[nodiscard]] double list_build_seconds() const { return list_seconds_; }
    // Particle pairs in the current Verlet list (touching or within the skin).
    [[nodiscard]] std::size_t list_pairs() const { return list_.pair_count(); }
    [[nodiscard]] std::size_t memory_bytes() const;
    // Throws RunError ("step N, t = …: grain K has a non-finite position or velocity") if a grain's state is
    // not finite.
    void check_finite() const;
    // Throws RunError naming the first grain whose centre lies more than its radius outside the box
    // [lo, hi] (the walls that enclose the run): a grain that passed through a wall in one step.
    void check_inside(const Vec3& lo, const Vec3& hi) const;

    // Jacobi sweeps of the rolling torques per step (default 1). The torques are warm-started from the
    // last step, so one sweep converges over a few steps in a static deposit; each extra sweep costs
    // two passes over the contacts (docs/dem.md).
    void set_rolling_sweeps(int sweeps);
    [[nodiscard]] int rolling_sweeps() const { return rolling_sweeps_; }
    // Largest Verlet skin of a fast grain, m (default: the skin, i.e. one skin for all). Each grain's
    // skin is chosen at every list build from its speed (about steps_per_half_skin steps of travel per
    // half-skin), between the skin given to the constructor and this; the list is rebuilt when a grain
    // has moved more than half its own skin. Changes which pairs are listed, never a force.
    void set_skin_max(double skin_max);
    [[nodiscard]] double skin() const { return skin_; }
    static constexpr double steps_per_half_skin = 16.0;
    // Changes gravity (a tilting table, a slope change); takes effect next step.
    void set_gravity(const Vec3& g) { gravity_ = g; }
    // Switches a wall on or off (an outlet gate, a temporary barrier); takes effect next step.
    void set_wall_active(std::size_t wall, bool active);
    // Sort the mobile grains by cell at the next list build and then every `builds` builds (0: never, the
    // default); keeps the pair loops cache-friendly as a flow mixes and each thread's range a compact slice
    // (dem/spatial_order.h). Indices of mobile grains then change: ids() maps each current index to the
    // grain's index at construction.
    void set_reorder_interval(int builds);
    // Largest overlap δ / d (smaller diameter) a step may reach before the run stops as failed (default 0.5).
    void set_overlap_limit(double ratio) { overlap_limit_ = ratio; }
    [[nodiscard]] const std::vector<std::uint32_t>& ids() const { return ids_; }
    // Takes the mobile grains i with gone[i] != 0 (one flag per current mobile grain) out of the
    // simulation at the next step's list rebuild: grains that left the domain through an outlet and
    // can no longer touch anything that matters. The others keep their order (and their contact
    // histories); fixed spheres move down behind them; ids() keeps naming every grain left.
    void remove_mobile(const std::vector<std::uint8_t>& gone);
    // Adds `arriving` as mobile grains after the present ones (their ids, new ones, are set here: above every
    // id the run has given), keeping every contact history, and rebuilds the lists now, so that a checkpoint
    // taken before the next step holds them. One process only (a divided run's grains come and go through
    // its halo). Their `vh` is their velocity, `f` and `t` zero.
    void add_mobile(std::vector<GrainRecord> arriving);
    // Mobile grains removed so far.
    [[nodiscard]] std::size_t removed_count() const { return removed_total_; }
    // Re-evaluates forces for the current state (after editing particles or walls by hand).
    void refresh();
    // A force and a torque on each mobile grain from outside the DEM (the fluid), N and N·m, indexed like
    // particles(): they act from this instant on (the force of the current state changes, so the next
    // kicks use them) and are held until set again; every force evaluation adds them to the contact force
    // and torque (particles().f and .t include them). They move with their grain when grains are reordered
    // or removed. None (and nothing added, not even + 0) until first set.
    void set_external_forces(std::span<const Vec3> force, std::span<const Vec3> torque);
    [[nodiscard]] std::span<const Vec3> external_forces() const { return external_force_; }
    [[nodiscard]] std::span<const Vec3> external_torques() const { return external_torque_; }
    // Forces a neighbour-list rebuild at the next force evaluation (contact history is carried over).
    void invalidate_lists() { lists_stale_ = true; }
    [[nodiscard]] bool lists_stale() const { return lists_stale_; }
    [[nodiscard]] double skin_max() const { return skin_max_; }
    // Torque on each particle in the last step, N·m (no synchronisation), and its active contacts.
    [[nodiscard]] const std::vector<Vec3>& torques() const { return p_.t; }
    [[nodiscard]] const std::vector<std::uint16_t>& contact_counts() const { return contact_count_; }

    // --- A run divided among processes (parallel/grain_halo.h). The last ghost_count() mobile grains are
    // ghosts: copies of grains another process owns, which sets their state every step. They have no list row
    // of their own: of their contacts only those with own grains are evaluated here (each contact of the run
    // once, in one process), and the reactions they receive go back to the owner (add_reaction); ghosts
    // touch no wall, fixed sphere or other ghost here. Global ids (ids()) name grains across processes.
    [[nodiscard]] std::size_t ghost_count() const { return ghost_count_; }
    [[nodiscard]] std::size_t own_count() const { return p_.n_mobile - ghost_count_; }
    // The records of the mobile grains at `indices`, appended to `out`.
    void pack_grains(std::span<const std::uint32_t> indices, std::vector<GrainRecord>& out) const;
    // The history of every live contact in the lists (own rows: particle pairs, fixed spheres, walls).
    void contact_records(std::vector<ContactRecord>& out) const;
    // Replaces the mobile grains by `grains` (own ones first, then `ghosts` ghosts; fixed spheres stay) and
    // carries the contact histories in `contacts` over to the lists of the next force evaluation, which
    // this makes stale: a contact in the new lists takes the record of its two ids (none: a fresh contact).
    void replace_mobile(std::span<const GrainRecord> grains, std::size_t ghosts,
                        std::vector<ContactRecord> contacts);
    // Forgets what the walls and fixed spheres received and the contact statistics of the last evaluation:
    // a rank of a divided run other than the first, whose copy of the undivided run's would count it again.
    void drop_last_reactions();
    // Rebuilds the lists now (after replace_mobile, before a step): the carried contacts keep their normal
    // forces, so the next step's rolling sweep acts on them as it would have without the replacement.
    void rebuild_lists_now();
    // The state of the mobile grains at `indices` as their ghost copies need it, into `out`.
    void ghost_states(std::span<const std::uint32_t> indices, std::vector<GhostState>& out) const;
    // Sets the ghosts' state, in ghost order.
    void set_ghost_states(std::span<const GhostState> states);
    // ω at the half step of each mobile grain (a ghost's changes by the rolling corrections of its contacts
    // here during drift(): the owner adds them with add_spin).
    [[nodiscard]] std::span<const Vec3> half_step_spins() const { return wh_; }
    // Rolling corrections of own grain i's contacts in another process, as a change of its ω_half.
    void add_spin(std::size_t i, const Vec3& dw);
    // Reactions that own grain i received from `count` contacts in another process in the last
    // finish_step(): added to its force and torque, and to the ω kick that step gave it.
    void add_reaction(std::size_t i, const Vec3& force, const Vec3& torque, std::uint32_t count);

    // Checkpoints (io/checkpoint.h): everything a step reads from the steps before it — grains with their
    // leapfrog state, the lists with every contact's history (tangential spring, slip state, rolling
    // torque, normal force, the active entries of each block), the walls' switches and forces, the
    // reordering and removal state, the clock. Settings (laws, Δt, skins) come from the case. A solver
    // made from the same case and then read back continues bit for bit as the one that was written; the
    // blocks of the passes are fixed-size, so this holds at another thread count too (the partition
    // follows the team). Call restored() after reading.
    template <class Archive>
    void transfer(Archive& a) {
        std::vector<std::uint8_t> active(walls_.size());
        for (std::size_t k = 0; k < walls_.size(); ++k) active[k] = walls_[k].active ? 1 : 0;
        a(p_, synced_, step_gravity_, gravity_, active, time_, steps_, lists_stale_, list_, reorder_interval_,
          builds_since_reorder_, reordered_, r_max_, ids_, order_, gone_, removed_now_, removed_total_, vh_,
          wh_, external_, external_force_, external_torque_, contact_count_, pair_hist_, pair_fn_,
          pair_touch_, pair_roll_, active_, block_active_, partner_reaction_, partner_fn_, wall_hist_,
          wall_roll_, wall_fn_, wall_touch_, wall_normal_, wall_force_, stats_, max_overlap_seen_,
          ghost_count_, next_id_);
        for (std::size_t k = 0; k < walls_.size() && k < active.size(); ++k)
            walls_[k].active = active[k] != 0;
    }
    // After transfer() read a checkpoint: checks the sizes against each other and sizes the scratch.
    void restored();

  private:
    void rebuild_lists();
    // Which of mesh wall entry k's slots each of a grain's contacts `now` with the wall takes
    // (dem/mesh_contacts.h): a slot whose contact starts afresh has its history cleared; each slot's normal
    // becomes its contact's. Slots left empty get nullptr (their histories are released by the caller).
    std::array<const WallTouch*, mesh_slots> place_in_slots(std::uint32_t k, const MeshTouches& now);
    // The history of the contact with `b` among one grain's carried records [first, last), if it has one;
    // `ordinal`: which of the records with `b` (a mesh wall's slots take its contacts in turn).
    static void carry_record(std::vector<ContactRecord>::const_iterator first,
                             std::vector<ContactRecord>::const_iterator last, std::uint32_t b,
                             std::uint32_t ordinal, TangentialState& history, Vec3& rolling,
                             double& normal_force, std::uint8_t& touch, Vec3& normal);
    struct ForceTotals {
        std::uint64_t contacts = 0, sliding = 0;
        double max_ratio = 0.0;
        int bad = 0;  // 1: coincident centres, 2: non-finite position
    };
    // Force evaluation outside step() (construction, refresh): rebuilds stale lists, then forces.
    void compute_forces();
    // The force region: force_passes on every thread, then finish_forces.
    void evaluate_forces(bool integrate);
    // integrate: also kick ω to the next half step as soon as a grain's forces are complete
    template <class Normal>
    void force_passes(const ContactLawSet<Normal>& laws, ForceTotals& totals, bool integrate);
    void finish_forces(const ForceTotals& totals);
    // For the failure messages (cold paths): the contact with the largest overlap, and the first grain
    // whose position or velocity is not finite, named by release id and position.
    [[nodiscard]] std::string largest_overlap_site() const;
    [[nodiscard]] std::string first_non_finite_grain() const;
    // One projected Jacobi update of every contact's rolling torque from the current ω_half (if
    // `rolling`), applied to ω_half; with `drift` also v kicked and x drifted. Inside a parallel region.
    template <class Normal>
    void sweep_pass(const ContactLawSet<Normal>& laws, bool rolling, bool drift, double& max_excess);
    // ω_half += Δt/J (own + received) rolling corrections; with `drift` the kick of v and the drift
    // (returns how far the grain is past its half-skin, NeighborList::excess).
    double finish_sweep(std::size_t i, const Vec3& dm, bool drift);
    struct Received;
    // Total force and torque on grain j: its own contacts' share plus the received reactions; with
    // `integrate` the ω kick.
    // (The own sums come as components, in registers: a Vec3 passed by reference goes through the stack,
    // written as scalars and read back as a 16-byte vector, a failed store-to-load forward per grain.)
    void finish_forces_of(std::size_t j, double fx, double fy, double fz, double tx, double ty, double tz,
                          std::uint32_t own_count, const Received& recv, bool integrate);
    void gather_reactions(std::ptrdiff_t j, bool integrate);
    // Writes the synchronous velocities into p_.v, p_.w if a step has run since the last call.
    void synchronize() const;
    void partition_blocks(int threads);
    // Grains [first, second) of thread t's blocks.
    [[nodiscard]] std::pair<std::size_t, std::size_t> grain_range(std::size_t t) const;
    // Partition and per-thread scratch for a team of omp_get_max_threads() threads, prepared before
    // a parallel region (so the passes need no serial section); returns the team size to request.
    int prepare_threads();
    // Called first in each pass inside a region: false (and the run stops after the region) if the
    // runtime gave a team of another size than prepared.
    bool team_matches_partition();
    bool team_mismatch_ = false;

    // mutable: p_.v and p_.w are a cache of the synchronous velocities, filled by synchronize()
    mutable Particles p_;
    mutable bool synced_ = true;
    Vec3 step_gravity_;  // gravity of the last force evaluation (for the synchronous velocities)
    std::vector<Wall> walls_;
    AnyContactLaws laws_;
    Vec3 gravity_;
    double dt_;
    double skin_;
    double skin_max_;                // largest skin of a fast grain (= skin_: one skin for all)
    std::vector<double> half_skin_;  // per mobile grain at the last build (scratch of rebuild_lists)
    int rolling_sweeps_ = 1;
    double time_ = 0.0;
    std::uint64_t steps_ = 0;
    bool lists_stale_ = true;
    double list_seconds_ = 0.0;  // list_build_seconds()
    std::size_t ghost_count_ = 0;
    // histories for the next rebuild by global ids (replace_mobile): every grain pair twice, seen from each
    // grain, sorted (dem/grain_records.h: before)
    std::vector<ContactRecord> carried_;
    bool carry_by_id_ = false;

    NeighborList list_;
    // spatial reordering (set_reorder_interval): order_ maps new index → index before the last reorder
    int reorder_interval_ = 0, builds_since_reorder_ = 0;
    bool reordered_ = false;  // the lists being built follow a reorder: histories are remapped
    double r_max_ = 0.0;
    std::vector<std::uint32_t> ids_, order_, order_start_, order_histogram_;
    std::uint32_t next_id_ = 0;  // above every id given so far (add_mobile; 0: not yet counted)
    double overlap_limit_ = 0.5;
    // grains flagged by remove_mobile(), taken out at the next rebuild (empty: none pending)
    std::vector<std::uint8_t> gone_;
    std::size_t removed_now_ = 0;  // mobile grains removed by the rebuild in progress (fixed-index shift)
    std::size_t removed_total_ = 0;
    // Renumbers the mobile grains new → old through order_ (every per-grain array follows), dropping
    // the grains order_ leaves out; with `sort` order_ is first the spatial order.
    void renumber_grains(bool sort);
    // Leapfrog state: v half a step behind the positions, ω half a step ahead (kicked when the forces
    // are gathered); the ω and v at the half step drive the contact kinematics.
    std::vector<Vec3> vh_, wh_;
    bool external_ = false;  // set_external_forces() was called: every force evaluation adds them
    std::vector<Vec3> external_force_, external_torque_;  // mobile grains (none until asked for)
    // active contacts per grain in the last evaluation (the rolling updates are split among them)
    std::vector<std::uint16_t> contact_count_;
    std::vector<Vec3> rolling_dm_;  // rolling-torque correction of a grain's own contacts (scratch)
    // How a grain receives the reactions of the pairs owned by lower-numbered grains. Summation order
    // is fixed: f = own + received, the received part summed in ascending owner order from zero.
    // A grain all of whose owners lie in the same thread's range, before it, receives them directly
    // into its Received record while that thread processes the owners (ascending by construction) and is
    // finished in the same pass; any other grain (owners in an earlier range, fixed spheres) is "parked": its
    // reactions go to the transposed slots and are gathered in ascending slot order after a barrier.
    // Both give the same bits, so the result still does not depend on the thread count; with one
    // thread nothing is parked and each step is two passes over the grains instead of four.
    std::vector<std::uint8_t> parked_;
    std::vector<std::uint32_t> parked_list_;  // the parked mobile grains, shared out after the barriers
    struct Received {                         // one record per grain: a reaction touches one cache line
        Vec3 force, torque;
        std::uint32_t count = 0;
    };
    // Cleared by the grain that consumes it. The rolling sweep uses `torque` alone, for the rolling
    // corrections received (the force pass of the same step has consumed the record before, and the
    // sweep leaves it cleared for the next force pass).
    std::vector<Received> recv_;
    // per pair entry (aligned with the list)
    struct Reaction {
        Vec3 force;     // force on i (−this on j)
        Vec3 torque_j;  // friction torque on the partner j
    };
    std::vector<TangentialState> pair_hist_;
    std::vector<double> pair_fn_;           // clipped normal force; 0 ⇒ the contact exerts nothing
    std::vector<std::uint8_t> pair_touch_;  // overlapping in the last evaluation (history is live)
    std::vector<Vec3> pair_roll_;  // rolling torque on i (−this on j), N·m: the next step's warm start
    // Entries with a positive normal force at the last evaluation, ascending, written by the force
    // pass per block of grains into the start of the block's own run of entries (block_active_[b] of
    // them): the rolling sweep of the next step visits only these.
    std::vector<std::uint32_t> active_;
    std::vector<std::uint32_t> block_active_;
    // per transposed slot (list_.t_slots()), so each partner reads its own slots in sequence: the
    // pass-1 reaction for the gather (between the gather and the next pass 1 the torque_j field
    // carries a sweep's rolling-torque correction for the partner) and a copy of the normal force
    std::vector<Reaction> partner_reaction_;
    std::vector<double> partner_fn_;
    // per wall-candidate entry
    std::vector<TangentialState> wall_hist_;
    std::vector<Vec3> wall_roll_;
    // a mesh wall's slot: the normal of its contact at the last evaluation (the next one's contacts are
    // matched to the slots by it, dem/mesh_contacts.h)
    std::vector<Vec3> wall_normal_;
    std::vector<double> wall_fn_;
    std::vector<std::uint8_t> wall_touch_;
    // a mesh wall's slot: the force its contact put on the wall in the last force pass (zero when apart)
    // and the triangle it lay on; written by every pass, so not kept in checkpoints
    std::vector<Vec3> wall_push_;
    std::vector<std::uint32_t> wall_triangle_;
    // wall reactions summed per block of grains, then over blocks in a fixed order (deterministic)
    std::vector<Vec3> wall_partial_;
    std::vector<Vec3> wall_scratch_;
    // thread t works on blocks [block_bounds_[t], block_bounds_[t+1]) in every pass
    std::vector<std::size_t> block_bounds_;
    std::vector<double> block_cost_;
    int partition_threads_ = 0;
    // Seconds each thread spent working in the passes since the last partition (stride busy_stride,
    // one cache line per thread). The next partition scales the modelled cost of each thread's
    // blocks by how long the thread actually took: results do not depend on the partition, so this
    // measured balancing leaves them bit-identical.
    static constexpr std::size_t busy_stride = 8;
    std::vector<double> busy_;
    std::vector<double> block_time_;  // scratch: cumulative measured-cost estimate per block
    // previous lists, for carrying history over a rebuild
    std::vector<std::uint32_t> prev_offset_, prev_partner_, prev_wall_offset_;
    std::vector<std::uint16_t> prev_wall_;
    std::vector<TangentialState> prev_pair_hist_, prev_wall_hist_;
    std::vector<Vec3> prev_pair_roll_, prev_wall_roll_, prev_wall_normal_;

    std::vector<Vec3> wall_force_;
    ContactStats stats_;
    double max_overlap_seen_ = 0.0;
};

}  // namespace sabo::dem
