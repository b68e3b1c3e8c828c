// SPDX-License-Identifier: MIT
#include "lbm/opencl/opencl_lattice.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <type_traits>

#include "core/error.h"
#include "lbm/opencl/cl.h"
#include "lbm/opencl/device_view.h"
#include "sabo/opencl_kernels.h"

namespace sabo::lbm::opencl {

namespace {

constexpr const char* key = "lattice.device = \"opencl\"";
// the kernels' integer counts of a step: τ at its minimum and maximum, updated cells, filled, emptied and
// orphan-excess cells
constexpr std::size_t counter_count = 7;
// summarize_cells' sums (mass, λρ, λρ in the region, largest speed) and counts (interface cells, the
// highest x and z of a cell with λ ≥ 0.1) per work-group
constexpr std::size_t summary_sums = 4, summary_counts = 3;
// cells of a row per work-item of the surface kernels (free_surface.cl, XCELLS)
constexpr int surface_cells_per_item = 8;

// Links of cells that may be wet (any but obstacles) to solids: the wall links whose momenta the device
// writes
template <class Real>
std::uint64_t count_wall_links(const FluidLattice<Real>& l) {
    const auto types = l.cell_types();
    const auto bits = l.solid_link_bits();
    std::uint64_t links = 0;
    for (std::size_t k = 0; k < types.size(); ++k)
        if (types[k] != CellType::obstacle) links += static_cast<std::uint64_t>(std::popcount(bits[k]));
    return links;
}

// Value c of an array of momentum sums as the device holds them: double where it has float64, else float.
double read_sum(const std::vector<std::byte>& v, std::size_t c, bool as_double) {
    if (as_double) {
        double value = 0.0;
        std::memcpy(&value, v.data() + c * sizeof(double), sizeof(double));
        return value;
    }
    float value = 0.0F;
    std::memcpy(&value, v.data() + c * sizeof(float), sizeof(float));
    return static_cast<double>(value);
}

void write_sum(std::vector<std::byte>& v, std::size_t c, double value, bool as_double) {
    if (as_double) {
        std::memcpy(v.data() + c * sizeof(double), &value, sizeof(double));
        return;
    }
    const auto narrow = static_cast<float>(value);
    std::memcpy(v.data() + c * sizeof(float), &narrow, sizeof(float));
}

}  // namespace

template <class Real>
struct OpenClLattice<Real>::Impl {
    // the momentum sums: double where the device has it
    bool acc_double = true;
    bool surface = false;  // the lattice has a free surface: the surface kernels and buffers
    bool divided = false;  // a slab of a divided run (own planes [host.own_begin(), host.own_end()))
    cl::Context context;
    cl::CommandQueue queue;
    cl::Device device;
    std::string options;  // the kernels' build options
    cl::Program program;
    cl::Kernel even, odd, reduce, reduce_elements, snapshot, summarize, pack, unpack, gather_links;
    // the host lattice's barrier links (FluidLattice::barrier_links): each one's index in link_momentum, and
    // their momenta gathered (gather_link_momenta)
    cl::Buffer barrier_link, barrier_momenta;
    std::size_t barrier_links = 0;
    // a slab's planes packed for its neighbours (slab_planes.cl): reals, sums and bytes of each cell
    cl::Buffer plane_reals, plane_wide, plane_bytes;
    int plane_capacity = 0;             // planes the staging buffers hold
    std::vector<std::byte> share_sums;  // a slab's orphan mass and interface cells, as the device holds them
    // snapshot(): the own cells' fields in image order (snapshot_fields)
    cl::Buffer snap_type, snap_fill, snap_tau, snap_rho, snap_u, snap_mass, snap_covered;
    // summary(): the region (one byte per stored cell) and the groups' sums (summarize_cells)
    cl::Buffer region, summary_sums, summary_counts;
    std::size_t summary_groups = 1;
    cl::Buffer f, tau, type, links, element, wall_u, link_start, link_momentum, counters, element_links,
        link_direction, chunk_begin, chunk_sums, element_chunk, forces;
    // free surface, per stored cell (free_surface.cl)
    cl::Kernel exchange, neighbours, demote, mark, convert_cells, fill_cells, shares, gather, sum, spread,
        finish, prepare;
    cl::Buffer fill, new_fill, mass, srho, su, normal, out, convert, change, out_known, excess, share_total,
        share_count, orphan, region_excess, pocket_near, group_total, group_count, share, outlet, drained;
    // the links into the region (count_crossings, sum_crossings): each one's cells, direction and tally,
    // the mass it carried in the step; and the region's inflow since the start (FluidLattice::region_inflow)
    cl::Kernel cross, sum_cross;
    // the inflow boundary's held cells (hold_inlet_cells): storage index, density, top flag, mass added
    cl::Kernel inlet;
    cl::Buffer inlet_cell, inlet_rho, inlet_top, inlet_added;
    std::size_t inlet_capacity = 0;
    // their host copies (reused: no allocation in the time loop once grown)
    std::vector<std::uint32_t> inlet_index;
    std::vector<std::byte> inlet_density, inlet_gained;
    std::vector<std::uint8_t> inlet_flags;
    cl::Buffer cross_from, cross_to, cross_direction, cross_part, cross_mass, region_inflow;
    std::size_t crossing_count = 0;
    std::size_t elements = 0, wall_links = 0, chunks = 0, reduce_group = 1, orphan_groups = 64;
    bool relaxes_per_cell = false;  // Bingham or Smagorinsky: τ is per cell and is copied back
    // cells covered by moving solids (SOLID: 0 none, 1 drag, 2 partially saturated): per stored cell the
    // share ε, the solid's velocity and the force on it; the last set_solid_cells() list and its forces
    int solid_mode = 0;
    cl::Kernel clear_solids, scatter_solids, gather_solids;
    cl::Buffer solid_fraction, solid_v, solid_force, solid_list, solid_list_fraction, solid_list_v,
        solid_list_force;
    std::size_t solid_count = 0, solid_capacity = 0;
    cl::NDRange cells, tile;  // the cell kernels' grid (padded rows × ny × nz) and work-group
    cl::NDRange surface_cells, surface_tile;  // the surface kernels' (surface_cells_per_item cells each)
    bool profiling = false;
    std::vector<std::pair<const cl::Kernel*, cl::Event>> events;
    // snapshot()'s staging arrays (as the device holds them)
    std::vector<Real> stage_fill, stage_tau, stage_u;
    std::vector<std::byte> stage_rho, stage_mass;  // with profiling: the launches so far

    // Enqueues `kernel` on `global` items in groups of `local`, with an event when profiling.
    void launch(cl::Kernel& kernel, const cl::NDRange& global, const cl::NDRange& local,
                const cl::NDRange& offset = cl::NullRange) {
        if (!profiling) {
            queue.enqueueNDRangeKernel(kernel, offset, global, local);
            return;
        }
        events.emplace_back(&kernel, cl::Event());
        queue.enqueueNDRangeKernel(kernel, offset, global, local, nullptr, &events.back().second);
    }
    void launch_cells(cl::Kernel& kernel) { launch(kernel, cells, tile); }
    void launch_surface(cl::Kernel& kernel) { launch(kernel, surface_cells, surface_tile); }

    std::size_t acc_size() const { return acc_double ? sizeof(double) : sizeof(float); }
};

namespace {

// kernel.setArg(0, a0), (1, a1), …
template <class... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
    cl_uint i = 0;
    (kernel.setArg(i++, args), ...);
}

// The work-items of a kernel over a list of `count` entries (each item one entry; the rest idle)
cl::NDRange list_items(std::size_t count) {
    return cl::NDRange((count + 63) / 64 * 64);
}

}  // namespace

template <class Real>
std::uint64_t OpenClLattice<Real>::device_bytes(const FluidLattice<Real>& host, bool solids) {
    const std::uint64_t links = count_wall_links(host);
    const std::uint64_t elements = host.element_velocities().size();
    return lattice_bytes(FluidLattice<Real>::stored_cells(host.shape()), sizeof(Real) == 4,
                         host.interface_count() > 0) +
           links * (8 + 4 + 1) + elements * (3 * sizeof(Real) + 4 + 3 * 8) +
           (links / 16 + elements + 1) * (3 * 8 + 4) + 64 +  // (+ the links' chunks, at most one per 16)
           (solids
                ? FluidLattice<Real>::stored_cells(host.shape()) * (solid_cell_bytes(sizeof(Real) == 4) + 1)
                : 0);
}

