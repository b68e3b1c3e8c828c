// SPDX-License-Identifier: MIT
// The lattice on an OpenCL device (docs/lbm.md, "Backends"): a FluidLattice built and prepared on the host
// as always, whose steps then run on the device. The host lattice stays the home of the state: push() copies
// it to the device (after the set-up, a checkpoint read, an edit), pull() copies the device's state back
// (populations, τ, the step count, the last step's element forces and clamps) before anything reads it —
// frames, checkpoints, observers. The device keeps the host's layout and storage (f_i − w_i, the AA
// pattern), so a state written by one backend continues on the other.
// Carried: fluid cells with BGK–Guo, Newtonian or Bingham, the Smagorinsky option, float32 or float64,
// periodic axes, bounce-back walls and moving walls with the momentum-exchange force per element.
// the free surface (mass exchange, conversions, excess mass; free_surface.cl) and outlets.
// Cells covered by moving solids (the grains of a coupled run), and a slab of a run divided among MPI
// ranks (FluidLattice::set_slab before it moves here): its ghost planes cross through the host
// (pack_planes, unpack_planes; parallel/device_halo.h) and the excess mass that finds no interface
// neighbour is summed over the ranks each step (set_orphan_sum).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/vec3.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_summary.h"
#include "lbm/inlet.h"
#include "lbm/opencl/devices.h"

namespace sabo::lbm::opencl {

struct DeviceView;  // device_view.h

template <class Real>
class OpenClLattice {
  public:
    // Builds the kernels for `host`'s shape, storage and rheology on `device`, allocates and pushes.
    // `profile`: every kernel launch timed by the device (kernel_seconds()), for benchmarks. `solids`: how
    // cells covered by moving solids exchange momentum with them (set_solid_cells; none: no such cells).
    OpenClLattice(FluidLattice<Real>& host, const DeviceInfo& device, bool profile = false,
                  std::optional<SolidExchange> solids = std::nullopt);
    ~OpenClLattice();
    OpenClLattice(const OpenClLattice&) = delete;
    OpenClLattice& operator=(const OpenClLattice&) = delete;

    // Bytes of device memory a lattice of `host`'s shape needs (populations, τ, the cells' types, links and
    // elements, the wall links' momenta), before anything is allocated.
    // With `solids`: the per-cell state of cells covered by moving solids too.
    [[nodiscard]] static std::uint64_t device_bytes(const FluidLattice<Real>& host, bool solids = false);
    // The refusal, with the numbers, of a lattice that does not fit `device` (none if it fits).
    static void check_fits(const FluidLattice<Real>& host, const DeviceInfo& device, bool solids = false);

    void push();
    void pull();
    // The macroscopic fields of the device's current state into `out` (lbm/fluid_fields.h), as the host
    // lattice's snapshot() gives them — what observers and frames read — without copying the populations
    // back: a few bytes a cell instead of the whole state.
    // Planes [x_begin, x_end) only (x_end < 0: to the last; out.first_x = x_begin): a section's cells.
    void snapshot(FluidFields& out, int x_begin = 0, int x_end = -1);
    // The sums a series row reads (lbm/fluid_summary.h), made on the device: a few numbers cross, not the
    // fields. `set_region`: each cell's RegionBits, one byte per cell in image order (x fastest, no padding;
    // empty: none): the cells of region_mass, and the region whose inflow the device counts from now on —
    // the host lattice's (FluidLattice::set_region, given the same region before).
    void set_region(std::span<const std::uint8_t> image);
    [[nodiscard]] FluidSummary summary();
    // The cells covered by moving solids for the next steps, as FluidLattice::set_solid_cells (built with
    // `solids`), and the force on the solid from each of them in the last step, lattice units.
    void set_solid_cells(std::span<const SolidCell> cells);
    [[nodiscard]] std::vector<Vec3> solid_cell_forces();
    // `count` steps on the device with the host lattice's current body force. `after_collision`, if
    // given, is called once the last step's collision is enqueued: what it enqueues (work that reads the
    // collision's results, such as the solids' forces) runs ahead of the free surface's passes, and the
    // host may wait for it alone.
    void step(std::uint64_t count = 1, const std::function<void()>& after_collision = {});
    [[nodiscard]] std::uint64_t steps() const { return steps_; }
    // Returns when the device has finished every step asked for (step() only enqueues them).
    void wait();
    // the fluid and interface cells the last step updated
    [[nodiscard]] std::uint64_t updated_cells();
    // The force on each element in the last step (read from the device when asked).
    [[nodiscard]] const std::vector<Vec3>& element_forces();
    // The last step's momentum of each of the host lattice's barrier links (FluidLattice::barrier_links, in
    // its order, as listed when last pushed; read from the device when asked): what the host's own steps
    // would have written into its list.
    [[nodiscard]] std::span<const double> barrier_link_momenta();
    [[nodiscard]] ClampCounts clamps();
    // The mass drained through each outlet since the start, lattice units.
    [[nodiscard]] std::array<double, max_outlets> drained();
    // The inflow boundary's held cells, as lbm::hold_inlet() on the host lattice (lbm/inlet.h): the mass
    // added, lattice units (the cells' sums in their order, on the host).
    double hold_inlet(std::span<const InletCell> cells, const Vec3& u);
    // The mass that entered the host lattice's region since the start (FluidLattice::region_inflow), counted
    // on the device in fixed orders (the CPU's sums to round-off), lattice units.
    [[nodiscard]] std::array<double, 3> region_inflow();
    [[nodiscard]] const DeviceInfo& device() const { return device_; }
    // The device and the lattice's buffers for kernels of the layers above (device_view.h).
    [[nodiscard]] DeviceView view() const;
    // With profiling: the device's time in each kernel since the last call, seconds (waits for the steps).
    [[nodiscard]] std::vector<std::pair<std::string, double>> kernel_seconds();

