// SPDX-License-Identifier: MIT
// What a case measures and writes during a run, plugged into the run loop (sim/run_loop.h). The loop calls,
// for each step n: before_step (n − 1 done, n not yet), the step, after_step, then frame when a frame is
// due and sample when a series row is due — each on every observer in the order they were given. A sample
// may end the run at a complete stop by returning true.
#pragma once
#include <string>

#include "io/checkpoint.h"
#include "sim/simulation.h"

namespace sabo::sim {

class Observer {
  public:
    virtual ~Observer() = default;
    // Before each step: changes to the set-up that take effect from this step on (opening a gate).
    virtual void before_step(Simulation&) {}
    // After every step: what must not be decimated (barrier forces and their peaks).
    virtual void after_step(Simulation&) {}
    // After every DEM step of a run with grains (the sub-steps of a coupled step; in a grains-only run,
    // every step, before after_step): the barrier's contact forces of every sub-step.
    virtual void after_grain_step(Simulation&) {}
    // A frame is due (output.frame_interval_s, the start, the last state).
    virtual void frame(Simulation&) {}
    // A series row is due (output.series_interval_s, the start); true ends the run at a complete stop.
    virtual bool sample(Simulation&) { return false; }
    // The phase the progress line names ("settling"), empty if the observer has none.
    [[nodiscard]] virtual std::string phase() const { return {}; }
    // What the observer has accumulated (peaks, series rows, frames), for a checkpoint: written after the
    // simulation's state, read back in the same order. An observer with state derives from Checkpointed.
    virtual void save(io::CheckpointOut&) {}
    virtual void load(io::CheckpointIn&) {}
};

// An observer whose state is its `template <class Archive> void transfer(Archive&)` (io/checkpoint.h).
template <class Derived>
class Checkpointed : public Observer {
  public:
    void save(io::CheckpointOut& out) final { static_cast<Derived*>(this)->transfer(out); }
    void load(io::CheckpointIn& in) final { static_cast<Derived*>(this)->transfer(in); }
};

}  // namespace sabo::sim