template <class Real>
void OpenClLattice<Real>::check_fits(const FluidLattice<Real>& host, const DeviceInfo& device, bool solids) {
    const std::uint64_t populations = static_cast<std::uint64_t>(Q) * host.slot_stride() * sizeof(Real);
    if (const std::string why = misfit(device_bytes(host, solids), populations, device); !why.empty())
        throw InputError(fmt::format("{}: {}: coarsen lattice.dx_m or store float32", key, why));
}

template <class Real>
OpenClLattice<Real>::OpenClLattice(FluidLattice<Real>& host, const DeviceInfo& device, bool profile,
                                   std::optional<SolidExchange> solids)
    : host_(host), device_(device), impl_(std::make_unique<Impl>()) {
    constexpr bool is_double = std::is_same_v<Real, double>;
    if (is_double && !device.fp64)
        throw InputError(
            fmt::format("{}: float64 storage needs cl_khr_fp64, which {} lacks: store float32 "
                        "(lattice.storage = \"float32\") or choose another lattice.opencl_device",
                        key, device.name));
    check_fits(host, device, solids.has_value());
    Impl& d = *impl_;
    d.acc_double = device.fp64;
    const Rheology& rh = host.rheology();
    d.relaxes_per_cell = rh.bingham || rh.smagorinsky > 0.0;
    d.surface = host.steps_surface();
    d.divided = host.own_begin() != 0 || host.own_end() != host.shape().nx;
    d.solid_mode = !solids ? 0 : (*solids == SolidExchange::drag ? 1 : 2);
    const GridShape& s = host.shape();
    // whether the pocket search's box spans a periodic axis shorter than its side (free_surface.cl)
    const auto pocket_spans = [&](int cells, std::size_t axis) {
        return s.periodic[axis] && cells < 2 * host.pocket_reach() + 1 ? 1 : 0;
    };
    try {
        std::vector<cl::Platform> platforms;
        cl::Platform::get(&platforms);
        std::vector<cl::Device> devices;
        platforms.at(static_cast<std::size_t>(device.platform_index))
            .getDevices(CL_DEVICE_TYPE_ALL, &devices);
        const cl::Device dev = devices.at(static_cast<std::size_t>(device.device_index));
        d.context = cl::Context(dev);
        d.profiling = profile;
        d.queue = cl::CommandQueue(d.context, dev, profile ? CL_QUEUE_PROFILING_ENABLE : 0);
        d.program = cl::Program(d.context, std::string(opencl_kernels::stream_collide) +
                                               opencl_kernels::free_surface + opencl_kernels::slab_planes);
        d.device = dev;
        d.options = fmt::format(
            "-cl-std=CL1.2 -D REAL={} {} -D ACC={} {} -D BINGHAM={} -D LES={} -D NX={} -D NY={} -D NZ={} "
            "-D ROW={} -D PLANE={} -D SLOT={} -D PX={} -D PY={} -D PZ={} -D TAU={:.17g} -D OMEGA={:.17g} "
            "-D TAU_MIN={:.17g} -D TAU_MAX={:.17g} -D NU_PLASTIC={:.17g} -D YIELD={:.17g} -D "
            "SMAGORINSKY={:.17g} "
            "-D FREE_SURFACE={} -D CELLS={} -D SURFACE_EPSILON={:.17g} -D MAX_OUTLETS={} -D XCELLS={} "
            "-D SOLID={} -D DIVIDED={} -D OWN_BEGIN={} -D OWN_END={} -D POCKET_REACH={} -D POCKET_FULL_X={} "
            "-D POCKET_FULL_Y={} -D POCKET_FULL_Z={}",
            is_double ? "double" : "float", is_double ? "-D REAL_IS_DOUBLE" : "",
            d.acc_double ? "double" : "float", d.acc_double ? "-D ACC_IS_DOUBLE" : "", rh.bingham ? 1 : 0,
            rh.smagorinsky > 0.0 ? 1 : 0, s.nx, s.ny, s.nz, FluidLattice<Real>::row_stride(s.nx),
            FluidLattice<Real>::row_stride(s.nx) * s.ny, host.slot_stride(), s.periodic[0] ? 1 : 0,
            s.periodic[1] ? 1 : 0, s.periodic[2] ? 1 : 0, rh.tau, 1.0 / rh.tau, rh.tau_min, rh.tau_max,
            rh.nu_plastic, rh.yield, rh.smagorinsky, d.surface ? 1 : 0, FluidLattice<Real>::stored_cells(s),
            FluidLattice<Real>::surface_epsilon, max_outlets, surface_cells_per_item, d.solid_mode,
            d.divided ? 1 : 0, host.own_begin(), host.own_end(), host.pocket_reach(), pocket_spans(s.nx, 0),
            pocket_spans(s.ny, 1), pocket_spans(s.nz, 2));
        try {
            d.program.build({dev}, d.options.c_str());
        } catch (const cl::Error&) {
            throw InputError(fmt::format("{}: the lattice's kernels did not build on {}:\n{}", key,
                                         device.name,
                                         d.program.template getBuildInfo<CL_PROGRAM_BUILD_LOG>(dev)));
        }
        d.even = cl::Kernel(d.program, "stream_collide_even");
        d.odd = cl::Kernel(d.program, "stream_collide_odd");
        d.reduce = cl::Kernel(d.program, "reduce_link_chunks");
        d.reduce_elements = cl::Kernel(d.program, "sum_element_chunks");
        d.gather_links = cl::Kernel(d.program, "gather_link_momenta");
        d.snapshot = cl::Kernel(d.program, "snapshot_fields");
        d.summarize = cl::Kernel(d.program, "summarize_cells");
        d.pack = cl::Kernel(d.program, "pack_planes");
        d.unpack = cl::Kernel(d.program, "unpack_planes");
        if (d.surface) {
            d.exchange = cl::Kernel(d.program, "surface_exchange");
            d.neighbours = cl::Kernel(d.program, "surface_neighbours");
            d.demote = cl::Kernel(d.program, "surface_demote");
            d.mark = cl::Kernel(d.program, "surface_mark");
            d.convert_cells = cl::Kernel(d.program, "surface_convert");
            d.fill_cells = cl::Kernel(d.program, "surface_fill");
            d.shares = cl::Kernel(d.program, "surface_shares");
            d.gather = cl::Kernel(d.program, "surface_gather");
            d.sum = cl::Kernel(d.program, "sum_orphans");
            d.spread = cl::Kernel(d.program, "spread_orphans");
            d.finish = cl::Kernel(d.program, "surface_finish");
            d.prepare = cl::Kernel(d.program, "surface_prepare");
            d.cross = cl::Kernel(d.program, "count_crossings");
            d.sum_cross = cl::Kernel(d.program, "sum_crossings");
            d.inlet = cl::Kernel(d.program, "hold_inlet_cells");
        }
        if (d.solid_mode != 0) {
            d.clear_solids = cl::Kernel(d.program, "clear_solid_cells");
            d.scatter_solids = cl::Kernel(d.program, "scatter_solid_cells");
            d.gather_solids = cl::Kernel(d.program, "gather_solid_forces");
        }
        std::size_t group = 1;
        while (group * 2 <= std::min<std::size_t>(device.max_work_group, 128)) group *= 2;
        d.reduce_group = group;
        // The cell kernels' work-groups: a tile of lx × ly cells of a plane, lx a power of two dividing the
        // padded row (reads along x coalesce), at most `group` items together. A driver left to choose
        // picks a divisor of the grid's extents, which for a row of 208 cells can be a poor one.
        const std::size_t row = FluidLattice<Real>::row_stride(s.nx), ny = static_cast<std::size_t>(s.ny);
        std::size_t lx = 1, ly = 1;
        while (lx * 2 <= group && row % (lx * 2) == 0) lx *= 2;
        while (lx * ly * 2 <= group && ny % (ly * 2) == 0) ly *= 2;
        d.cells = cl::NDRange(row, ny, static_cast<std::size_t>(s.nz));
        d.tile = cl::NDRange(lx, ly, 1);
        // the surface kernels: ceil(nx / XCELLS) work-items along a row, padded to whole groups of up to 32
        const std::size_t items =
            (static_cast<std::size_t>(s.nx) + surface_cells_per_item - 1) / surface_cells_per_item;
        std::size_t sx = 1, sy = 1;
        while (sx * 2 <= std::min<std::size_t>(group, 32) && sx * 2 <= items) sx *= 2;
        while (sx * sy * 2 <= group && ny % (sy * 2) == 0) sy *= 2;
        d.surface_cells = cl::NDRange((items + sx - 1) / sx * sx, ny, static_cast<std::size_t>(s.nz));
        d.surface_tile = cl::NDRange(sx, sy, 1);
        // the orphans' sums: ~32 cells per work-item, so that the pass runs at the memory's speed (a
        // fixed count per lattice size: the same grid, and so the same sums, on every device)
        d.orphan_groups =
            std::clamp<std::size_t>(FluidLattice<Real>::stored_cells(s) / (32 * d.reduce_group), 1, 4096);
    } catch (const cl::Error& e) {
        throw InputError(
            fmt::format("{}: OpenCL failed on {} ({}, error {})", key, device.name, e.what(), e.err()));
    }
    push();
}

