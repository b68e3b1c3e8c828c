// SPDX-License-Identifier: MIT
// One simulation: the solvers a case uses (grains, fluid, or both once they are coupled), one clock and
// the domain geometry. Every case type runs on it through the one run loop (sim/run_loop.h); what a case
// measures plugs in as observers (sim/observer.h). See docs/architecture.md.
#pragma once
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <utility>
#include <variant>
#include <vector>

#include "core/stopwatch.h"
#include "core/vec3.h"
#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_solver.h"
#include "dem/grain_view.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_summary.h"
#include "lbm/inlet.h"
#include "lbm/opencl/opencl_lattice.h"
#include "parallel/device_halo.h"
#include "parallel/domain.h"
#include "parallel/fluid_halo.h"
#include "parallel/grain_assembly.h"
#include "parallel/grain_halo.h"
#include "parallel/grain_visitors.h"
#include "parallel/slab_partition.h"
#include "parallel/slab_rebalance.h"
#include "sim/link_triangles.h"
#include "sim/phase_times.h"

namespace sabo::sim {

// Simulated time as a step count: t = steps · Δt (no drift from summing Δt).
struct Clock {
    double dt = 0.0;  // s
    std::uint64_t steps = 0;
    [[nodiscard]] double time() const { return static_cast<double>(steps) * dt; }
};

// The fluid, in the precision the case chose (lattice.storage).
using AnyLattice = std::variant<std::monostate, std::unique_ptr<lbm::FluidLattice<float>>,
                                std::unique_ptr<lbm::FluidLattice<double>>>;
// The same lattice's steps on an OpenCL device (lattice.device = "opencl"), when it runs there.
using AnyDeviceLattice = std::variant<std::monostate, std::unique_ptr<lbm::opencl::OpenClLattice<float>>,
                                      std::unique_ptr<lbm::opencl::OpenClLattice<double>>>;

class Simulation {
  public:
    // Grains alone: the clock is the DEM step.
    explicit Simulation(dem::DemSolver grains, parallel::Domain domain = {});
    // Fluid alone: the clock is the lattice step of `dt` seconds.
    // Divided among ranks (domain.divided()), the lattice is the rank's slab (domain.local_shape()).
    template <class Real>
    Simulation(std::unique_ptr<lbm::FluidLattice<Real>> fluid, double dt, parallel::Domain domain)
        : fluid_(std::move(fluid)), clock_{dt, 0}, domain_(std::move(domain)) {
        clock_.steps = lattice_steps();
        if (domain_.divided()) divide_lattice<Real>();
    }

    // Grains in the fluid: the clock is the lattice step of `dt` seconds, each with the coupling's DEM
    // sub-steps. One physics, said three times, must agree (else InputError): the grains' Δt times the
    // sub-steps is `dt`, and the lattice's acceleration, the grains' gravity and the coupling's gravity (its
    // buoyancy) are one g. Divided among ranks, the lattice is the rank's slab and the grains take the same
    // faces (parallel/grain_visitors.h).
    template <class Real>
    Simulation(dem::DemSolver grains, std::unique_ptr<lbm::FluidLattice<Real>> fluid,
               coupling::GrainFluidCoupling coupling, double dt, parallel::Domain domain)
        : grains_(std::make_unique<dem::DemSolver>(std::move(grains))),
          fluid_(std::move(fluid)),
          coupling_(std::move(coupling)),
          clock_{dt, 0},
          domain_(domain) {
        check_coupled_set_up(std::get<std::unique_ptr<lbm::FluidLattice<Real>>>(fluid_)->acceleration());
        clock_.steps = lattice_steps();
        if (!domain_.divided()) return;
        divide_lattice<Real>();
        divide_grains_with_lattice();
    }

    // From now on the fluid steps on an OpenCL device (docs/lbm.md, "Backends"): the lattice as it is moves
    // there, and its state comes back only when something reads it (fluid_fields(), a checkpoint). A divided
    // run's slab steps on its rank's device, its ghost planes staged through the host
    // (parallel/device_halo.h). Every rank calls it.
    void run_fluid_on(const lbm::opencl::DeviceInfo& device);

