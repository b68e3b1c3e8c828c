// SPDX-License-Identifier: MIT
// The lattice Boltzmann fluid (docs/lbm.md): D3Q19 BGK with Guo forcing, Newtonian or Bingham relaxation,
// half-way bounce-back on obstacle cells (walls, barrier elements; moving walls for Couette flows) and
// the momentum-exchange force on every obstacle element.
//
// Layout (docs/lbm.md): populations as a structure of arrays (population i of cell k at
// f_[i·S + k], S ≥ N the slot stride), stored as f_i − w_i (the deviation from rest, so float32 storage keeps
// its digits for what changes), one copy only: the AA pattern streams in place. An even step reads a cell's
// own populations and writes its post-collision ones back into the opposite slots; an odd step reads the
// populations arriving from the neighbours' slots and writes its post-collision ones into the
// neighbours' slots they travel to. Each step touches every population once for reading and once for
// writing, with no second array and no write-allocate of a separate destination. Obstacle and gas
// cells are skipped.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <type_traits>
#include <vector>

#include "core/huge_pages.h"
#include "core/vec3.h"
#include "lbm/barrier_links.h"
#include "lbm/d3q19.h"
#include "lbm/fluid_fields.h"
#include "lbm/rheology.h"

namespace sabo::lbm::detail {
template <class T>
struct Relaxation;
template <class T>
struct SolidLanes;
enum class Solid : std::uint8_t;
}  // namespace sabo::lbm::detail

namespace sabo::lbm {

struct GridShape {
    int nx = 1, ny = 1, nz = 1;
    // a non-periodic axis is closed by a wall half a cell beyond its first and last cells
    // (element 0, at rest)
    std::array<bool, 3> periodic{false, false, false};
    [[nodiscard]] std::size_t cells() const {
        return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
    }
};

// A lattice cell covered by a moving solid that the fluid flows through (the grains of the grain–fluid
// coupling): its storage index (FluidLattice::index), the velocity of the solid's surface at the cell's
// centre, lattice units, and the share ε of the cell's volume the solid takes (1: wholly covered).
struct SolidCell {
    std::size_t cell = 0;
    Vec3 velocity{};
    double fraction = 1.0;
};

// How the fluid of a cell covered by a solid exchanges momentum with it (set_solid_cells), B the
// saturation_weight() and λ the cell's fill fraction:
// - drag: F_h = B λ ρ (u_f − v_p), u_f = Σ c_i f_i / ρ before any force shift, the cell's force density
//   ρ a − F_h through the Guo term (Leonardi et al. 2016's simplified immersed boundary);
// - psm: Noble & Torczynski's (1998) partially saturated collision: the share B λ of the cell is solid,
//   relaxed toward v_p by the non-equilibrium bounce-back and not weighed; F_h the momentum that takes from
//   the fluid, the pressure on that share included (detail::collide_cell).
enum class SolidExchange : std::uint8_t { drag, psm };

// The drag weight of a cell partly covered by a solid (ε of its volume) at relaxation time τ (Noble &
// Torczynski 1998): B = ε (τ − ½) / ((1 − ε) + (τ − ½)), which tends to ε for large τ and gives a partial
// cell less weight near τ = ½, where BGK's boundary would otherwise move with the viscosity. Exactly 1 for ε
// = 1.
[[nodiscard]] inline double saturation_weight(double fraction, double tau) {
    if (fraction >= 1.0) return 1.0;
    const double t = tau - 0.5;
    return fraction * t / ((1.0 - fraction) + t);
}

// The excess mass of one cell conversion that found no interface neighbour (spread over the whole surface),
// with its place in the order the undivided lattice adds them up (FluidLattice::SlabRole).
struct OrphanMass {
    std::uint64_t order = 0;
    double mass = 0.0;
    // The order of cell (x global, y, z) in pass `pass` (filled cells 0, emptied ones 1): 20 bits each.
    [[nodiscard]] static std::uint64_t order_of(std::uint64_t pass, int x, int y, int z) {
        return pass << 60 | static_cast<std::uint64_t>(z) << 40 | static_cast<std::uint64_t>(y) << 20 |
               static_cast<std::uint64_t>(x);
    }
    // The cell it came from: global x, y, z.
    [[nodiscard]] std::array<int, 3> cell() const {
        return {static_cast<int>(order & 0xFFFFF), static_cast<int>(order >> 20 & 0xFFFFF),
                static_cast<int>(order >> 40 & 0xFFFFF)};
    }
};

// A link into a lattice's region (FluidLattice::set_region): from cell `from` outside it along c_`direction`
// to its neighbour `to` inside (storage indices); `part` 0 from a cell above the crest, else 1.
struct Crossing {
    std::size_t from = 0, to = 0;
    std::uint8_t direction = 0, part = 0;
};

template <class Real>
class FluidLattice {
  public:
    using value_type = Real;  // the storage type
    FluidLattice(const GridShape& shape, const Rheology& rheology) : FluidLattice(shape, rheology, nullptr) {}
    // The same, in `storage`'s memory (its per-cell arrays, emptied): where their capacity suffices no new
    // memory is touched. A divided run's face moves build a lattice every few hundred steps; fresh pages
    // for it (huge pages, compacted by the kernel on first touch) took 0.3–0.6 s a move on a 2-core VM.
    FluidLattice(const GridShape& shape, const Rheology& rheology, FluidLattice&& storage)
        : FluidLattice(shape, rheology, &storage) {}

