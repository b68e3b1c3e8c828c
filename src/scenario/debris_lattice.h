// SPDX-License-Identifier: MIT
// The debris case (reference case C5) on the lattice: the released fluid block and the barrier's obstacle
// cells. A cell belongs to a shape when its centre, (x+½, y+½, z+½) Δx in the channel frame, lies inside it.
// A lattice that is one slab of the channel's (a run divided among ranks) holds the planes from global plane
// `first_global_x` on; its own planes are those the lattice names (FluidLattice::own_begin/own_end).
#pragma once
#include <cstddef>
#include <vector>

#include "lbm/fluid_lattice.h"
#include "scenario/debris_case.h"

namespace sabo::scenario {

// Fluid at rest (lattice density 1) in the cells of the block.
template <class Real>
void fill_fluid_block(lbm::FluidLattice<Real>& lattice, const DebrisCase& c, double dx,
                      int first_global_x = 0);

// Barrier cells: a cell whose centre lies in a barrier element is an obstacle of element 1 + e (0 is the
// channel walls); inside several overlapping spheres it belongs to the nearest centre. Returns the
// obstacle cell count per element (of the own planes).
template <class Real>
[[nodiscard]] std::vector<std::size_t> mark_barrier(lbm::FluidLattice<Real>& lattice, const DebrisCase& c,
                                                    double dx, int first_global_x = 0);

// The channel mesh's cells (c.channel_mesh: its side walls): obstacles of element 0, the channel's walls, as
// the domain's edges are; a cell whose centre a part holds.
template <class Real>
void mark_channel_mesh(lbm::FluidLattice<Real>& lattice, const DebrisCase& c, double dx,
                       int first_global_x = 0);
// The bed under the column (global plane x, row y) of a lattice of `nz` cells high: how many of its cells,
// from the inclined plane up, the channel mesh's bed parts mark (mark_channel_mesh: a cell whose centre a
// part holds), the relief under it (0 without a mesh); −1 where a side wall holds the cell above them (the
// column is the wall's) or the relief fills the column.
[[nodiscard]] int bed_cells(const DebrisCase& c, double dx, int x, int y, int nz);
// The bed under each row of the first plane (bed_cells at x = 0): where the inflow boundary's columns
// stand.
[[nodiscard]] std::vector<int> inlet_bed_cells(const DebrisCase& c, double dx, const lbm::GridShape& shape);
// An inflow's seed (c.inflow): fluid at rest in the two bottom layers above the bed of the first two planes,
// which the inflow boundary (lbm/inlet.h) then holds and fills; returns its mass, lattice units (0 without an
// inflow or off this slab).
template <class Real>
double seed_inlet(lbm::FluidLattice<Real>& lattice, const DebrisCase& c, double dx, int first_global_x = 0);

// An open channel's outlets: with an open top or end, outlet DebrisOutlet::end every cell at X ≥ c.outflow_x
// and the last plane (global_nx − 1); with an open top also ::sides the side planes above the walls' height
// and ::top the highest plane (a cell on two counts with the later). Obstacle cells are left out; a closed
// box (lid, end wall) has none.
template <class Real>
void mark_outlets(lbm::FluidLattice<Real>& lattice, const DebrisCase& c, double dx, int global_nx,
                  int first_global_x = 0);

}  // namespace sabo::scenario