    // A slab's: told each step this slab's excess mass that found no interface neighbour and its interface
    // cells (own planes), `sum` makes them every slab's (a sum over the ranks), which the step then spreads.
    using SumOrphans = std::function<void(double& orphan_mass, double& surface_cells)>;
    void set_orphan_sum(SumOrphans sum) { sum_orphans_ = std::move(sum); }
    // Bytes of the state of `planes` whole planes (pack_planes): what a step reads of their cells.
    [[nodiscard]] std::size_t packed_bytes(int planes) const;
    // Enqueue the state of planes [x0, x0 + planes) into `message` / from it, which must stay alive and
    // untouched until the next wait() (the queue keeps their order: the steps after see the new state).
    void pack_planes(int x0, int planes, std::span<std::byte> message);
    void unpack_planes(int x0, int planes, std::span<const std::byte> message);
    // The last step's element forces, to be replaced by their sums over the ranks (a slab counts its own
    // planes' links).
    [[nodiscard]] std::span<Vec3> element_forces_to_sum();

  private:
    struct Impl;
    FluidLattice<Real>& host_;
    DeviceInfo device_;
    std::unique_ptr<Impl> impl_;
    // the last step's counts (τ clamps, updated cells), read from the device when asked
    void read_counters();
    // a slab's orphan mass and interface cells summed over the ranks (sum_orphans_), the share written back
    void share_orphans();
    // Bytes of `planes` planes' state in a message: the reals, the sums (as the device holds them), the
    // bytes.
    struct PlaneParts {
        std::size_t reals, wide, bytes;
    };
    [[nodiscard]] PlaneParts plane_parts(int planes) const;
    // pack_planes (into a message) or unpack_planes (from one)
    void move_planes(int x0, int planes, std::byte* into, const std::byte* from, std::size_t size);
    std::uint64_t steps_ = 0;
    std::vector<Vec3> forces_;
    bool forces_read_ = false;
    std::vector<double> barrier_momenta_;
    bool barrier_read_ = false;
    ClampCounts clamps_;
    std::uint64_t updated_ = 0;
    typename FluidLattice<Real>::SurfaceStats surface_stats_;
    std::array<double, max_outlets> drained_{};  // through each outlet so far (as of the last pull)
    std::array<double, 3> region_inflow_{};      // into the region so far (idem)
    double region_spread_ = 0.0;  // a slab's: the spreads' inflow since the last push (share_orphans())
    void set_crossings(std::span<const Crossing> links);
    bool counters_read_ = false;
    SumOrphans sum_orphans_;
};

extern template class OpenClLattice<float>;
extern template class OpenClLattice<double>;

}  // namespace sabo::lbm::opencl