template <class Real>
OpenClLattice<Real>::~OpenClLattice() = default;

template <class Real>
void OpenClLattice<Real>::push() {
    FluidLattice<Real>& h = host_;
    Impl& d = *impl_;
    if (!d.surface && h.steps_surface())
        throw InputError(
            fmt::format("{}: the lattice gained a free surface after it moved to the device", key));
    if (!h.solid_cells().empty() && d.solid_mode == 0)
        throw InputError(
            fmt::format("{}: grain cells (the coupling) are not carried by the OpenCL backend yet", key));
    const GridShape& s = h.shape();
    const auto types = h.cell_types();
    const auto bits = h.solid_link_bits();
    const auto elements = h.obstacle_elements();
    const std::size_t n = types.size();
    // the wall links of the cells that may be wet, in storage order, each cell's in ascending direction (a
    // slab's ghost cells' links go to no element: the neighbour who owns them counts their force)
    d.elements = h.element_velocities().size();
    if (d.elements > 0xffff) throw InputError(fmt::format("{}: more than 65535 obstacle elements", key));
    const auto ghost_links = static_cast<std::uint16_t>(d.elements);
    std::vector<std::uint32_t> link_start(n, 0);
    std::vector<std::uint16_t> link_element;
    std::vector<std::uint8_t> link_dir;
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const std::size_t k = h.index(x, y, z);
                if (types[k] == CellType::obstacle) continue;
                link_start[k] = static_cast<std::uint32_t>(link_dir.size());
                for (std::uint32_t b = bits[k]; b != 0; b &= b - 1) {
                    const int i = std::countr_zero(b);
                    const std::ptrdiff_t nb = h.neighbour(x, y, z, i, 1);
                    const auto un = static_cast<std::size_t>(nb);
                    link_element.push_back(!h.own_x(static_cast<std::size_t>(x))        ? ghost_links
                                           : nb >= 0 && types[un] == CellType::obstacle ? elements[un]
                                                                                        : 0);
                    link_dir.push_back(static_cast<std::uint8_t>(i));
                }
            }
    // the barrier's links as the host lists them, by their place among the wall links
    const BarrierLinks& kept = h.barrier_links();
    std::vector<std::uint32_t> barrier_link(kept.size());
    for (std::size_t j = 0; j < kept.size(); ++j) {
        const std::uint32_t below = (1U << kept.direction[j]) - 1U;  // the cell's links listed before
        barrier_link[j] =
            link_start[kept.cell[j]] + static_cast<std::uint32_t>(std::popcount(bits[kept.cell[j]] & below));
    }
    d.barrier_links = kept.size();
    if (link_dir.size() >= (std::size_t{1} << 32))
        throw InputError(
            fmt::format("{}: {} wall links exceed the backend's 32-bit link index", key, link_dir.size()));
    // the links of each element in ascending link order (a counting sort): the reduction's fixed order
    d.wall_links = link_dir.size();
    std::vector<std::uint32_t> begin(d.elements + 2, 0), order(d.wall_links);
    std::vector<std::uint8_t> order_dir(d.wall_links);
    for (const std::uint16_t e : link_element) ++begin[e + 1];
    for (std::size_t e = 0; e <= d.elements; ++e) begin[e + 1] += begin[e];
    {
        std::vector<std::uint32_t> next(begin.begin(), begin.end() - 1);
        for (std::size_t j = 0; j < d.wall_links; ++j) {
            const std::uint32_t at = next[link_element[j]]++;
            order[at] = static_cast<std::uint32_t>(j);
            order_dir[at] = link_dir[j];
        }
    }
    // each element's links cut into chunks of at most chunk_links, one work-group each (the cut depends on
    // the geometry alone: the same sums on every device)
    const std::size_t chunk_links = 16 * d.reduce_group;
    std::vector<std::uint32_t> chunk_begin{0}, element_chunk{0};
    for (std::size_t e = 0; e < d.elements; ++e) {
        for (std::uint32_t j = begin[e]; j < begin[e + 1];) {
            j = static_cast<std::uint32_t>(std::min<std::size_t>(j + chunk_links, begin[e + 1]));
            chunk_begin.push_back(j);
        }
        element_chunk.push_back(static_cast<std::uint32_t>(chunk_begin.size() - 1));
    }
    d.chunks = chunk_begin.size() - 1;
    std::vector<Real> wall_u;
    for (const Vec3& u : h.element_velocities())
        for (int a = 0; a < 3; ++a) wall_u.push_back(static_cast<Real>(u[a]));
    const auto populations = h.populations();
    const auto taus = h.relaxation_times();
    const std::size_t acc_size = d.acc_size();
    const auto bytes = [](const auto& v) { return std::max<std::size_t>(v.size() * sizeof(v[0]), 1); };
    try {
        // every buffer starts as the host's data or zeros (the padding cells' entries are never written)
        const auto make = [&](cl::Buffer& b, std::size_t size, const void* data) {
            const std::size_t at_least = std::max<std::size_t>((size + 7) / 8 * 8, 8);
            b = cl::Buffer(d.context, CL_MEM_READ_WRITE, at_least);
            d.queue.enqueueFillBuffer(b, std::uint64_t{0}, 0, at_least);
            if (data != nullptr && size > 0) d.queue.enqueueWriteBuffer(b, CL_FALSE, 0, size, data);
        };
        make(d.f, populations.size_bytes(), populations.data());
        make(d.tau, taus.size_bytes(), taus.data());
        make(d.type, n, types.data());
        make(d.links, bits.size_bytes(), bits.data());
        make(d.element, elements.size_bytes(), elements.data());
        make(d.wall_u, bytes(wall_u), wall_u.data());
        make(d.link_start, bytes(link_start), link_start.data());
        make(d.link_momentum, d.wall_links * acc_size, nullptr);
        make(d.counters, counter_count * sizeof(std::uint32_t), nullptr);
        make(d.element_links, bytes(order), order.data());
        make(d.link_direction, bytes(order_dir), order_dir.data());
        make(d.chunk_begin, bytes(chunk_begin), chunk_begin.data());
        make(d.chunk_sums, std::max<std::size_t>(3 * d.chunks * acc_size, 1), nullptr);
        make(d.element_chunk, bytes(element_chunk), element_chunk.data());
        make(d.forces, 3 * d.elements * acc_size, nullptr);
        make(d.barrier_link, bytes(barrier_link), barrier_link.data());
        make(d.barrier_momenta, d.barrier_links * acc_size, nullptr);
        // the free surface: λ, m and the interface cells' last-collision state (FluidLattice::pack_surface)
        std::vector<Real> su, normal, out;
        std::vector<std::uint8_t> known;
        std::vector<std::byte> mass, srho, drained, inflow;  // (alive until the writes are done)
        if (d.surface) {
            su.assign(3 * n, Real(0));
            normal.assign(3 * n, Real(0));
            out.assign(Q * n, Real(0));
            known.assign(n, 0);
            mass.resize(n * acc_size);
            srho.resize(n * acc_size);
            const auto put = [&](std::vector<std::byte>& v, std::size_t k, double value) {
                write_sum(v, k, value, d.acc_double);
            };
            const auto masses = h.masses();
            for (std::size_t k = 0; k < n; ++k) put(mass, k, masses[k]);
            std::vector<double> records;
            h.pack_surface(0, s.nx, records);
            std::size_t r = 0;
            for (std::size_t k = 0; k < n; ++k) {
                if (types[k] != CellType::interface) continue;
                const double* rec = records.data() + r++ * FluidLattice<Real>::surface_record;
                put(srho, k, rec[0]);
                for (int a = 0; a < 3; ++a) {
                    su[3 * k + static_cast<std::size_t>(a)] = static_cast<Real>(rec[1 + a]);
                    normal[3 * k + static_cast<std::size_t>(a)] = static_cast<Real>(rec[4 + a]);
                }
                for (int i = 0; i < Q; ++i)
                    out[static_cast<std::size_t>(i) * n + k] =
                        static_cast<Real>(rec[7 + i] - weight[static_cast<std::size_t>(i)]);
                known[k] = 1;
            }
            const auto fills = h.fill_fractions();
            make(d.fill, fills.size_bytes(), fills.data());
            make(d.new_fill, fills.size_bytes(), nullptr);
            make(d.mass, mass.size(), mass.data());
            make(d.srho, srho.size(), srho.data());
            make(d.su, bytes(su), su.data());
            make(d.normal, bytes(normal), normal.data());
            make(d.out, bytes(out), out.data());
            make(d.out_known, bytes(known), known.data());
            make(d.convert, n, nullptr);
            make(d.change, n, nullptr);
            make(d.excess, n * acc_size, nullptr);
            make(d.share_total, n * acc_size, nullptr);
            make(d.share_count, n, nullptr);
            make(d.orphan, n * acc_size, nullptr);
            make(d.region_excess, n * acc_size, nullptr);
            make(d.pocket_near, n, nullptr);
            make(d.group_total, d.orphan_groups * (3 + max_outlets) * acc_size, nullptr);
            make(d.group_count, 2 * d.orphan_groups * sizeof(std::uint32_t), nullptr);
            make(d.share, 4 * acc_size, nullptr);
            // the outlets' cells (0: none; 1 + the outlet) and the mass drained through each so far
            const auto outlets = h.outlet_cells();
            make(d.outlet, n, outlets.empty() ? nullptr : outlets.data());
            drained.resize(max_outlets * acc_size);
            for (std::size_t o = 0; o < max_outlets; ++o) put(drained, o, h.drained()[o]);
            make(d.drained, drained.size(), drained.data());
            // the region's inflow so far (the region and its links: set_region(), after every push)
            inflow.resize(3 * acc_size);
            for (std::size_t part = 0; part < 3; ++part) put(inflow, part, h.region_inflow()[part]);
            make(d.region_inflow, inflow.size(), inflow.data());
            d.crossing_count = 0;
        }
        d.queue.finish();  // the host vectors above go out of scope
        if (d.solid_mode != 0) {
            make(d.solid_fraction, n * sizeof(Real), nullptr);
            make(d.solid_v, 3 * n * sizeof(Real), nullptr);
            make(d.solid_force, 3 * n * acc_size, nullptr);
            d.solid_count = d.solid_capacity = 0;
        }
        for (cl::Kernel* k : {&d.even, &d.odd}) {
            set_args(*k, d.f, d.tau, d.type, d.links, d.element, d.wall_u, d.link_start, d.link_momentum,
                     d.counters);
            cl_uint a = 12;
            if (d.surface)
                for (const cl::Buffer* b : {&d.su, &d.normal, &d.out, &d.srho, &d.out_known})
                    k->setArg(a++, *b);
            if (d.solid_mode != 0) {
                for (const cl::Buffer* b : {&d.solid_fraction, &d.solid_v, &d.solid_force})
                    k->setArg(a++, *b);
                if (d.surface) k->setArg(a++, d.fill);
            }
        }
        const std::size_t image =
            static_cast<std::size_t>(s.nx) * static_cast<std::size_t>(s.ny) * static_cast<std::size_t>(s.nz);
        make(d.snap_type, image, nullptr);
        make(d.snap_fill, image * sizeof(Real), nullptr);
        make(d.snap_tau, image * sizeof(Real), nullptr);
        make(d.snap_rho, image * acc_size, nullptr);
        make(d.snap_u, 3 * image * sizeof(Real), nullptr);
        make(d.snap_mass, image * acc_size, nullptr);
        set_args(d.snapshot, 0, 0, s.nx, d.f, d.tau, d.type, d.links, d.element, d.wall_u, Real(0), Real(0),
                 Real(0), d.snap_type, d.snap_fill, d.snap_tau, d.snap_rho, d.snap_u, d.snap_mass);
        cl_uint at = 18;
        if (d.surface)
            for (const cl::Buffer* b : {&d.fill, &d.mass, &d.srho, &d.su}) d.snapshot.setArg(at++, *b);
        if (d.solid_mode != 0) {
            make(d.snap_covered, image, nullptr);
            d.snapshot.setArg(at++, d.solid_fraction);
            d.snapshot.setArg(at++, d.snap_covered);
        }
        d.summary_groups = d.orphan_groups;
        make(d.region, n, nullptr);
        make(d.summary_sums, d.summary_groups * summary_sums * acc_size, nullptr);
        make(d.summary_counts, d.summary_groups * summary_counts * sizeof(std::int32_t), nullptr);
        set_args(d.summarize, 0, d.f, d.type, d.links, d.element, d.wall_u, Real(0), Real(0), Real(0),
                 d.region, d.summary_sums, d.summary_counts,
                 cl::Local(summary_sums * d.reduce_group * acc_size),
                 cl::Local(summary_counts * d.reduce_group * sizeof(std::int32_t)));
        at = 14;
        if (d.surface)
            for (const cl::Buffer* b : {&d.fill, &d.mass, &d.srho, &d.su}) d.summarize.setArg(at++, *b);
        if (d.solid_mode != 0) d.summarize.setArg(at++, d.solid_fraction);
        set_args(d.reduce, d.link_momentum, d.element_links, d.link_direction, d.chunk_begin, d.chunk_sums,
                 cl::Local(3 * d.reduce_group * acc_size));
        set_args(d.reduce_elements, d.element_chunk, d.chunk_sums, d.forces,
                 cl::Local(3 * d.reduce_group * acc_size));
        if (d.surface) {
            // argument 0 of the kernels that read populations is the parity, set each step
            set_args(d.exchange, 0, d.f, d.type, d.fill, d.new_fill, d.mass, d.srho, d.out, d.convert,
                     d.outlet, d.change);
            set_args(d.neighbours, d.type, d.fill, d.new_fill, d.convert, d.change);
            set_args(d.demote, d.type, d.fill, d.convert, d.change, d.normal);
            set_args(d.mark, 0, d.f, d.type, d.links, d.element, d.wall_u, d.change, d.srho, d.su);
            set_args(d.convert_cells, 0, d.f, d.tau, d.type, d.element, d.wall_u, d.fill, d.mass, d.convert,
                     d.change, d.srho, d.su, d.out_known, d.excess, d.counters);
            set_args(d.fill_cells, 0, d.f, d.type, d.element, d.wall_u, d.fill, d.mass, d.convert, d.change,
                     d.excess, d.counters);
            set_args(d.shares, d.type, d.change, d.normal, d.excess, d.share_total, d.share_count, d.orphan,
                     d.counters, d.outlet, d.region, d.region_excess, d.pocket_near);
            set_args(d.gather, d.type, d.change, d.normal, d.excess, d.share_total, d.share_count, d.mass,
                     d.region, d.pocket_near);
            // (free_surface.cl's SUMS values and two counts per work-item)
            const std::size_t sums = (3 + max_outlets) * d.reduce_group * acc_size;
            const cl::LocalSpaceArg counts = cl::Local(2 * d.reduce_group * sizeof(std::uint32_t));
            set_args(d.sum, d.orphan, d.type, d.outlet, d.change, d.region, d.region_excess, d.group_total,
                     d.group_count, cl::Local(sums), counts);
            set_args(d.spread, static_cast<int>(d.orphan_groups), d.group_total, d.group_count, d.share,
                     d.drained, d.region_inflow, cl::Local(sums), counts);
            set_args(d.finish, d.type, d.mass, d.fill, d.srho, d.share);
            set_args(d.prepare, 0, d.f, d.type, d.element, d.wall_u, d.fill, d.out_known, d.out, d.normal);
        }
    } catch (const cl::Error& e) {
        throw InputError(
            fmt::format("{}: OpenCL failed on {} ({}, error {})", key, device_.name, e.what(), e.err()));
    }
    steps_ = h.steps();
    forces_ = h.element_forces();
    forces_read_ = true;
    clamps_ = h.clamps();
    updated_ = h.updated_cells();
    surface_stats_ = h.surface_stats();
    drained_ = h.drained();
    region_inflow_ = h.region_inflow();
    region_spread_ = 0.0;
    counters_read_ = true;
    if (!h.solid_cells().empty()) set_solid_cells(h.solid_cells());
}

