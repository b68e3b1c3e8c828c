// SPDX-License-Identifier: MIT
// The frames of a run as observers: the grains (.vtp + particles.pvd) and the fluid (.vti + fluid.pvd),
// written whenever the run loop says a frame is due.
#pragma once
#include <filesystem>

#include "io/fluid_frames.h"
#include "io/run_output.h"
#include "lbm/units.h"
#include "sim/observer.h"

namespace sabo::sim {

class ParticleFrames final : public Checkpointed<ParticleFrames> {
  public:
    explicit ParticleFrames(const std::filesystem::path& dir) : writer_(dir) {}
    void frame(Simulation& sim) override {
        const dem::GrainView grains = sim.grain_view();  // every rank: a collective call when divided
        if (sim.domain().writes_outputs()) writer_.write(grains.time, grains.particles, grains.ids);
    }
    // The series' state (its frames so far) for a checkpoint.
    template <class Archive>
    void transfer(Archive& a) {
        writer_.transfer(a);
    }

  private:
    io::FrameWriter writer_;
};

class FluidFrames final : public Checkpointed<FluidFrames> {
  public:
    // A divided run: each rank writes its own planes as a piece of each frame.
    FluidFrames(const std::filesystem::path& dir, const lbm::UnitConverter& units) : writer_(dir, units) {}
    void frame(Simulation& sim) override {
        const parallel::Domain& d = sim.domain();
        const io::FluidPieces pieces{d.divided() ? d.world->rank() : 0, d.cuts};
        writer_.write(sim.fluid_fields(), sim.time(), pieces);
    }
    // The series' state (its frames so far) for a checkpoint.
    template <class Archive>
    void transfer(Archive& a) {
        writer_.transfer(a);
    }

  private:
    io::FluidFrameWriter writer_;
};

}  // namespace sabo::sim
