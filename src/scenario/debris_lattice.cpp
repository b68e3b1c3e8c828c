// SPDX-License-Identifier: MIT
#include "scenario/debris_lattice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "geometry/mesh_queries.h"

namespace sabo::scenario {

namespace {

Vec3 cell_centre(int x, int y, int z, double dx) {
    return {(x + 0.5) * dx, (y + 0.5) * dx, (z + 0.5) * dx};
}

}  // namespace

template <class Real>
void fill_fluid_block(lbm::FluidLattice<Real>& l, const DebrisCase& s, double dx, int first_global_x) {
    const auto& sh = l.shape();
    for (int z = 0; z < sh.nz; ++z)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = 0; x < sh.nx; ++x) {
                const Vec3 c = cell_centre(first_global_x + x, y, z, dx);
                if (c.x < s.block_hi.x && c.y > s.block_lo.y && c.y < s.block_hi.y && c.z < s.block_hi.z)
                    l.set_fluid(x, y, z, 1.0, {});
            }
}

template <class Real>
std::vector<std::size_t> mark_barrier(lbm::FluidLattice<Real>& l, const DebrisCase& s, double dx,
                                      int first_global_x) {
    const auto& sh = l.shape();
    const std::size_t ne = s.barrier.elements.size();
    std::vector<std::size_t> count(ne, 0);
    std::vector<std::uint16_t> ids(ne);
    for (std::size_t e = 0; e < ne; ++e) ids[e] = l.add_element();
    // per stored cell (l.index)
    std::vector<float> best(lbm::FluidLattice<Real>::stored_cells(sh),
                            std::numeric_limits<float>::infinity());
    std::vector<std::int32_t> owner(best.size(), -1);
    // a cell two elements claim goes to the one whose centre is nearer
    const auto claim = [&](std::size_t e, int x, int y, int z) {
        const std::size_t k = l.index(x, y, z);
        const auto d = static_cast<float>(
            norm2(cell_centre(first_global_x + x, y, z, dx) - s.barrier.elements[e].centre));
        if (d < best[k]) {
            best[k] = d;
            owner[k] = static_cast<std::int32_t>(e);
        }
    };
    for (std::size_t e = 0; e < ne; ++e) {
        const auto& el = s.barrier.elements[e];
        if (el.mesh_part) {  // the part's cells, row by row (the slab's planes: its first global plane's x)
            const geometry::CellGrid grid{{first_global_x * dx, 0.0, 0.0}, dx, sh.nx, sh.ny, sh.nz};
            geometry::for_cells_inside(*s.barrier.mesh, el.part, grid,
                                       [&](int x, int y, int z) { claim(e, x, y, z); });
            continue;
        }
        Vec3 lo, hi;
        if (el.sphere) {
            const double r = s.particles.r[s.barrier.sphere_position(el, s.particles.size())];
            lo = el.centre - Vec3{r, r, r};
            hi = el.centre + Vec3{r, r, r};
        } else {
            const auto& w = s.walls[el.index];
            Vec3 ext{};
            for (int a = 0; a < 3; ++a) {
                const double h = a == 0 ? w.half.x : (a == 1 ? w.half.y : w.half.z);
                ext += Vec3{std::abs(w.axes[a].x), std::abs(w.axes[a].y), std::abs(w.axes[a].z)} * h;
            }
            lo = w.point - ext;
            hi = w.point + ext;
        }
        // (x: local planes, shifted by the slab's first global plane)
        const auto first = [&](double v, int n, int shift = 0) {
            return std::clamp(static_cast<int>(std::floor(v / dx - 0.5)) - shift, 0, n - 1);
        };
        const auto last = [&](double v, int n, int shift = 0) {
            return std::clamp(static_cast<int>(std::ceil(v / dx - 0.5)) - shift, 0, n - 1);
        };
        for (int z = first(lo.z, sh.nz); z <= last(hi.z, sh.nz); ++z)
            for (int y = first(lo.y, sh.ny); y <= last(hi.y, sh.ny); ++y)
                for (int x = first(lo.x, sh.nx, first_global_x); x <= last(hi.x, sh.nx, first_global_x);
                     ++x) {
                    if (inside_element(s, e, cell_centre(first_global_x + x, y, z, dx))) claim(e, x, y, z);
                }
    }
    for (int z = 0; z < sh.nz; ++z)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = 0; x < sh.nx; ++x) {
                const std::int32_t e = owner[l.index(x, y, z)];
                if (e < 0) continue;
                l.set_obstacle(x, y, z, ids[static_cast<std::size_t>(e)]);
                if (x >= l.own_begin() && x < l.own_end()) ++count[static_cast<std::size_t>(e)];
            }
    return count;
}

