// SPDX-License-Identifier: MIT
// What code above the lattice needs to run kernels of its own on a lattice's device (the grain–fluid
// coupling finds its grain cells there): the context, queue and device, the build options that describe
// the lattice's storage and shape (NX, NY, NZ, ROW, PLANE, CELLS, REAL, …: a kernel built with them indexes
// cells as the lattice's do) and the per-cell buffers such kernels read.
#pragma once
#include <string>

#include "lbm/opencl/cl.h"

namespace sabo::lbm::opencl {

struct DeviceView {
    cl::Context context;
    cl::CommandQueue queue;
    cl::Device device;
    std::string options;
    cl::Buffer type;  // per stored cell: lbm::CellType as a byte
    cl::Buffer tau;   // per stored cell: the last relaxation time (storage type)
    cl::Buffer fill;  // per stored cell: λ (with a free surface; else none)
    // built for solids (OpenClLattice's `solids`): per stored cell the share a solid covers (0: none), its
    // velocity there (3 values) and the force on it from the cell in the last step (3 sums); else none
    bool solids = false;
    cl::Buffer solid_fraction, solid_v, solid_force;
};

}  // namespace sabo::lbm::opencl