    // One step of the clock: the lattice step, the DEM step, or the coupled step (the lattice step with the
    // grain–fluid exchange, then the DEM sub-steps). `after_grain_step` runs after every DEM step (the
    // barrier's contact forces of every sub-step).
    void step(const std::function<void()>& after_grain_step = {});
    // The state of every solver (io/checkpoint.h): the grains, the fluid, the coupling's last exchange.
    // The set-up (geometry, settings) is the case's: a simulation built from the same case and read back
    // continues as the one that was written. The clock follows the solvers.
    template <class Archive>
    void transfer(Archive& a) {
        if (grains_) a(*grains_);
        if (grain_halo_) a(*grain_halo_);
        if (domain_.divided() && has_fluid()) {  // the slab faces, and a lattice of that slab to read into
            std::vector<int> cuts = domain_.cuts;
            a(cuts, rebalances_);
            if constexpr (Archive::reading)
                if (cuts != domain_.cuts)
                    with_fluid([&](auto& l) {
                        move_faces(cuts,
                                   parallel::slab_lattice(*domain_.world, l, cuts, domain_.halo.ghosts));
                    });
        }
        if constexpr (!Archive::reading) pull_fluid();
        if (has_fluid()) with_fluid([&](auto& l) { a(l); });
        if (coupling_) a(*coupling_);
        if constexpr (Archive::reading) {
            state_changed();
            if (grains_) grains_->restored();
            if (has_fluid()) with_fluid([](auto& l) { l.restored(); });
            push_fluid();
            // restored() derived the surface state of the ghost planes too, where it is the neighbours' to
            // say (an outer ghost's normal saw the wall beyond it): refreshed, as after a step
            if (halo_) halo_->prepare();
            follow_solvers();
        }
    }

    [[nodiscard]] double time() const { return clock_.time(); }
    [[nodiscard]] std::uint64_t steps() const { return clock_.steps; }
    [[nodiscard]] double dt() const { return clock_.dt; }
    [[nodiscard]] const parallel::Domain& domain() const { return domain_; }

    // Throws RunError naming the first grain whose state is not finite (a blow-up that no contact saw: a
    // free grain's NaN reaches no overlap test) or that left the domain's box (when the domain has one: the
    // walls enclose it). O(grains): the run loop calls it at each series row.
    void check_state() const {
        if (!grains_) return;
        grains_->check_finite();
        if (domain_.box.x > 0.0) grains_->check_inside(domain_.origin, domain_.origin + domain_.box);
    }