    // Geometry, before the first step (or between steps; call prepare() after editing). Element 0
    // is the domain walls; add_element() gives further ones (a moving wall: its velocity, lattice units).
    std::uint16_t add_element(const Vec3& wall_velocity = {});
    void set_obstacle(int x, int y, int z, std::uint16_t element);
    void set_fluid(int x, int y, int z, double rho, const Vec3& u);  // at equilibrium
    // A free-surface cell holding the fill fraction `fill` of its volume (mass fill·ρ), at equilibrium.
    // Cells not set are gas. Fluid must not touch gas: put interface cells between them.
    void set_interface(int x, int y, int z, double rho, const Vec3& u, double fill);
    // An outlet cell (`outlet` < max_outlets): fluid that reaches it leaves the domain. An interface cell
    // there empties at the end of every step, its mass counted as drained through that outlet (not handed to
    // its neighbours); it never fills. An outlet cell is gas at the start (fluid there is refused by
    // prepare()). An open channel's end, the top of its air, its sides above the walls (docs/lbm.md).
    void set_outlet(int x, int y, int z, std::size_t outlet);
    // Between steps, after any number of them (an inflow boundary, lbm/inlet.h): a fluid or interface cell's
    // density, and a fluid cell put back at equilibrium (ρ, u) with mass ρ — in the layout of the step
    // count's parity (after an odd count, a cell's arriving populations sit in its neighbours' slots). The
    // obstacles next to it must be at rest.
    [[nodiscard]] double density_at(int x, int y, int z) const;
    // An interface cell's density of its last collision (its gas-side populations reconstructed: the ρ of
    // its fill fraction λ = m/ρ); its arriving populations from gas cells are not physical.
    [[nodiscard]] double surface_density(std::size_t k) const { return surface_rho_[surface_index(k)]; }
    void set_equilibrium(int x, int y, int z, double rho, const Vec3& u);
    // After such edits in planes x < `planes`: the free surface's normals and the new interface cells'
    // outgoing populations there (and in the next plane, whose normals and arrivals they touch) read again
    // from the edited state, as a checkpoint's restore reads them: a run continued from one stays the same.
    void surface_edited(int planes);
    // Recomputes the per-cell flags (cells next to an obstacle or the domain walls).
    void prepare();

    void set_acceleration(const Vec3& a) { accel_ = a; }  // body force per unit mass (gravity), lattice
    [[nodiscard]] const Vec3& acceleration() const { return accel_; }
    // The cells covered by moving solids for the next steps, ascending by cell, each once (replaces the
    // last list), and how they exchange momentum with their solid: a fluid or interface cell among them
    // exchanges F_h (SolidExchange) with weight B λ (λ its fill fraction, B = saturation_weight(ε, τ) with τ
    // the cell's last relaxation time: 1 in a wholly covered cell). Gas and obstacle cells exchange
    // nothing. Results with an empty list are those of a lattice without solids, bit for bit.
    void set_solid_cells(std::span<const SolidCell> cells, SolidExchange exchange = SolidExchange::drag);
    [[nodiscard]] const std::vector<SolidCell>& solid_cells() const { return solid_cells_; }
    [[nodiscard]] bool covered_by_solid(std::size_t k) const { return (near_wall_[k] & solid_bit) != 0; }
    // F_h of each solid cell in the last step (lattice units; 0 where the cell was not wet).
    [[nodiscard]] const std::vector<Vec3>& solid_cell_forces() const { return solid_force_; }
    void step();
    // Mass drained through each outlet since the start, lattice units (a slab's: its own planes').
    [[nodiscard]] const std::array<double, max_outlets>& drained() const { return drained_; }
    // A region whose inflow the lattice counts every step (a debris run's: the cells behind its barrier;
    // docs/analysis.md, "Overflow"): `bits` holds each stored cell's RegionBits (empty: none). Fluid enters
    // it two ways. Across the links into it (crossings(); a slab's: from its own planes' cells), carrying
    // what the free surface's mass exchange counts: α (f_i streamed in − f_ī streamed out), α = 1 between
    // wet cells unless both are interface cells (then the mean of their fill fractions), 0 with a gas or
    // obstacle cell — region_inflow()[0] from cells above the crest, [1] from the others. And by the free
    // surface's conversions ([2]): a filled or emptied cell's excess handed to its interface neighbours
    // across the region's face, and the excess of a conversion with no interface neighbour (or that closed
    // a gas pocket), which goes to every interface cell of the whole surface — the region's interface
    // cells' shares less the excess of its own such conversions.
    void set_region(std::vector<std::uint8_t> bits);
    [[nodiscard]] const std::vector<Crossing>& crossings() const { return crossings_; }
    // Cell k's RegionBits (0 without a region).
    [[nodiscard]] std::uint8_t region_bits(std::size_t k) const { return region_.empty() ? 0 : region_[k]; }
    // Mass that entered the region since the start, lattice units (a slab's: through its own planes' links
    // and into its own cells).
    [[nodiscard]] const std::array<double, 3>& region_inflow() const { return region_inflow_; }