template <class Real>
void OpenClLattice<Real>::set_solid_cells(std::span<const SolidCell> cells) {
    Impl& d = *impl_;
    if (d.solid_mode == 0)
        throw std::logic_error("OpenClLattice::set_solid_cells: the lattice was built without solids");
    const std::size_t n = cells.size(), stored = host_.cell_types().size();
    std::vector<std::uint32_t> index(n);
    std::vector<Real> fraction(n), velocity(3 * n);
    for (std::size_t g = 0; g < n; ++g) {
        if (cells[g].cell >= stored || (g > 0 && cells[g - 1].cell >= cells[g].cell))
            throw std::invalid_argument("set_solid_cells: cells must be lattice cells, ascending, each once");
        index[g] = static_cast<std::uint32_t>(cells[g].cell);
        fraction[g] = static_cast<Real>(cells[g].fraction);
        for (std::size_t a = 0; a < 3; ++a)
            velocity[3 * g + a] = static_cast<Real>(cells[g].velocity[static_cast<int>(a)]);
    }
    try {
        if (d.solid_count > 0) {  // the last list's cells, uncovered
            set_args(d.clear_solids, static_cast<cl_uint>(d.solid_count), d.solid_list, d.solid_fraction);
            d.queue.enqueueNDRangeKernel(d.clear_solids, cl::NullRange, list_items(d.solid_count),
                                         cl::NullRange);
        }
        if (n > d.solid_capacity) {
            d.solid_capacity = std::max<std::size_t>(n, 2 * d.solid_capacity);
            d.solid_list = cl::Buffer(d.context, CL_MEM_READ_WRITE, d.solid_capacity * sizeof(std::uint32_t));
            d.solid_list_fraction = cl::Buffer(d.context, CL_MEM_READ_WRITE, d.solid_capacity * sizeof(Real));
            d.solid_list_v = cl::Buffer(d.context, CL_MEM_READ_WRITE, 3 * d.solid_capacity * sizeof(Real));
            d.solid_list_force =
                cl::Buffer(d.context, CL_MEM_READ_WRITE, 3 * d.solid_capacity * d.acc_size());
        }
        d.solid_count = n;
        if (n > 0) {
            d.queue.enqueueWriteBuffer(d.solid_list, CL_FALSE, 0, n * sizeof(std::uint32_t), index.data());
            d.queue.enqueueWriteBuffer(d.solid_list_fraction, CL_FALSE, 0, n * sizeof(Real), fraction.data());
            d.queue.enqueueWriteBuffer(d.solid_list_v, CL_FALSE, 0, 3 * n * sizeof(Real), velocity.data());
            set_args(d.scatter_solids, static_cast<cl_uint>(n), d.solid_list, d.solid_list_fraction,
                     d.solid_list_v, d.solid_fraction, d.solid_v);
            d.queue.enqueueNDRangeKernel(d.scatter_solids, cl::NullRange, list_items(n), cl::NullRange);
        }
        d.queue.finish();  // (the host vectors go out of scope)
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: setting the solids' cells on {} failed ({}, error {})", key,
                                   device_.name, e.what(), e.err()));
    }
}

