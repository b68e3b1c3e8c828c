// SPDX-License-Identifier: MIT
// Fluid frames of a lattice run (docs/outputs.md): frames/fluid_NNNNN.vti (fill fraction, velocity,
// pressure above the atmosphere, cell type, apparent viscosity, in SI) and fluid.pvd with their times.
#pragma once
#include <filesystem>

#include "io/vtk_writer.h"
#include "lbm/fluid_lattice.h"
#include "lbm/units.h"

namespace sabo::io {

class FluidFrameWriter {
  public:
    FluidFrameWriter(std::filesystem::path dir, const lbm::UnitConverter& units);
    template <class Real>
    void write(const lbm::FluidLattice<Real>& lattice, double time);
    // the frames written so far (io/checkpoint.h)
    template <class Archive>
    void transfer(Archive& a) {
        a(pvd_, index_);
    }

  private:
    std::filesystem::path dir_;
    lbm::UnitConverter units_;
    PvdSeries pvd_;
    int index_ = 0;
};

}  // namespace sabo::io