    // A lattice that is one slab along x of a larger one (parallel/fluid_halo.h): its planes [own_begin,
    // own_end) are its own, the others ghosts mirroring a neighbour's; local plane x is plane x +
    // first_global_x of the whole. The excess mass of conversions with no interface neighbour goes to the
    // whole surface, every slab's: `spread` (called by every slab in every step, collectively) receives this
    // slab's own records, in order, and the number of its own interface cells, and leaves every slab's
    // records, in order, and the total count. Results are then those of the undivided lattice, bit for bit,
    // given exact ghosts. (Set without `spread` before the set-up, so that it counts its own planes' cells.)
    using SpreadOrphans = std::function<void(std::vector<OrphanMass>& orphans, std::uint64_t& surface_cells)>;
    struct SlabRole {
        int own_begin = 0, own_end = 0, first_global_x = 0;
        SpreadOrphans spread;
    };
    void set_slab(SlabRole role);
    // What the slab exchange copies between neighbours' lattices besides the populations and τ: λ, m and the
    // cell types, cell by cell (index()), and the free-surface state of the interface cells of some planes.
    [[nodiscard]] std::span<Real> fill_fractions() { return fill_; }
    [[nodiscard]] std::span<double> masses() { return mass_; }
    [[nodiscard]] std::span<CellType> cell_types() { return type_; }
    [[nodiscard]] std::span<const CellType> cell_types() const { return type_; }
    // surface_record values per interface cell: ρ, u, the normal, the Q outgoing populations, whether the
    // sweep recorded them
    static constexpr std::size_t surface_record = 8 + Q;
    // Appends the records of the interface cells of planes [x0, x0 + planes) to `records`, ascending.
    void pack_surface(int x0, int planes, std::vector<double>& records) const;
    // Replaces the interface cells of planes [x0, x0 + planes) and their state by those the (already
    // replaced) cell types name there, with `records` as pack_surface() wrote them for those cells.
    void replace_surface(int x0, int planes, std::span<const double> records);

    // Moving planes to the lattice of a rank whose slab changes (sim/simulation.h, rebalance): the whole
    // state of planes [x0, x0 + planes) — every cell's populations, τ, type, λ, mass and obstacle element,
    // and the interface cells' surface records — appended to `out`. import_planes() writes such a block into
    // the planes from x0 on of a lattice of the same ny × nz (their interface cells replaced) and returns the
    // bytes it read. After the last import: adopt() (the step count, body force, elements and last step's
    // measures of the lattice the planes came from), then relink() (the flags that follow from the types).
    void export_planes(int x0, int planes, std::vector<std::byte>& out) const;
    std::size_t import_planes(int x0, int planes, std::span<const std::byte> in);
    // The same as export_planes(from_x0, planes) of `from` imported at x0, without the block between.
    void copy_planes(const FluidLattice& from, int from_x0, int x0, int planes);
    void relink();
    void adopt(const FluidLattice& from);

    // What a device backend (lbm/opencl/) copies to its memory and back: the whole population storage
    // (population_slots() of every i, slot_stride() apart), the obstacles' elements, each cell's solid links
    // (bit i: the neighbour along c_i is an obstacle or beyond a closed edge; set by prepare()) and the
    // elements' wall velocities. record_steps() takes back what the device's steps leave behind: the step
    // count, the last step's element forces, clamps, updated cells and cell conversions, and the mass drained
    // through each outlet and into the region so far.
    [[nodiscard]] std::span<Real> populations() { return {f_.data(), f_.size()}; }
    [[nodiscard]] std::size_t slot_stride() const { return slot_; }
    [[nodiscard]] std::span<const std::uint16_t> obstacle_elements() const { return element_; }
    [[nodiscard]] std::span<const std::uint32_t> solid_link_bits() const { return solid_links_; }
    // Neighbour of (x, y, z) along c_i (sign +1) or −c_i (sign −1): its index, or −1 outside a
    // non-periodic axis.
    [[gnu::always_inline]] [[nodiscard]] std::ptrdiff_t neighbour(int x, int y, int z, int i,
                                                                  int sign) const {
        const int px = x + sign * cx[i], py = y + sign * cy[i], pz = z + sign * cz[i];
        if (static_cast<unsigned>(px) < static_cast<unsigned>(shape_.nx) &&
            static_cast<unsigned>(py) < static_cast<unsigned>(shape_.ny) &&
            static_cast<unsigned>(pz) < static_cast<unsigned>(shape_.nz))
            return static_cast<std::ptrdiff_t>(index(px, py, pz));
        return beyond_edge(px, py, pz);
    }
    // (x, y, z) outside the lattice on some axis: wrapped if that axis is periodic, −1 otherwise
    [[nodiscard]] std::ptrdiff_t beyond_edge(int x, int y, int z) const;
    [[nodiscard]] const std::vector<Vec3>& element_velocities() const { return element_velocity_; }
    // per cell 0, or 1 + its outlet (empty: the lattice has none)
    [[nodiscard]] std::span<const std::uint8_t> outlet_cells() const { return outlet_; }
    struct SurfaceStats;
    void record_steps(std::uint64_t steps, std::span<const Vec3> element_forces, ClampCounts clamps,
                      std::uint64_t updated_cells, const SurfaceStats& surface,
                      const std::array<double, max_outlets>& drained,
                      const std::array<double, 3>& region_inflow);