template <class Real>
void mark_outlets(lbm::FluidLattice<Real>& l, const DebrisCase& s, double dx, int global_nx,
                  int first_global_x) {
    const bool open_top = s.bounds.top == ChannelTop::open;
    if (!open_top && s.bounds.end != ChannelEnd::open) return;
    const auto& sh = l.shape();
    for (int z = 0; z < sh.nz; ++z)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = 0; x < sh.nx; ++x) {
                if (l.type(l.index(x, y, z)) == lbm::CellType::obstacle) continue;
                const Vec3 c = cell_centre(first_global_x + x, y, z, dx);
                std::optional<DebrisOutlet> outlet;
                if (first_global_x + x == global_nx - 1 || c.x >= s.outflow_x) outlet = DebrisOutlet::end;
                if (open_top && (y == 0 || y == sh.ny - 1) && c.z > s.channel.height)
                    outlet = DebrisOutlet::sides;
                if (open_top && z == sh.nz - 1) outlet = DebrisOutlet::top;
                if (outlet) l.set_outlet(x, y, z, static_cast<std::size_t>(*outlet));
            }
}

template <class Real>
void mark_channel_mesh(lbm::FluidLattice<Real>& l, const DebrisCase& s, double dx, int first_global_x) {
    if (!s.channel_mesh) return;
    const auto& sh = l.shape();
    const geometry::CellGrid grid{{first_global_x * dx, 0.0, 0.0}, dx, sh.nx, sh.ny, sh.nz};
    // every plane of the lattice, a slab's ghost planes too (they mirror the neighbour's)
    for (std::size_t p = 0; p < s.channel_mesh->parts(); ++p)
        geometry::for_cells_inside(*s.channel_mesh, p, grid,
                                   [&](int x, int y, int z) { l.set_obstacle(x, y, z, 0); });
}

template void mark_channel_mesh(lbm::FluidLattice<float>&, const DebrisCase&, double, int);
template void mark_channel_mesh(lbm::FluidLattice<double>&, const DebrisCase&, double, int);

int bed_cells(const DebrisCase& s, double dx, int x, int y, int nz) {
    if (!s.channel_mesh) return 0;
    const geometry::TriangleMesh& mesh = *s.channel_mesh;
    const auto inside = [&](int k, bool bed) {
        for (std::size_t p = 0; p < mesh.parts(); ++p)
            if (is_bed_part(mesh.part_names[p]) == bed &&
                geometry::contains(mesh, p, cell_centre(x, y, k, dx)))
                return true;
        return false;
    };
    int z = 0;
    while (z < nz && inside(z, true)) ++z;
    return z < nz && !inside(z, false) ? z : -1;
}

std::vector<int> inlet_bed_cells(const DebrisCase& s, double dx, const lbm::GridShape& shape) {
    std::vector<int> bed(static_cast<std::size_t>(shape.ny));
    for (int y = 0; y < shape.ny; ++y) bed[static_cast<std::size_t>(y)] = bed_cells(s, dx, 0, y, shape.nz);
    return bed;
}

template <class Real>
double seed_inlet(lbm::FluidLattice<Real>& l, const DebrisCase& s, double dx, int first_global_x) {
    if (!s.inflow || first_global_x != 0) return 0.0;
    double mass = 0.0;
    // two planes, two layers: the bed's cells of the first plane are then fluid under their interface cells
    // (a layer of interface cells alone, with no fluid under it, empties at the first step)
    const auto& sh = l.shape();
    for (int y = 0; y < sh.ny; ++y)
        for (int x = 0; x < 2; ++x) {
            const int bed = bed_cells(s, dx, x, y, sh.nz);
            if (bed < 0) continue;  // a side wall's column
            for (int z = bed; z < std::min(bed + 2, sh.nz); ++z) {
                if (l.type(l.index(x, y, z)) != lbm::CellType::gas)
                    continue;  // a block's fluid or an obstacle
                l.set_fluid(x, y, z, 1.0, {});
                mass += 1.0;
            }
        }
    return mass;
}

template double seed_inlet(lbm::FluidLattice<float>&, const DebrisCase&, double, int);
template double seed_inlet(lbm::FluidLattice<double>&, const DebrisCase&, double, int);

template void fill_fluid_block(lbm::FluidLattice<float>&, const DebrisCase&, double, int);
template void fill_fluid_block(lbm::FluidLattice<double>&, const DebrisCase&, double, int);
template std::vector<std::size_t> mark_barrier(lbm::FluidLattice<float>&, const DebrisCase&, double, int);
template std::vector<std::size_t> mark_barrier(lbm::FluidLattice<double>&, const DebrisCase&, double, int);
template void mark_outlets(lbm::FluidLattice<float>&, const DebrisCase&, double, int, int);
template void mark_outlets(lbm::FluidLattice<double>&, const DebrisCase&, double, int, int);

}  // namespace sabo::scenario