template <class Real>
std::vector<Vec3> OpenClLattice<Real>::solid_cell_forces() {
    Impl& d = *impl_;
    const std::size_t n = d.solid_count;
    std::vector<Vec3> out(n);
    if (n == 0) return out;
    std::vector<std::byte> sums(3 * n * d.acc_size());
    try {
        set_args(d.gather_solids, static_cast<cl_uint>(n), d.solid_list, d.solid_force, d.solid_list_force);
        d.queue.enqueueNDRangeKernel(d.gather_solids, cl::NullRange, list_items(n), cl::NullRange);
        d.queue.enqueueReadBuffer(d.solid_list_force, CL_TRUE, 0, sums.size(), sums.data());
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: reading the solids' forces from {} failed ({}, error {})", key,
                                   device_.name, e.what(), e.err()));
    }
    for (std::size_t g = 0; g < n; ++g)
        out[g] = {read_sum(sums, 3 * g, d.acc_double), read_sum(sums, 3 * g + 1, d.acc_double),
                  read_sum(sums, 3 * g + 2, d.acc_double)};
    return out;
}

template <class Real>
void OpenClLattice<Real>::step(std::uint64_t count, const std::function<void()>& after_collision) {
    Impl& d = *impl_;
    const Vec3 a = host_.acceleration();
    const auto ax = static_cast<Real>(a.x), ay = static_cast<Real>(a.y), az = static_cast<Real>(a.z);
    try {
        for (std::uint64_t c = 0; c < count; ++c) {
            cl::Kernel& k = steps_ % 2 == 1 ? d.odd : d.even;
            k.setArg(9, ax);
            k.setArg(10, ay);
            k.setArg(11, az);
            d.queue.enqueueFillBuffer(d.counters, std::uint32_t{0}, 0, counter_count * sizeof(std::uint32_t));
            d.launch_cells(k);
            ++steps_;
            if (after_collision && c + 1 == count) {
                after_collision();
                d.queue.flush();  // (the device starts on them while the rest is enqueued)
            }
            if (d.crossing_count >
                0) {  // the populations just streamed, λ and the types before the surface's
                d.cross.setArg(0, static_cast<int>(steps_ % 2));
                d.launch(d.cross, list_items(d.crossing_count), cl::NullRange);
                d.launch(d.sum_cross, cl::NDRange(d.reduce_group), cl::NDRange(d.reduce_group));
            }
            if (d.surface) {
                // the parity of the steps done, which says where the populations now are
                const int odd = static_cast<int>(steps_ % 2);
                for (cl::Kernel* sk : {&d.exchange, &d.mark, &d.convert_cells, &d.fill_cells, &d.prepare})
                    sk->setArg(0, odd);
                d.mark.setArg(9, ax);
                d.mark.setArg(10, ay);
                d.mark.setArg(11, az);
                for (cl::Kernel* sk : {&d.exchange, &d.neighbours, &d.demote, &d.mark, &d.convert_cells,
                                       &d.fill_cells, &d.shares, &d.gather})
                    d.launch_surface(*sk);
                d.launch(d.sum, cl::NDRange(d.orphan_groups * d.reduce_group), cl::NDRange(d.reduce_group));
                d.launch(d.spread, cl::NDRange(d.reduce_group), cl::NDRange(d.reduce_group));
                if (d.divided) share_orphans();
                d.launch_surface(d.finish);
                d.launch_surface(d.prepare);
            }
            if (d.wall_links > 0) {
                d.launch(d.reduce, cl::NDRange(d.chunks * d.reduce_group), cl::NDRange(d.reduce_group));
                d.launch(d.reduce_elements, cl::NDRange(d.elements * d.reduce_group),
                         cl::NDRange(d.reduce_group));
            }
        }
        d.queue.flush();
    } catch (const cl::Error& e) {
        throw RunError(
            fmt::format("{}: a step failed on {} ({}, error {})", key, device_.name, e.what(), e.err()));
    }
    forces_read_ = false;
    barrier_read_ = false;
    counters_read_ = false;
}

template <class Real>
void OpenClLattice<Real>::share_orphans() {
    // (a sync point each step, as on the CPU: every slab waits for the others' sums)
    Impl& d = *impl_;
    d.share_sums.resize(4 * d.acc_size());
    d.queue.enqueueReadBuffer(d.share, CL_TRUE, 0, d.share_sums.size(), d.share_sums.data());
    double mass = read_sum(d.share_sums, 0, d.acc_double), cells = read_sum(d.share_sums, 1, d.acc_double);
    if (sum_orphans_) sum_orphans_(mass, cells);
    const bool spread = mass != 0.0 && cells > 0.0;
    const double share = spread ? mass / cells : 0.0;
    write_sum(d.share_sums, 0, share, d.acc_double);
    if (spread)  // what the spread brings the region's own interface cells, less its own orphans
        region_spread_ +=
            share * read_sum(d.share_sums, 3, d.acc_double) - read_sum(d.share_sums, 2, d.acc_double);
    d.queue.enqueueWriteBuffer(d.share, CL_TRUE, 0, d.acc_size(), d.share_sums.data());
}

