// SPDX-License-Identifier: MIT
// Fluid frames of a lattice run (docs/outputs.md): frames/fluid_NNNNN.vti (fill fraction, velocity,
// pressure above the atmosphere, cell type, apparent viscosity, in SI) and fluid.pvd with their times. A
// lattice divided into slabs among ranks: each rank writes its own planes as frames/fluid_NNNNN_rR.vti, and
// rank 0 the frames/fluid_NNNNN.pvti that joins them (ParaView opens it as one image) and fluid.pvd.
#pragma once
#include <filesystem>
#include <vector>

#include "io/vtk_writer.h"
#include "lbm/fluid_fields.h"
#include "lbm/units.h"

namespace sabo::io {

// Where this rank's planes lie among the others' (a lattice divided into slabs).
struct FluidPieces {
    int rank = 0;
    std::vector<int> cuts;  // rank r's own planes are [cuts[r], cuts[r + 1]) (empty: undivided)
};

class FluidFrameWriter {
  public:
    FluidFrameWriter(std::filesystem::path dir, const lbm::UnitConverter& units);
    // `fields`: the lattice's own planes (sim::Simulation::fluid_fields()); `pieces`: where they lie among
    // the ranks' now (their slabs may move during a run).
    void write(const lbm::FluidFields& fields, double time, const FluidPieces& pieces = {});
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