    // an interface cell fills above (1 + ε)ρ and empties below −ερ (docs/lbm.md)
    static constexpr double surface_epsilon = 1e-3;

    [[nodiscard]] const GridShape& shape() const { return shape_; }
    [[nodiscard]] const Rheology& rheology() const { return rheology_; }
    // Cells are stored row by row with rows padded to whole cache lines (row_stride() ≥ nx cells): every
    // row starts on a line, so the sweep's vectors of a row's cells are whole lines (docs/lbm.md, "Data
    // layout"). The padding cells are gas and nobody's neighbour. Loop over x, y, z and ask index(); the
    // storage holds stored_cells(shape) ≥ shape.cells() cells.
    [[nodiscard]] static std::size_t row_stride(int nx) {
        constexpr std::size_t line = 64 / sizeof(Real);
        return (static_cast<std::size_t>(nx) + line - 1) / line * line;
    }
    [[nodiscard]] static std::size_t stored_cells(const GridShape& shape) {
        return row_stride(shape.nx) * static_cast<std::size_t>(shape.ny) * static_cast<std::size_t>(shape.nz);
    }
    [[nodiscard]] std::size_t index(int x, int y, int z) const {
        return static_cast<std::size_t>(x) + row_ * static_cast<std::size_t>(y) +
               plane_ * static_cast<std::size_t>(z);
    }
    // (x, y, z) of the cell stored at k
    [[nodiscard]] std::array<int, 3> coords(std::size_t k) const {
        const std::size_t in_plane = k % plane_;
        return {static_cast<int>(in_plane % row_), static_cast<int>(in_plane / row_),
                static_cast<int>(k / plane_)};
    }
    [[nodiscard]] CellType type(std::size_t k) const { return type_[k]; }
    // The stored slots of population i (f_i − w_i of every stored cell, by index()): what the slab exchange
    // copies between neighbouring ranks' lattices (parallel/slab_exchange.h, docs/scaling.md).
    [[nodiscard]] std::span<Real> population_slots(int i) {
        return {f_.data() + static_cast<std::size_t>(i) * slot_, n_};
    }
    // Each cell's relaxation time of its last collision (a Bingham collision starts from it): exchanged
    // with the populations.
    [[nodiscard]] std::span<Real> relaxation_times() { return tau_; }
    // Density and velocity (u = (Σ f c + F/2)/ρ, the velocity of the collision) of a fluid cell now.
    void moments(std::size_t k, double& rho, Vec3& u) const;
    [[nodiscard]] double tau(std::size_t k) const { return static_cast<double>(tau_[k]); }
    // Lattice mass (Σ ρ over the fluid cells + Σ m over the interface cells) and the largest |u| over
    // both, in one pass over the own planes (a slab's: set_slab); `visit(k, rho, u)` sees every such cell on
    // the way (a run's own sums).
    template <class Visit>
    [[nodiscard]] FluidTotals totals(Visit&& visit) const {
        FluidTotals t;
        for (int z = 0; z < shape_.nz; ++z)
            for (int y = 0; y < shape_.ny; ++y)
                for (int x = slab_.own_begin; x < slab_.own_end; ++x) {
                    const std::size_t k = index(x, y, z);
                    if (type_[k] != CellType::fluid && type_[k] != CellType::interface) continue;
                    double rho = 0.0;
                    Vec3 u;
                    moments(k, rho, u);
                    t.mass += type_[k] == CellType::interface ? mass_[k] : rho;
                    t.max_speed = std::max(t.max_speed, norm(u));
                    visit(k, rho, u);
                }
        return t;
    }
    [[nodiscard]] FluidTotals totals() const {
        return totals([](std::size_t, double, const Vec3&) {});
    }
    [[nodiscard]] double total_mass() const { return totals().mass; }
    // The macroscopic state of the own planes into `out` (lbm/fluid_fields.h): what observers and writers
    // read.
    void snapshot(FluidFields& out) const;
    // Fill fraction λ: 1 fluid, 0 gas and obstacle, m/ρ interface.
    [[nodiscard]] double fill(std::size_t k) const { return static_cast<double>(fill_[k]); }
    // The share of a solid cell's drag that acts: its fill clamped to [0, 1] (an interface cell's fill
    // strays up to ε outside [0, 1] before the cell converts).
    [[nodiscard]] double coupling_weight(std::size_t k) const { return std::clamp(fill(k), 0.0, 1.0); }
    // A z-plane holding at least this many interface cells is swept in blocks of rows (sweep_tiles()).
    static constexpr std::size_t split_plane_interface_cells = 1024;
    // interface cells in the own planes
    [[nodiscard]] std::size_t interface_count() const {
        if (slab_.own_begin == 0 && slab_.own_end == shape_.nx) return interface_.size();
        return static_cast<std::size_t>(std::count_if(interface_.begin(), interface_.end(),
                                                      [&](std::uint32_t k) { return own_plane(k); }));
    }
    // The own planes' local x range (all planes but in a slab).
    [[nodiscard]] int own_begin() const { return slab_.own_begin; }
    [[nodiscard]] int own_end() const { return slab_.own_end; }
    [[nodiscard]] int first_global_x() const { return slab_.first_global_x; }
    // Wall-clock seconds this process spent in the free surface's passes of its steps (mass exchange,
    // conversions, the new interface's normals; not a slab's waits for the others' orphan mass, which the
    // halo counts among its exchanges): for the run's timing, not part of its state.
    [[nodiscard]] double surface_seconds() const {
        return surface_seconds_.exchange + surface_seconds_.conversions + surface_seconds_.prepare;
    }
    // The same split by pass: the mass exchange, the cell conversions (with the orphan mass's spread, but not
    // a slab's wait for the others'), the new interface's normals and outgoing populations
    // (bench/lbm_throughput prints them).
    struct SurfaceSeconds {
        double exchange = 0.0, conversions = 0.0, prepare = 0.0;
    };
    [[nodiscard]] const SurfaceSeconds& surface_pass_seconds() const { return surface_seconds_; }
    // Whether its steps run the free-surface passes: it has interface cells, or it is a slab that takes
    // part in the spread of the others' orphan mass (set_slab's spread).
    [[nodiscard]] bool steps_surface() const { return has_surface() || static_cast<bool>(slab_.spread); }
    // Whether local plane x, or cell k, is one of the slab's own (not a ghost).
    [[nodiscard]] bool own_x(std::size_t x) const {
        return static_cast<int>(x) >= slab_.own_begin && static_cast<int>(x) < slab_.own_end;
    }
    [[nodiscard]] bool own_plane(std::size_t k) const {
        return own_x(static_cast<std::size_t>(coords(k)[0]));
    }
    // Cell conversions of the last step, those whose excess mass went to the whole surface (no interface
    // neighbour, or the volume of a closed gas pocket) and the closed pockets' cells whose deficit went to
    // the surface near them (set_pocket_reach); a slab counts its own planes' only.
    struct SurfaceStats {
        std::size_t filled = 0, emptied = 0, orphan_excess_cells = 0, pocket_cells = 0;
    };
    [[nodiscard]] const SurfaceStats& surface_stats() const { return surface_stats_; }
    // Force of the fluid on each element in the last step (momentum exchange), lattice units, relative to
    // the atmosphere (the fluid at rest at ρ_A = 1 exerts none).
    // A slab's count its own planes' cells only, until the slab exchange sums them over the ranks (through
    // element_forces_to_sum(); a lattice with no element but the domain's walls is not summed).
    [[nodiscard]] const std::vector<Vec3>& element_forces() const { return element_force_; }
    [[nodiscard]] std::span<Vec3> element_forces_to_sum() { return element_force_; }
    // The wall links into the obstacles of elements ≥ 1 kept one by one from now on, with each step's
    // momentum exchange (lbm/barrier_links.h): what a force map finer than the elements sums. Off until
    // asked for (it costs a lookup per barrier link and step); listed by the next prepare() or relink(), and
    // asked for again on the lattice of a face move (parallel::slab_lattice).
    void keep_barrier_links() { keep_barrier_links_ = true; }
    // Where the deficit of an enclosed interface cell that fills (a closed gas pocket's volume) is taken
    // from: 0, every interface cell (the default); n ≥ 1, the interface cells reachable from it through wet
    // cells within n steps along the links (every interface cell if there are none). Read by the OpenCL
    // lattice when it is built; in slabs, the halo must be 2n planes deeper
    // (parallel::HaloSettings::with_free_surface; docs/lbm.md, "What the spread moves").
    void set_pocket_reach(int cells);
    static constexpr int max_pocket_reach = 8;  // (the search's box of marks is sized for it)
    [[nodiscard]] int pocket_reach() const { return pocket_reach_; }
    [[nodiscard]] bool keeps_barrier_links() const { return keep_barrier_links_; }
    [[nodiscard]] const BarrierLinks& barrier_links() const { return barrier_links_; }
    [[nodiscard]] const ClampCounts& clamps() const { return clamps_; }
    // fluid and interface cells the last step updated (the work measure of MLUPS)
    [[nodiscard]] std::uint64_t updated_cells() const { return updated_cells_; }
    [[nodiscard]] std::uint64_t steps() const { return steps_; }
    // The state that evolves (io/checkpoint.h): populations, τ, cell types and the obstacles' elements, λ,
    // masses, the interface list and its last-collision state, the step count, the body force and the
    // elements' velocities. A lattice is restored by building it as the run did and calling prepare() (or
    // empty, of the shape it had: a slab whose faces moved), then transfer() from a CheckpointIn and
    // restored().
    template <class Archive>
    void transfer(Archive& a) {
        a(steps_, accel_, f_, tau_, type_, element_, fill_, mass_, interface_, surface_rho_, surface_u_, out_,
          out_known_, element_velocity_, outlet_, drained_, region_inflow_);
    }
    // Checks what transfer() read against the lattice's shape and rebuilds what follows from it.
    void restored();
    [[nodiscard]] static constexpr std::size_t bytes_per_cell() {
        // populations, τ, fill fraction, mass (double), type, wall flag, solid links, element, outlet, region
        return Q * sizeof(Real) + 2 * sizeof(Real) + sizeof(double) + sizeof(CellType) +
               sizeof(std::uint8_t) + sizeof(std::uint32_t) + sizeof(std::uint16_t) +
               2 * sizeof(std::uint8_t);
    }