    [[nodiscard]] bool has_grains() const { return grains_ != nullptr; }
    // This rank's solver (in a divided run its own grains and their ghosts: analyses read grain_view()).
    [[nodiscard]] dem::DemSolver& grains() { return *grains_; }
    [[nodiscard]] const dem::DemSolver& grains() const { return *grains_; }
    // Every grain of the run (dem/grain_view.h; in a divided run a collective call, O(grains)), made once
    // per state: valid until the next step (or a grain edited by hand: then step or read a checkpoint first).
    [[nodiscard]] dem::GrainView grain_view() const;
    // The last step's contact forces on the fixed spheres and walls (in a divided run summed over the ranks
    // at every step).
    [[nodiscard]] dem::ContactForces contact_forces() const {
        if (!grain_halo_) return {grains_->forces(), grains_->wall_forces()};
        return {last_forces_.particles, last_forces_.walls};
    }
    // The force the grains' contacts of the last step put on each triangle of `mesh` (a barrier's; N,
    // indexed as its triangles) into `out`; summed over the ranks of a divided run (collective).
    void triangle_forces(const geometry::TriangleMesh& mesh, std::vector<Vec3>& out) const;
    // The fluid's force in the last lattice step on each triangle of `mesh` (a barrier's, whose part
    // element_part[e − 1] is the lattice's element e) into `out`, lattice units, indexed as its triangles:
    // each barrier link's momentum exchange on the triangle nearest its midpoint (sim/link_triangles.h;
    // the lattice keeps its links: FluidLattice::keep_barrier_links), so that a part's triangles add up to
    // its element's force; summed over the ranks of a divided run (collective).
    void fluid_triangle_forces(const geometry::TriangleMesh& mesh, std::span<const std::size_t> element_part,
                               std::vector<Vec3>& out) const;
    // Takes the mobile grains whose centre satisfies `leaves` out of the run (an outlet's): on one process at
    // the next list build, divided at the next step's re-partition. Every rank calls it at the same point.
    void remove_grains(const std::function<bool(const Vec3&)>& leaves);
    // Adds grains to the run (an inflow's; dem::DemSolver::add_mobile). Divided among ranks:
    // collective, every rank the same grains (parallel::GrainHalo::add).
    void add_grains(std::vector<dem::GrainRecord> grains);
    // Grains removed so far (over all ranks).
    [[nodiscard]] std::size_t removed_grains() const {
        return grain_halo_ ? grain_halo_->removed() : grains_->removed_count();
    }
    [[nodiscard]] bool has_fluid() const { return fluid_.index() != 0; }
    // The fluid's macroscopic fields on this rank's own planes (lbm/fluid_fields.h): what observers and
    // writers read of it, made once per state (valid until the next step), whatever the lattice's precision.
    [[nodiscard]] const lbm::FluidFields& fluid_fields() const;
    // At least planes [x_begin, x_end) (the lattice's global x) of them: a section's cells. A lattice on a
    // device copies those planes alone; the CPU's gives all its own (fields.first_x and nx say which).
    [[nodiscard]] const lbm::FluidFields& fluid_fields(int x_begin, int x_end) const;
    // The sums a series row reads of the fluid (lbm/fluid_summary.h), made where the lattice is: a lattice
    // on a device makes them there. `region` gives each cell's centre its RegionBits: region_mass sums the
    // cells in the region, region_inflow what entered it (FluidLattice::set_region) (set_fluid_region(),
    // once, before the first summary; none: 0).
    void set_fluid_region(const std::function<std::uint8_t(const Vec3&)>& region);
    [[nodiscard]] const lbm::FluidSummary& fluid_summary() const;
    // The fluid's force on each obstacle element in the last lattice step (element 0: the domain's walls),
    // lattice units.
    [[nodiscard]] std::span<const Vec3> fluid_element_forces() const;
    [[nodiscard]] bool coupled() const { return coupling_.has_value(); }
    [[nodiscard]] const coupling::GrainFluidCoupling& coupling() const { return *coupling_; }
    // Calls f(lattice) with the lattice in its precision (f is written once, for both; it returns the same
    // type for both).
    template <class F>
    decltype(auto) with_fluid(F&& f) {
        if (auto* single = std::get_if<1>(&fluid_)) return f(**single);
        if (auto* twice = std::get_if<2>(&fluid_)) return f(**twice);
        throw std::logic_error("the simulation has no fluid");
    }
    template <class F>
    decltype(auto) with_fluid(F&& f) const {
        if (const auto* single = std::get_if<1>(&fluid_)) return f(std::as_const(**single));
        if (const auto* twice = std::get_if<2>(&fluid_)) return f(std::as_const(**twice));
        throw std::logic_error("the simulation has no fluid");
    }

    // Holds an inflow boundary's cells (lbm/inlet.h) between steps, where the lattice is (on a device
    // there; what was read of the old state is dropped); the mass added, lattice units.
    double hold_inlet(std::span<const lbm::InletCell> cells, const Vec3& u) {
        state_changed();
        double added = 0.0;
        if (with_device([&](auto& d) { added = d.hold_inlet(cells, u); })) return added;
        return with_fluid([&](auto& l) { return lbm::hold_inlet(l, cells, u); });
    }