template <class Real>
typename OpenClLattice<Real>::PlaneParts OpenClLattice<Real>::plane_parts(int planes) const {
    const Impl& d = *impl_;
    const GridShape& s = host_.shape();
    const auto cells =
        static_cast<std::size_t>(planes) * static_cast<std::size_t>(s.ny) * static_cast<std::size_t>(s.nz);
    // slab_planes.cl: Q populations and τ; with a surface λ, u, normal, Q outgoing, m, ρ, type, known
    const std::size_t reals = d.surface ? 2 * Q + 8 : Q + 1, wide = d.surface ? 2 : 0, bytes = wide;
    return {cells * reals * sizeof(Real), cells * wide * d.acc_size(), cells * bytes};
}

template <class Real>
std::size_t OpenClLattice<Real>::packed_bytes(int planes) const {
    const PlaneParts p = plane_parts(planes);
    return p.reals + p.wide + p.bytes;
}

template <class Real>
void OpenClLattice<Real>::pack_planes(int x0, int planes, std::span<std::byte> message) {
    move_planes(x0, planes, message.data(), nullptr, message.size());
}

template <class Real>
void OpenClLattice<Real>::unpack_planes(int x0, int planes, std::span<const std::byte> message) {
    move_planes(x0, planes, nullptr, message.data(), message.size());
}

template <class Real>
void OpenClLattice<Real>::move_planes(int x0, int planes, std::byte* into, const std::byte* from,
                                      std::size_t size) {
    Impl& d = *impl_;
    const bool out = into != nullptr;
    const GridShape& s = host_.shape();
    if (x0 < 0 || planes < 1 || x0 + planes > s.nx || size != packed_bytes(planes))
        throw std::logic_error(
            "OpenClLattice::pack_planes: planes outside the lattice or a message of another size");
    const auto [reals, wide, bytes] = plane_parts(planes);
    try {
        if (planes > d.plane_capacity) {  // (once: a halo asks for as many planes every time)
            d.plane_capacity = planes;
            d.plane_reals = cl::Buffer(d.context, CL_MEM_READ_WRITE, reals);
            d.plane_wide = cl::Buffer(d.context, CL_MEM_READ_WRITE, std::max<std::size_t>(wide, 8));
            d.plane_bytes = cl::Buffer(d.context, CL_MEM_READ_WRITE, std::max<std::size_t>(bytes, 8));
        }
        cl::Kernel& k = out ? d.pack : d.unpack;
        set_args(k, x0, planes, d.f, d.tau, d.plane_reals);
        if (d.surface) {
            cl_uint a = 5;
            for (const cl::Buffer* b : {&d.type, &d.fill, &d.mass, &d.srho, &d.su, &d.normal, &d.out,
                                        &d.out_known, &d.plane_wide, &d.plane_bytes})
                k.setArg(a++, *b);
        }
        const cl::NDRange items(static_cast<std::size_t>(planes), static_cast<std::size_t>(s.ny),
                                static_cast<std::size_t>(s.nz));
        if (out) {
            d.launch(k, items, cl::NullRange);
            d.queue.enqueueReadBuffer(d.plane_reals, CL_FALSE, 0, reals, into);
            if (d.surface) {
                d.queue.enqueueReadBuffer(d.plane_wide, CL_FALSE, 0, wide, into + reals);
                d.queue.enqueueReadBuffer(d.plane_bytes, CL_FALSE, 0, bytes, into + reals + wide);
            }
        } else {
            d.queue.enqueueWriteBuffer(d.plane_reals, CL_FALSE, 0, reals, from);
            if (d.surface) {
                d.queue.enqueueWriteBuffer(d.plane_wide, CL_FALSE, 0, wide, from + reals);
                d.queue.enqueueWriteBuffer(d.plane_bytes, CL_FALSE, 0, bytes, from + reals + wide);
            }
            d.launch(k, items, cl::NullRange);
        }
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: moving a slab's planes {} the device {} failed ({}, error {})", key,
                                   out ? "from" : "to", device_.name, e.what(), e.err()));
    }
}

template <class Real>
std::span<Vec3> OpenClLattice<Real>::element_forces_to_sum() {
    (void)element_forces();
    return forces_;
}

template <class Real>
void OpenClLattice<Real>::wait() {
    impl_->queue.finish();
}

template <class Real>
DeviceView OpenClLattice<Real>::view() const {
    const Impl& d = *impl_;
    return {d.context, d.queue,           d.device,         d.options, d.type,       d.tau,
            d.fill,    d.solid_mode != 0, d.solid_fraction, d.solid_v, d.solid_force};
}

template <class Real>
std::vector<std::pair<std::string, double>> OpenClLattice<Real>::kernel_seconds() {
    Impl& d = *impl_;
    d.queue.finish();
    std::vector<std::pair<std::string, double>> out;
    for (auto& [kernel, event] : d.events) {
        const auto name = kernel->template getInfo<CL_KERNEL_FUNCTION_NAME>();
        const double s =
            1e-9 * static_cast<double>(event.template getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                                       event.template getProfilingInfo<CL_PROFILING_COMMAND_START>());
        auto at = std::find_if(out.begin(), out.end(), [&](const auto& e) { return e.first == name; });
        if (at == out.end())
            out.emplace_back(name, s);
        else
            at->second += s;
    }
    d.events.clear();
    return out;
}

template <class Real>
const std::vector<Vec3>& OpenClLattice<Real>::element_forces() {
    if (forces_read_) return forces_;
    Impl& d = *impl_;
    forces_.assign(d.elements, Vec3{});
    if (d.wall_links > 0) {
        std::vector<std::byte> sums(3 * d.elements * d.acc_size());
        d.queue.enqueueReadBuffer(d.forces, CL_TRUE, 0, sums.size(), sums.data());
        for (std::size_t e = 0; e < d.elements; ++e)
            forces_[e] = {read_sum(sums, 3 * e, d.acc_double), read_sum(sums, 3 * e + 1, d.acc_double),
                          read_sum(sums, 3 * e + 2, d.acc_double)};
    }
    forces_read_ = true;
    return forces_;
}

template <class Real>
std::span<const double> OpenClLattice<Real>::barrier_link_momenta() {
    Impl& d = *impl_;
    if (barrier_read_ || d.barrier_links == 0) return barrier_momenta_;
    barrier_momenta_.resize(d.barrier_links);
    set_args(d.gather_links, d.link_momentum, d.barrier_link, d.barrier_momenta,
             static_cast<cl_uint>(d.barrier_links));
    const std::size_t group = 64;
    d.launch(d.gather_links, cl::NDRange((d.barrier_links + group - 1) / group * group), cl::NDRange(group));
    std::vector<std::byte> momenta(d.barrier_links * d.acc_size());
    d.queue.enqueueReadBuffer(d.barrier_momenta, CL_TRUE, 0, momenta.size(), momenta.data());
    for (std::size_t j = 0; j < d.barrier_links; ++j)
        barrier_momenta_[j] = read_sum(momenta, j, d.acc_double);
    barrier_read_ = true;
    return barrier_momenta_;
}

template <class Real>
void OpenClLattice<Real>::read_counters() {
    if (counters_read_) return;
    std::uint32_t c[counter_count] = {};
    impl_->queue.enqueueReadBuffer(impl_->counters, CL_TRUE, 0, sizeof(c), c);
    clamps_ = {c[0], c[1]};
    updated_ = c[2];
    surface_stats_ = {c[3], c[4], c[5], c[6]};
    counters_read_ = true;
}

template <class Real>
ClampCounts OpenClLattice<Real>::clamps() {
    read_counters();
    return clamps_;
}