  private:
    FluidLattice(const GridShape& shape, const Rheology& rheology, FluidLattice* storage);
    template <bool Odd, bool Bingham, bool Les>
    void stream_collide();
    // The fused stream-collide of n interior fluid cells from cell k on (a run along x; with Column, the same
    // place in n consecutive rows), vectorised; the neighbour along c_i of each is at index + shift[i].
    // S other than none: the n cells are wet solid cells (or of weight 0), `grains` their weights, v_p and
    // F_h (detail::SolidLanes).
    template <bool Odd, bool Bingham, bool Les, bool Column = false,
              detail::Solid S = detail::Solid{}>  // {}: none
    ClampCounts collide_interior(std::size_t k, std::size_t n, const std::ptrdiff_t* shift,
                                 std::uint32_t solid_bits, const detail::Relaxation<Real>& r,
                                 const detail::SolidLanes<Real>* grains = nullptr);
    // Asks the caches for the populations the step (odd or even) reads and writes for the cells from row +
    // from to row + to (shift: the sweep's for the row's middle cells); software prefetch, nothing is read.
    template <bool Odd>
    void request_row(std::size_t row, std::size_t from, std::size_t to, const std::ptrdiff_t* shift) const;
    // Pre-collision populations of fluid cell (x, y, z) at the current parity (odd: after an even
    // step), population i into f[i·stride]; neighbour by neighbour (walls, periodic wrap).
    template <bool Odd>
    void gather(int x, int y, int z, std::size_t k, double* f, std::size_t stride) const;
    // The same for the sweep, which knows the cell's neighbours: nb[i] along c_i as in detail::Batch.
    template <bool Odd>
    void gather_links(std::size_t k, const std::ptrdiff_t* nb, double* f, std::size_t stride) const;
    // The first x' ≥ x below nx of the row from cell `row` on that is a fluid or interface cell (nx if none).
    [[nodiscard]] std::size_t next_wet(std::size_t row, std::size_t x, std::size_t nx) const;
    // Past the whole groups of eight cells from x on (below nx) that are all fluid (Fluid) and have no solid
    // link (NoWalls): where a cell-by-cell search (a run's end, its cells next to a wall) goes on.
    template <bool Fluid, bool NoWalls>
    [[nodiscard]] std::size_t plain_run_end(std::size_t row, std::size_t x, std::size_t nx) const;
    // nb[i] (as in detail::Batch) of cell k, whose neighbour along c_i is k + shift[i] unless solid (bit i of
    // solid_bits, its solid_links_ entry)
    void links(std::size_t k, const std::ptrdiff_t* shift, std::uint32_t solid_bits,
               std::ptrdiff_t* nb) const;
    // Around a run of fluid cells from row + from to row + to (shift: the sweep's for the row's first cell,
    // the middle ones and the last), for those next to an obstacle: before an odd step's collision, the
    // moving-wall term of the populations about to return from the obstacles; after the collision, the
    // force on the obstacles (momentum exchange, into plane[element]) and, odd steps with moving walls,
    // the term of the populations just bounced back.
    void return_from_walls(std::size_t row, std::size_t from, std::size_t to,
                           const std::ptrdiff_t (&shift)[3][Q]);
    template <bool Odd>
    void wall_links(std::size_t row, std::size_t from, std::size_t to, const std::ptrdiff_t (&shift)[3][Q],
                    bool moving_walls, Vec3* plane);
    [[nodiscard]] bool solid(std::ptrdiff_t n) const {
        return n < 0 || type_[static_cast<std::size_t>(n)] == CellType::obstacle;
    }
    [[nodiscard]] std::uint16_t element_of(std::ptrdiff_t n) const {
        return n < 0 ? 0 : element_[static_cast<std::size_t>(n)];
    }
    [[nodiscard]] bool solid_or_gas(std::ptrdiff_t n) const {
        return n < 0 || type_[static_cast<std::size_t>(n)] == CellType::obstacle ||
               type_[static_cast<std::size_t>(n)] == CellType::gas;
    }