    // Work done by the last step, what the progress line's rate counts: the grains that moved, or the
    // fluid and interface cells the lattice updated (gas and obstacle cells cost nothing).
    [[nodiscard]] double work_of_last_step() const;
    // A divided run's wall-clock seconds on this rank: stepping its lattice (the measured cost of its slab),
    // and exchanging with the other ranks — the ghost planes, the sums, moving faces — waiting for them
    // included (0 on one process).
    [[nodiscard]] double stepping_seconds() const { return stepping_; }
    [[nodiscard]] double exchange_seconds() const;
    // Of those, the grains' (their halo, re-partitions, visitors, force sums).
    [[nodiscard]] double grain_exchange_seconds() const;
    // A divided run of grains alone: x of the faces between the ranks' slabs, m (none otherwise).
    [[nodiscard]] std::vector<double> grain_faces() const {
        return grain_halo_ && !has_fluid() ? grain_halo_->faces() : std::vector<double>{};
    }
    // How many times a divided run's slab faces moved (toward equal costs).
    [[nodiscard]] std::uint64_t rebalances() const {
        return grain_halo_ && !has_fluid() ? grain_halo_->face_moves() : rebalances_;
    }
    [[nodiscard]] const char* work_unit() const { return has_fluid() ? "cell updates" : "particle-steps"; }
    // Where this process's time went in its steps (sim/phase_times.h); the run loop adds the observers'
    // and the checkpoints' (add_time).
    [[nodiscard]] PhaseTimes timing() const {
        PhaseTimes t = times_;
        t.set(Phase::exchanges, exchange_seconds());
        if (has_fluid())
            t.parts.free_surface =
                surface_before_ + with_fluid([](const auto& l) { return l.surface_seconds(); });
        if (grains_) t.parts.neighbour_lists = grains_->list_build_seconds();
        t.parts.lattice_exchanges = halo_ ? halo_->exchange_seconds() : 0.0;
        t.parts.face_moves = face_moving_;
        t.parts.grain_exchanges = grain_exchange_seconds();
        return t;
    }
    void add_time(Phase phase, double seconds) { times_.add(phase, seconds); }