template <class Real>
std::array<double, max_outlets> OpenClLattice<Real>::drained() {
    Impl& d = *impl_;
    if (!d.surface) return drained_;
    std::vector<std::byte> bytes(max_outlets * d.acc_size());
    d.queue.enqueueReadBuffer(d.drained, CL_TRUE, 0, bytes.size(), bytes.data());
    for (std::size_t o = 0; o < max_outlets; ++o) drained_[o] = read_sum(bytes, o, d.acc_double);
    return drained_;
}

template <class Real>
void OpenClLattice<Real>::set_crossings(std::span<const Crossing> links) {
    Impl& d = *impl_;
    d.crossing_count = 0;
    if (links.empty()) return;
    if (!d.surface) throw std::logic_error("OpenClLattice::set_crossings: a lattice without a free surface");
    const std::size_t n = links.size();
    std::vector<std::uint32_t> from(n), to(n);
    std::vector<std::uint8_t> direction(n), part(n);
    for (std::size_t g = 0; g < n; ++g) {
        if (links[g].to > std::numeric_limits<std::uint32_t>::max() ||
            links[g].from > std::numeric_limits<std::uint32_t>::max())
            throw std::logic_error("OpenClLattice::set_crossings: a cell index beyond 32 bits");
        from[g] = static_cast<std::uint32_t>(links[g].from);
        to[g] = static_cast<std::uint32_t>(links[g].to);
        direction[g] = links[g].direction;
        part[g] = links[g].part;
    }
    try {
        const auto make = [&](cl::Buffer& b, std::size_t size, const void* data) {
            b = cl::Buffer(d.context, CL_MEM_READ_WRITE, size);
            if (data != nullptr) d.queue.enqueueWriteBuffer(b, CL_TRUE, 0, size, data);
        };
        make(d.cross_from, n * sizeof(std::uint32_t), from.data());
        make(d.cross_to, n * sizeof(std::uint32_t), to.data());
        make(d.cross_direction, n, direction.data());
        make(d.cross_part, n, part.data());
        make(d.cross_mass, n * d.acc_size(), nullptr);
        set_args(d.cross, 0, d.f, d.type, d.element, d.wall_u, d.fill, d.cross_from, d.cross_to,
                 d.cross_direction, static_cast<cl_uint>(n), d.cross_mass);
        set_args(d.sum_cross, static_cast<cl_uint>(n), d.cross_mass, d.cross_part, d.region_inflow,
                 cl::Local(2 * d.reduce_group * d.acc_size()));
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: the crossings could not be placed on {} ({}, error {})", key,
                                   device_.name, e.what(), e.err()));
    }
    d.crossing_count = n;
}

template <class Real>
double OpenClLattice<Real>::hold_inlet(std::span<const InletCell> cells, const Vec3& u) {
    Impl& d = *impl_;
    if (!d.surface) throw std::logic_error("OpenClLattice::hold_inlet: a lattice without a free surface");
    const std::size_t n = cells.size();
    if (n == 0) return 0.0;
    std::vector<std::uint32_t>& index = d.inlet_index;
    std::vector<std::byte>&rho = d.inlet_density, &added = d.inlet_gained;
    std::vector<std::uint8_t>& top = d.inlet_flags;
    index.resize(n);
    rho.resize(n * d.acc_size());
    added.resize(n * d.acc_size());
    top.resize(n);
    int planes = 0;
    for (std::size_t g = 0; g < n; ++g) {
        const InletCell& c = cells[g];
        index[g] = static_cast<std::uint32_t>(host_.index(c.x, c.y, c.z));
        write_sum(rho, g, c.rho, d.acc_double);
        top[g] = c.top ? 1 : 0;
        planes = std::max(planes, c.x + 1);
    }
    try {
        if (n > d.inlet_capacity) {  // (grown once to the deepest inflow's cells)
            d.inlet_cell = cl::Buffer(d.context, CL_MEM_READ_ONLY, n * sizeof(std::uint32_t));
            d.inlet_rho = cl::Buffer(d.context, CL_MEM_READ_ONLY, n * d.acc_size());
            d.inlet_top = cl::Buffer(d.context, CL_MEM_READ_ONLY, n);
            d.inlet_added = cl::Buffer(d.context, CL_MEM_READ_WRITE, n * d.acc_size());
            d.inlet_capacity = n;
        }
        d.queue.enqueueWriteBuffer(d.inlet_cell, CL_FALSE, 0, n * sizeof(std::uint32_t), index.data());
        d.queue.enqueueWriteBuffer(d.inlet_rho, CL_FALSE, 0, rho.size(), rho.data());
        d.queue.enqueueWriteBuffer(d.inlet_top, CL_FALSE, 0, n, top.data());
        set_args(d.inlet, static_cast<int>(steps_ % 2), d.f, d.type, d.element, d.wall_u, d.fill, d.mass,
                 d.srho, d.inlet_cell, d.inlet_rho, d.inlet_top, static_cast<cl_uint>(n),
                 static_cast<Real>(u.x), static_cast<Real>(u.y), static_cast<Real>(u.z), d.inlet_added);
        d.launch(d.inlet, list_items(n), cl::NullRange);
        // the normals (and new interface cells' outgoing populations) of the planes the cells touch, read
        // again from the edited fill: FluidLattice::surface_edited()
        d.prepare.setArg(0, static_cast<int>(steps_ % 2));
        const auto items =
            static_cast<std::size_t>((planes + surface_cells_per_item) / surface_cells_per_item);
        d.launch(d.prepare, cl::NDRange(items, d.surface_cells[1], d.surface_cells[2]), cl::NullRange);
        d.queue.enqueueReadBuffer(d.inlet_added, CL_TRUE, 0, added.size(), added.data());
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: holding the inflow's cells on {} failed ({}, error {})", key,
                                   device_.name, e.what(), e.err()));
    }
    double sum = 0.0;  // (in the cells' order, as the host lattice adds them)
    for (std::size_t g = 0; g < n; ++g) sum += read_sum(added, g, d.acc_double);
    return sum;
}

template <class Real>
std::array<double, 3> OpenClLattice<Real>::region_inflow() {
    Impl& d = *impl_;
    if (!d.surface) return region_inflow_;
    std::vector<std::byte> bytes(3 * d.acc_size());
    d.queue.enqueueReadBuffer(d.region_inflow, CL_TRUE, 0, bytes.size(), bytes.data());
    for (std::size_t part = 0; part < 3; ++part) region_inflow_[part] = read_sum(bytes, part, d.acc_double);
    region_inflow_[2] += region_spread_;
    return region_inflow_;
}

template <class Real>
std::uint64_t OpenClLattice<Real>::updated_cells() {
    read_counters();
    return updated_;
}

