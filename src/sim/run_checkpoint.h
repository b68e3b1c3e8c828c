// SPDX-License-Identifier: MIT
// The checkpoint of a run, for every run type (docs/outputs.md, "Checkpoints and resuming"):
// OUTDIR/checkpoint.bin holds the resolved case (less its end time), the wall time and work of the run's
// earlier parts, how the run ended (if it did), the simulation's state (sim/simulation.h) and each
// observer's (sim/observer.h), in that order. Written atomically at the schedule's intervals, when a run is
// interrupted and at its end; read back whole, and checked, before the run goes on.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "sim/case_settings.h"
#include "sim/observer.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/simulation.h"

namespace sabo::sim {

class RunCheckpoint {
  public:
    // `cfg`: the run's case, read and finished (its resolved text is what a checkpoint must match). A run
    // divided among ranks (`domain`): each rank writes and reads its own, OUTDIR/checkpoint.rankR.bin, and
    // resumes with the same number of ranks only.
    RunCheckpoint(const std::filesystem::path& out_dir, const Config& cfg,
                  const parallel::Domain& domain = {});

    [[nodiscard]] const std::filesystem::path& file() const { return file_; }
    // Reads the checkpoint into `sim` (built from the case as a new run would be) and the observers (made
    // as for a new run); refuses a missing file, another case, another format and a truncated file
    // (InputError naming the file and why).
    void load(Simulation& sim, const std::vector<Observer*>& observers);
    // Writes it: `wall_s` and `work` of this part of the run (added to the earlier parts'); `ended_by`: how
    // the run ended, empty while it goes on.
    void save(Simulation& sim, const std::vector<Observer*>& observers, double wall_s, double work,
              const std::string& ended_by);
    // Sets the schedule's checkpoints: every `every.checkpoint_wall_s` of wall time and
    // `every.checkpoint_sim_s` of simulated time, and at the end; a resumed run starts without the first
    // row and frame (it has them), and one that had come to a complete stop takes no further step.
    void schedule(Schedule& at, const OutputSettings& every, Simulation& sim,
                  const std::vector<Observer*>& observers, const RunControl& control, bool resumed);

    // After the run: an interrupted run (exit 130) says how to continue it.
    void tell_how_to_resume(int exit_code) const;

    // Wall time (s) and work (particle-steps or cell updates) of the run's parts before this one.
    [[nodiscard]] double wall_before() const { return wall_before_; }
    [[nodiscard]] double work_before() const { return work_before_; }

  private:
    void read(Simulation& sim, const std::vector<Observer*>& observers);

    parallel::Domain domain_;  // a copy: callers may pass a temporary (the default)
    std::filesystem::path file_;
    std::string identity_;
    double wall_before_ = 0.0, work_before_ = 0.0;
    std::string ended_by_;  // of the checkpoint read
};

}  // namespace sabo::sim