  private:
    template <class Real>
    void divide_lattice() {
        auto& lattice = *std::get<std::unique_ptr<lbm::FluidLattice<Real>>>(fluid_);
        halo_ = std::make_unique<parallel::LatticeHalo<Real>>(*domain_.world, lattice, domain_.slab,
                                                              domain_.halo);
        halo_->prepare();
    }
    // Refuses a coupled set-up whose steps or gravities disagree (`lattice_acceleration`: lattice units).
    void check_coupled_set_up(const Vec3& lattice_acceleration) const;
    // The grains divided at the lattice's faces, which they follow from then on.
    void divide_grains_with_lattice();
    // The fewest planes a slab of a coupled run may have: a grain then reaches no farther than its
    // neighbours' lattices (ghost planes included) and its contacts no farther than their grains.
    [[nodiscard]] int thinnest_coupled_slab() const {
        return domain_.halo.ghosts + static_cast<int>(std::ceil(grain_halo_->ghost_reach() / domain_.dx));
    }
    // The device's lattice of precision Real, if the fluid runs there.
    template <class Real>
    [[nodiscard]] lbm::opencl::OpenClLattice<Real>* device_lattice() const {
        auto* d = std::get_if<std::unique_ptr<lbm::opencl::OpenClLattice<Real>>>(&device_);
        return d != nullptr ? d->get() : nullptr;
    }
    // Calls f(lattice) with the device's lattice, whatever its precision, and says whether the fluid runs on
    // a device (false: f not called).
    template <class F>
    bool with_device(F&& f) const {
        if (auto* d = device_lattice<float>()) {
            f(*d);
            return true;
        }
        if (auto* d = device_lattice<double>()) {
            f(*d);
            return true;
        }
        return false;
    }
    [[nodiscard]] bool on_device() const { return device_.index() != 0; }
    // The device's state into the host lattice, if it has stepped since (before the host lattice is read),
    // and the host lattice's onto the device (after it was read from a checkpoint).
    void pull_fluid() const;
    void push_fluid();
    // Runs f() and adds its wall time, less the exchanges' within it, to `phase`.
    template <class F>
    void timed(Phase phase, F&& f) {
        const auto start = std::chrono::steady_clock::now();
        const double exchanged = exchange_seconds();
        f();
        times_.add(phase, seconds_since(start) - (exchange_seconds() - exchanged));
    }
    // The lattice step (a divided run's: the ghost planes exchanged after it, its time counted; on a
    // device: there, the host lattice's state left behind until it is read). `after_collision`: what a
    // device runs right after the collision, ahead of the free surface's passes (the grains' sums: the
    // DEM's steps wait for them alone).
    template <class Real>
    void step_lattice(lbm::FluidLattice<Real>& lattice, const std::function<void()>& after_collision = {}) {
        auto* device = device_lattice<Real>();
        const auto step = [&] {
            if (device == nullptr) return lattice.step();
            device->step(1, after_collision);
            host_behind_ = true;
        };
        if (!halo_) return step();
        const auto start = std::chrono::steady_clock::now();
        const double exchanged = exchange_seconds();  // the step itself waits for the others' orphan mass
        step();
        stepping_ += seconds_since(start) - (exchange_seconds() - exchanged);
        halo_->after_step();
    }
    // The grains' part of a coupled lattice step: their cells (divided: with those of the neighbours' grains
    // that reach into this rank's lattice), the lattice step, the fluid's forces set on them.
    template <class Real>
    void exchange_with_fluid(lbm::FluidLattice<Real>& lattice) {
        timed(Phase::grain_cells, [&] {
            const dem::Particles& p = grains_->particles();
            std::size_t own = p.n_mobile;
            std::span<const coupling::VisitingGrain> visitors;
            if (grain_halo_) {
                const auto [lo, hi] = domain_.neighbours_reach();
                visitors_->send(*grains_, lo, hi);
                own = grains_->own_count();
                visitors = visitors_->arrived();
            }
            // (the lattice on a device: the grains' cells found and covered there)
            if (device_cells_)
                coupling_->before_device_step(p, own, visitors, lattice, *device_cells_);
            else
                coupling_->before_fluid_step(p, own, visitors, lattice);
        });
        timed(Phase::lattice, [&] {
            // the grains' sums read back as soon as the collision has made them, and the DEM steps run while
            // the device does the free surface's passes — on a GPU: a CPU device (POCL) would take the
            // DEM's cores
            if (device_cells_ && device_info_->gpu)
                step_lattice(lattice, [&] { device_cells_->request_sums(); });
            else
                step_lattice(lattice);
        });
        timed(Phase::fluid_forces, [&] {
            if (device_cells_)
                coupling_->find_forces(*device_cells_);
            else
                coupling_->find_forces(lattice);
            if (!grain_halo_) return grains_->set_external_forces(coupling_->forces(), coupling_->torques());
            visitors_->gather_forces(coupling_->forces(), coupling_->torques(), *grains_);
            grain_halo_->set_external_forces(visitors_->forces(), visitors_->torques());
        });
    }
    // One DEM step (a divided run's: with its ghosts, and the barrier's forces summed over the ranks).
    void step_grains(const std::function<void()>& after_grain_step);
    // Moves the faces toward equal costs (every domain_.rebalance_every lattice steps); whether they moved.
    bool rebalance();
    // Takes `lattice` as the rank's lattice for the faces `cuts`, with a halo of its own.
    template <class Real>
    void move_faces(const std::vector<int>& cuts, std::unique_ptr<lbm::FluidLattice<Real>> lattice) {
        surface_before_ +=
            with_fluid([](const auto& l) { return l.surface_seconds(); });  // (the old lattice's)
        domain_.cuts = cuts;
        domain_.slab =
            parallel::SlabPartition::from_cuts(cuts).local(domain_.world->rank(), domain_.halo.ghosts);
        auto& l = *lattice;
        // the lattice replaced: the next move's memory (divided runs on the host)
        spare_fluid_ = std::move(fluid_);
        fluid_ = std::move(lattice);
        const double exchanged = halo_ ? halo_->exchange_seconds() : 0.0;
        halo_ = std::make_unique<parallel::LatticeHalo<Real>>(*domain_.world, l, domain_.slab, domain_.halo);
        halo_->add_exchange_seconds(exchanged);
        if (device_info_)
            place_on_device(l);  // (the kernels are built for the slab's planes; the region goes there too)
        else
            apply_region();
    }
    // Steps `lattice` on device_info_'s device from now on (with a slab's halo there).
    template <class Real>
    void place_on_device(lbm::FluidLattice<Real>& lattice);
    std::optional<lbm::opencl::DeviceInfo> device_info_;
    // The clock follows the step count of the solver that sets it.
    void follow_solvers() { clock_.steps = fluid_.index() != 0 ? lattice_steps() : grains_->steps(); }
    [[nodiscard]] std::uint64_t lattice_steps() const {
        std::uint64_t steps = 0;
        if (with_device([&](const auto& d) { steps = d.steps(); })) return steps;
        return with_fluid([](const auto& l) { return l.steps(); });
    }