    // Free surface (free_surface.cpp; Körner et al. 2005, Thürey & Rüde 2009). The populations around
    // a cell as the layout holds them between steps (steps_ even: the last step was odd or none):
    // incoming(k, j) = f_j(k) before the next collision; outgoing(k, i) = f_i*(k) after the last one.
    [[nodiscard]] double incoming(int x, int y, int z, std::size_t k, int j) const;
    [[nodiscard]] double outgoing(int x, int y, int z, std::size_t k, int i) const;
    void set_outgoing(int x, int y, int z, std::size_t k, int i, double value);
    // incoming(k, j) from the lattice neighbour src = k − c_j that is not solid
    [[nodiscard]] double streamed_in(std::size_t k, int j, std::size_t src) const;
    // After the sweep (steps_ already counted), in this order: exchange_mass() — the mass the interface
    // cells exchanged with their neighbours through the populations just streamed, λ = m/ρ, and which
    // cells fill or empty; convert_cells() — the conversions, the excess mass, the new list;
    // prepare_surface() — the outgoing populations and normals of the new list for the next sweep.
    void exchange_mass();
    void convert_cells();
    void prepare_surface();
    void prepare_surface_cell(std::size_t s);  // one interface cell's (its place in the interface list)
    // In the sweep: replaces the populations of interface cell `s` that come from gas or from the gas
    // side (n·c_j < 0) by the atmospheric reconstruction; f[j·stride] holds the gathered ones.
    // gas_bits: bit i set where the neighbour along c_i is gas.
    void reconstruct(std::size_t s, const std::ptrdiff_t* nb, std::uint32_t gas_bits, double* f,
                     std::size_t stride) const;
    [[nodiscard]] Vec3 surface_normal(int x, int y, int z) const;
    [[nodiscard]] std::size_t surface_index(std::size_t k) const;
    [[nodiscard]] bool has_surface() const { return !interface_.empty(); }
    // replace_surface()'s common case: the planes hold the same interface cells; false (and nothing
    // consistent written) otherwise
    bool overwrite_surface(int x0, int planes, std::span<const double> records);
    // each(k) for the cells of planes [x0, x0 + planes), z, then y, then x (the order of export_planes'
    // blocks)
    // visit(field of a, the same field of b) for every per-cell field that moves with a plane (the
    // populations, τ, type, obstacle element, λ, mass), in the order of export_planes' blocks: one list for
    // the export, the import and the copy of planes
    template <class A, class B, class Visit>
    static void moving_fields(A& a, B& b, Visit&& visit) {
        for (std::size_t i = 0; i < Q; ++i) visit(a.f_.data() + i * a.slot_, b.f_.data() + i * b.slot_);
        visit(a.tau_.data(), b.tau_.data());
        visit(a.type_.data(), b.type_.data());
        visit(a.element_.data(), b.element_.data());
        visit(a.fill_.data(), b.fill_.data());
        visit(a.mass_.data(), b.mass_.data());
    }
    // The rows of planes [x0, x0 + planes) of one field, appended to a block at `at` (Export) or read from
    // it.
    template <class T, bool Export>
    void plane_rows(int x0, int planes, std::conditional_t<Export, const T*, T*> field,
                    std::conditional_t<Export, std::vector<std::byte>&, std::span<const std::byte>> io,
                    std::size_t& at) const;
    template <class Each>
    void for_planes(int x0, int planes, Each&& each) const {
        for (int z = 0; z < shape_.nz; ++z)
            for (int y = 0; y < shape_.ny; ++y)
                for (int x = x0; x < x0 + planes; ++x) each(index(x, y, z));
    }