template <class Real>
void OpenClLattice<Real>::snapshot(FluidFields& out, int x_begin, int x_end) {
    Impl& d = *impl_;
    const GridShape& s = host_.shape();
    if (x_end < 0) x_end = s.nx;
    x_begin = std::clamp(x_begin, 0, s.nx);
    x_end = std::clamp(x_end, x_begin, s.nx);
    const std::size_t n = static_cast<std::size_t>(x_end - x_begin) * static_cast<std::size_t>(s.ny) *
                          static_cast<std::size_t>(s.nz);
    out.shape(x_end - x_begin, s.ny, s.nz, x_begin);
    // (the staging arrays keep their size from one snapshot to the next)
    d.stage_fill.resize(n);
    d.stage_tau.resize(n);
    d.stage_u.resize(3 * n);
    d.stage_rho.resize(n * d.acc_size());
    d.stage_mass.resize(n * d.acc_size());
    const Vec3 a = host_.acceleration();
    try {
        set_args(d.snapshot, static_cast<int>(steps_ % 2), x_begin, x_end);
        d.snapshot.setArg(9, static_cast<Real>(a.x));
        d.snapshot.setArg(10, static_cast<Real>(a.y));
        d.snapshot.setArg(11, static_cast<Real>(a.z));
        if (n > 0) {
            const std::size_t lx = d.tile[0], first = static_cast<std::size_t>(x_begin) / lx * lx;
            const std::size_t width = (static_cast<std::size_t>(x_end) - first + lx - 1) / lx * lx;
            d.launch(d.snapshot, cl::NDRange(width, d.cells[1], d.cells[2]), d.tile,
                     cl::NDRange(first, 0, 0));
            d.queue.enqueueReadBuffer(d.snap_type, CL_FALSE, 0, n, out.type.data());
            d.queue.enqueueReadBuffer(d.snap_fill, CL_FALSE, 0, n * sizeof(Real), d.stage_fill.data());
            d.queue.enqueueReadBuffer(d.snap_tau, CL_FALSE, 0, n * sizeof(Real), d.stage_tau.data());
            d.queue.enqueueReadBuffer(d.snap_rho, CL_FALSE, 0, d.stage_rho.size(), d.stage_rho.data());
            d.queue.enqueueReadBuffer(d.snap_u, CL_FALSE, 0, 3 * n * sizeof(Real), d.stage_u.data());
            d.queue.enqueueReadBuffer(d.snap_mass, CL_FALSE, 0, d.stage_mass.size(), d.stage_mass.data());
            if (d.solid_mode != 0)
                d.queue.enqueueReadBuffer(d.snap_covered, CL_FALSE, 0, n, out.covered.data());
            else
                std::fill(out.covered.begin(), out.covered.end(), std::uint8_t{0});
        }
        d.queue.finish();
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: reading the fields from {} failed ({}, error {})", key, device_.name,
                                   e.what(), e.err()));
    }
    const auto wide = [&](const std::vector<std::byte>& v, std::size_t c) {
        return read_sum(v, c, d.acc_double);
    };
    // the totals in the host lattice's order (z, y, x): the same sums as its own snapshot's
    FluidTotals t;
    std::size_t interface_cells = 0;
    for (std::size_t c = 0; c < n; ++c) {
        out.fill[c] = static_cast<double>(d.stage_fill[c]);
        out.tau[c] = static_cast<double>(d.stage_tau[c]);
        out.density[c] = wide(d.stage_rho, c);
        out.velocity[c] = {static_cast<double>(d.stage_u[3 * c]), static_cast<double>(d.stage_u[3 * c + 1]),
                           static_cast<double>(d.stage_u[3 * c + 2])};
        if (out.type[c] != CellType::fluid && out.type[c] != CellType::interface) continue;
        interface_cells += out.type[c] == CellType::interface ? 1 : 0;
        t.mass += wide(d.stage_mass, c);
        t.max_speed = std::max(t.max_speed, norm(out.velocity[c]));
    }
    out.totals = t;
    out.interface_cells = interface_cells;
    out.clamps = clamps();
    out.drained = drained();
    out.region_inflow = region_inflow();
}

template <class Real>
void OpenClLattice<Real>::set_region(std::span<const std::uint8_t> image) {
    Impl& d = *impl_;
    const GridShape& s = host_.shape();
    std::vector<std::uint8_t> stored(FluidLattice<Real>::stored_cells(s), 0);
    if (!image.empty())
        for (int z = 0, c = 0; z < s.nz; ++z)
            for (int y = 0; y < s.ny; ++y)
                for (int x = 0; x < s.nx; ++x, ++c)
                    stored[host_.index(x, y, z)] = image[static_cast<std::size_t>(c)];
    d.queue.enqueueWriteBuffer(d.region, CL_TRUE, 0, stored.size(), stored.data());
    set_crossings(host_.crossings());
}

template <class Real>
FluidSummary OpenClLattice<Real>::summary() {
    Impl& d = *impl_;
    const std::size_t groups = d.summary_groups;
    std::vector<std::byte> sums(groups * summary_sums * d.acc_size());
    std::vector<std::int32_t> counts(groups * summary_counts);
    const Vec3 a = host_.acceleration();
    try {
        d.summarize.setArg(0, static_cast<int>(steps_ % 2));
        d.summarize.setArg(6, static_cast<Real>(a.x));
        d.summarize.setArg(7, static_cast<Real>(a.y));
        d.summarize.setArg(8, static_cast<Real>(a.z));
        d.launch(d.summarize, cl::NDRange(groups * d.reduce_group), cl::NDRange(d.reduce_group));
        d.queue.enqueueReadBuffer(d.summary_sums, CL_FALSE, 0, sums.size(), sums.data());
        d.queue.enqueueReadBuffer(d.summary_counts, CL_TRUE, 0, counts.size() * sizeof(std::int32_t),
                                  counts.data());
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: summing the fields on {} failed ({}, error {})", key, device_.name,
                                   e.what(), e.err()));
    }
    FluidSummary out;
    out.nz = host_.shape().nz;
    for (std::size_t g = 0; g < groups; ++g) {
        const auto sum = [&](std::size_t c) { return read_sum(sums, g * summary_sums + c, d.acc_double); };
        out.totals.mass += sum(0);
        out.free_mass += sum(1);
        out.region_mass += sum(2);
        out.totals.max_speed = std::max(out.totals.max_speed, sum(3));
        out.interface_cells += static_cast<std::size_t>(counts[g * summary_counts]);
        out.front_x = std::max(out.front_x, counts[g * summary_counts + 1]);
        out.top_z = std::max(out.top_z, counts[g * summary_counts + 2]);
    }
    out.clamps = clamps();
    out.drained = drained();
    out.region_inflow = region_inflow();
    return out;
}

template <class Real>
void OpenClLattice<Real>::pull() {
    Impl& d = *impl_;
    FluidLattice<Real>& h = host_;
    const auto populations = h.populations();
    const std::size_t n = h.cell_types().size();
    const std::size_t acc_size = d.acc_size();
    std::vector<Real> su, normal, out;
    std::vector<std::uint8_t> known;
    std::vector<std::byte> mass, srho;
    try {
        d.queue.enqueueReadBuffer(d.f, CL_FALSE, 0, populations.size_bytes(), populations.data());
        if (d.relaxes_per_cell || d.surface) {
            const auto taus = h.relaxation_times();
            d.queue.enqueueReadBuffer(d.tau, CL_FALSE, 0, taus.size_bytes(), taus.data());
        }
        if (d.surface) {
            const auto types = h.cell_types();
            const auto fills = h.fill_fractions();
            su.resize(3 * n);
            normal.resize(3 * n);
            out.resize(Q * n);
            known.resize(n);
            mass.resize(n * acc_size);
            srho.resize(n * acc_size);
            d.queue.enqueueReadBuffer(d.type, CL_FALSE, 0, n, types.data());
            d.queue.enqueueReadBuffer(d.fill, CL_FALSE, 0, fills.size_bytes(), fills.data());
            d.queue.enqueueReadBuffer(d.mass, CL_FALSE, 0, mass.size(), mass.data());
            d.queue.enqueueReadBuffer(d.srho, CL_FALSE, 0, srho.size(), srho.data());
            d.queue.enqueueReadBuffer(d.su, CL_FALSE, 0, su.size() * sizeof(Real), su.data());
            d.queue.enqueueReadBuffer(d.normal, CL_FALSE, 0, normal.size() * sizeof(Real), normal.data());
            d.queue.enqueueReadBuffer(d.out, CL_FALSE, 0, out.size() * sizeof(Real), out.data());
            d.queue.enqueueReadBuffer(d.out_known, CL_FALSE, 0, n, known.data());
        }
        d.queue.finish();
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("{}: reading the state back from {} failed ({}, error {})", key,
                                   device_.name, e.what(), e.err()));
    }
    if (d.surface) {
        const auto get = [&](const std::vector<std::byte>& v, std::size_t k) {
            return read_sum(v, k, d.acc_double);
        };
        const auto types = h.cell_types();
        const auto masses = h.masses();
        std::vector<double> records;
        for (std::size_t k = 0; k < n; ++k) {
            masses[k] = get(mass, k);
            if (types[k] != CellType::interface) continue;
            records.insert(records.end(),
                           {get(srho, k), double(su[3 * k]), double(su[3 * k + 1]), double(su[3 * k + 2]),
                            double(normal[3 * k]), double(normal[3 * k + 1]), double(normal[3 * k + 2])});
            for (int i = 0; i < Q; ++i)
                records.push_back(static_cast<double>(out[static_cast<std::size_t>(i) * n + k]) +
                                  weight[static_cast<std::size_t>(i)]);
            records.push_back(known[k]);
        }
        h.replace_surface(0, h.shape().nx, records);
    }
    // the counters first: surface_stats_ below is read_counters()' too
    read_counters();
    const std::vector<Vec3> forces = element_forces();
    h.record_steps(steps_, forces, clamps_, updated_, surface_stats_, drained(), region_inflow());
}

template class OpenClLattice<float>;
template class OpenClLattice<double>;

}  // namespace sabo::lbm::opencl