    std::unique_ptr<dem::DemSolver> grains_;  // (on the heap: the grain halo holds it)
    AnyLattice fluid_;
    AnyLattice spare_fluid_;                // the lattice the faces' last move replaced (move_faces)
    mutable LinkTriangles link_triangles_;  // fluid_triangle_forces()
    AnyDeviceLattice device_;
    // a coupled run's grain cells on the device (coupling/opencl), made with the device's lattice
    std::unique_ptr<coupling::opencl::DeviceGrainCells> device_cells_;
    void make_device_cells();
    mutable bool host_behind_ = false;  // the device has stepped since the host lattice was last brought up
    std::optional<coupling::GrainFluidCoupling> coupling_;
    Clock clock_;
    parallel::Domain domain_;
    std::unique_ptr<parallel::FluidHalo> halo_;        // the ghost planes of a divided run's lattice
    std::unique_ptr<parallel::GrainHalo> grain_halo_;  // the ghost grains of a divided run of grains
    std::unique_ptr<parallel::GrainVisitors>
        visitors_;                              // a divided coupled run's grains that reach into other slabs
    mutable parallel::GrainAssembly assembly_;  // a divided run's views of every grain
    dem::ContactForces last_forces_;            // a divided run's, summed over the ranks after each step
    double summing_ = 0.0;                      // seconds spent summing them
    mutable std::optional<dem::GrainView> view_;  // grain_view() of the current state
    mutable lbm::FluidFields fields_;             // fluid_fields(), of the current state when fields_fresh_
    mutable bool fields_fresh_ = false;           // (then its planes: fields_.first_x, fields_.nx)
    mutable std::optional<lbm::FluidSummary> summary_;  // fluid_summary() of the current state
    std::function<std::uint8_t(const Vec3&)> region_;   // set_fluid_region()'s
    // the region's cells to the lattice (and to a device)
    void apply_region();
    // What was read of the state is out of date (a step, a restore).
    void state_changed() {
        view_.reset();
        fields_fresh_ = false;
        summary_.reset();
    }
    [[nodiscard]] dem::GrainView make_grain_view() const;
    double stepping_ = 0.0;
    double face_moving_ = 0.0;   // seconds in rebalance(), the grains' part of it (move_faces) included
    double grains_moved_ = 0.0;  // that part, which the grain halo counts as re-partitioning too
    PhaseTimes times_;
    double surface_before_ = 0.0;  // the free surface's seconds of the lattices the faces' moves replaced
    std::uint64_t rebalances_ = 0;
    std::vector<std::uint8_t> leaving_;  // remove_grains() scratch
};

}  // namespace sabo::sim