    GridShape shape_;
    Rheology rheology_;
    std::size_t row_ = 0;     // cells from one row to the next (nx padded, row_stride())
    std::size_t plane_ = 0;   // cells from one plane to the next
    std::size_t n_ = 0;       // cells stored (padding included)
    std::size_t slot_ = 0;    // stride between the populations' slots (≥ n_, see the constructor)
    HugePageVector<Real> f_;  // f_i − w_i, population i of cell k at f_[i slot_ + k]
    std::vector<Real> tau_;
    std::vector<CellType> type_;
    // bit 0: some neighbour is an obstacle or outside the domain; bit 1 (solid_bit): a moving solid covers
    // the cell. Either takes the cell out of the vectorised runs.
    std::vector<std::uint8_t> near_wall_;
    static constexpr std::uint8_t solid_bit = 2;
    std::vector<SolidCell> solid_cells_;  // set_solid_cells
    SolidExchange exchange_ = SolidExchange::drag;
    std::vector<Vec3> solid_force_;  // F_h per solid cell
    // Rows with wet solid cells go through the vectorised runs with each cell's weight (1 or 0), v_p and F_h
    // laid out along the row: per thread, solid_row_stride() values of each of the 7, zero but where a row
    // is being swept
    std::vector<Real> solid_rows_;
    [[nodiscard]] std::size_t solid_row_stride() const { return row_ + 64 / sizeof(Real); }
    std::vector<std::uint32_t> solid_links_;  // bit i: the neighbour along c_i is solid
    std::vector<std::uint16_t> element_;
    // per cell: 0, or 1 + the outlet it belongs to (empty: the lattice has none)
    std::vector<std::uint8_t> outlet_;
    std::array<double, max_outlets> drained_{};
    std::vector<std::uint8_t> region_;  // set_region(): per cell its RegionBits (empty: no region)
    std::vector<Crossing> crossings_;   // the links into it
    std::array<double, 3> region_inflow_{};
    [[nodiscard]] bool in_region(std::size_t k) const {
        return !region_.empty() && (region_[k] & region_downstream) != 0;
    }
    // (lbm/region_inflow.cpp: out of the free surface's loops, whose inlining they would disturb)
    void count_crossings();  // after the sweep's streaming, before the mass exchange updates λ
    // the excess of this slab's orphans (those spread over the whole surface) that the region's cells shed
    [[nodiscard]] double region_orphan_excess(std::span<const OrphanMass> orphans) const;
    // after convert_cells()' shares and spread (`share` per interface cell): what they brought the region
    void count_region_conversions(double share, double region_orphans);
    // The pockets' search: one thread's cells to visit with their steps from the pocket, and the interface
    // cells it found (ConversionScratch::pocket_search).
    struct PocketStep {
        std::uint32_t cell;
        std::array<int, 3> at;  // its coordinates
        int steps;              // from the pocket
    };
    struct PocketSearch {
        std::vector<PocketStep> queue;
        std::vector<std::uint32_t> found;
    };
    // Appends to search.found the interface cells within pocket_reach_ steps of cell k through wet cells
    // (any thread: the search's marks are its own).
    void find_pocket_receivers(std::uint32_t k, PocketSearch& search) const;
    // The deficit (m − ρ < 0) of enclosed cell k that filled, taken in equal shares from `receivers`.
    void spread_pocket(std::uint32_t k, double deficit, std::span<const std::uint32_t> receivers);
    SurfaceSeconds surface_seconds_;  // surface_pass_seconds()
    [[nodiscard]] std::size_t outlet_of(std::size_t k) const { return outlet_.empty() ? 0 : outlet_[k]; }
    std::vector<Vec3> element_velocity_;
    std::vector<Vec3> element_force_;
    bool keep_barrier_links_ = false;
    int pocket_reach_ = 0;        // set_pocket_reach()
    BarrierLinks barrier_links_;  // (keep_barrier_links(); built by relink())
    void list_barrier_links();
    // the step's momentum of the kept link of cell k along i (none kept there: nothing)
    void keep_link(std::size_t k, int i, double momentum) {
        const std::size_t j = barrier_links_.find(static_cast<std::uint32_t>(k), i);
        if (j < barrier_links_.size()) barrier_links_.momentum[j] = momentum;
    }
    // The sweep's work items: a z-plane, or a block of its rows where the plane holds much of the free
    // surface (sweep_tiles()); each with its own partial sums of the element forces (fixed summation order)
    struct SweepTile {
        int z = 0, y_begin = 0, y_end = 0;
    };
    static constexpr int sweep_tile_rows = 8;
    [[nodiscard]] std::size_t most_tiles() const {
        return static_cast<std::size_t>(shape_.nz) *
               static_cast<std::size_t>((shape_.ny + sweep_tile_rows - 1) / sweep_tile_rows);
    }
    std::vector<SweepTile> tiles_;
    std::vector<Vec3> tile_force_;
    void sweep_tiles();
    Vec3 accel_{};
    ClampCounts clamps_;
    std::uint64_t updated_cells_ = 0;
    // free surface
    std::vector<Real> fill_;                // λ per cell
    std::vector<double> mass_;              // m per cell (interface cells; fluid: ρ implied)
    std::vector<std::uint32_t> interface_;  // the interface cells, ascending
    // per interface cell (same order), filled by exchange_mass() and the sweep
    std::vector<double> out_;              // Q outgoing populations of the last step
    std::vector<std::uint8_t> out_known_;  // 1: out_ recorded by the sweep (else read by prepare_surface)
    std::vector<Vec3> normal_;             // −∇λ (central differences)
    std::vector<double> surface_rho_;      // density of the last collision
    std::vector<Vec3> surface_u_;          // velocity of the last collision (used by the reconstruction)
    std::vector<std::int8_t> convert_;  // +1 filled (+2: for having no gas neighbour), −1 emptied, 0 stays
    std::vector<std::ptrdiff_t> surface_nb_;  // Q neighbours as the sweep found them (detail::Batch::nb)
    struct NeighbourKinds {
        std::uint32_t gas = 0, fluid = 0;  // bit i: the neighbour along c_i is a gas / a fluid cell
    };
    std::vector<NeighbourKinds> surface_kinds_;  // as the sweep found them
    std::vector<Real> new_fill_;                 // exchange_mass's scratch: λ after the exchange
    // convert_cells()'s lists of one step, kept so that their capacity is reused (the new interface
    // list and its per-cell state are built in the next_* ones and swapped with the lattice's)
    struct ConversionScratch {
        std::vector<std::uint32_t> filled, emptied, born;
        std::vector<std::uint8_t> enclosed;  // per filled cell: 1 if it filled for having no gas neighbour
        std::vector<Vec3> filled_normal, emptied_normal;
        std::vector<double> born_rho;
        std::vector<Vec3> born_u;
        std::vector<std::uint32_t> demoted;
        std::vector<double> demoted_rho;
        std::vector<Vec3> demoted_u;
        std::vector<double> filled_excess, emptied_excess, filled_rho;
        // per filled cell and direction: what its neighbour is to it (convert_cells()); per converted cell
        // and direction: the neighbour that takes a share of its excess mass and the share's mass
        std::vector<std::uint64_t> marks;
        std::vector<std::int64_t> share_to;
        std::vector<double> share_mass;
        std::vector<std::uint32_t> next;
        std::vector<double> next_rho, next_out;
        std::vector<Vec3> next_u;
        std::vector<std::uint8_t> next_known;
        // per cell of `next`: where its state comes from (its index in the old list, or in born or demoted
        // with a flag: convert_cells())
        std::vector<std::uint32_t> next_from;
        // the pockets' searches, one per thread, and per filled cell where its receivers lie: its thread's
        // search, the first in that search's list and how many
        std::vector<PocketSearch> pocket_search;
        std::vector<std::uint32_t> pocket_thread, pocket_first, pocket_receivers;
    } scratch_;
    std::vector<OrphanMass> orphans_;  // convert_cells()'s excess mass with no interface neighbour
    std::vector<Vec3> next_normal_;    // replace_surface()'s new normals
    SlabRole slab_;
    SurfaceStats surface_stats_;
    std::uint64_t steps_ = 0;
};

extern template class FluidLattice<float>;
extern template class FluidLattice<double>;

}  // namespace sabo::lbm
