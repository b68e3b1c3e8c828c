// SPDX-License-Identifier: MIT
// The one time loop every run goes through: steps to the end time or a complete stop, the observers'
// hooks (sim/observer.h), frames and series rows every N steps, Ctrl-C (exit 130), the progress line, a
// RunError ending the run as a failure (exit 3), the last state written as a frame, and checkpoints.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/observer.h"
#include "sim/run_control.h"
#include "sim/simulation.h"

namespace sabo::sim {

struct Schedule {
    double end_time = 0.0;  // s
    std::uint64_t series_every = 1, frame_every = 1;
    bool sample_at_end = false;  // a last series row for the final state (unless one was just taken)
    bool start_outputs = true;   // the first row and frame at the start (a resumed run has them)
    std::uint64_t progress_every = 64;
    // wall-clock seconds and steps between checkpoints (0: only at the end); `checkpoint(work)` saves the
    // state with the work the loop has done so far; at the end too, unless the run failed.
    double checkpoint_wall_s = 0.0;
    std::uint64_t checkpoint_every = 0;
    // `ended_by`: empty while the run goes on, else how it ended ("end time", "complete stop")
    std::function<void(double work, const std::string& ended_by)> checkpoint;
    bool stopped = false;  // a run resumed from its checkpoint at a complete stop: nothing is left to step
};

// Steps between series rows and between frames (at least one each) for a clock of `dt` seconds.
[[nodiscard]] Schedule make_schedule(double dt, double end_time, double series_interval,
                                     double frame_interval);

// How a run that did not fail or stop early came to its end.
enum class RunEnding : std::uint8_t { end_time, complete_stop };
// "end time", "complete stop" (summary.json's ended_by, the checkpoint's record)
[[nodiscard]] constexpr std::string_view name(RunEnding e) {
    return e == RunEnding::end_time ? "end time" : "complete stop";
}

struct RunEnd {
    int exit_code = 0;  // 0 end time or complete stop, 130 interrupted, 3 failed
    std::string failure;
    RunEnding ending = RunEnding::end_time;
    double time = 0.0;  // s
    double work = 0.0;  // particle-steps or cell updates of this loop's steps
};

RunEnd run(Simulation& sim, const Schedule& at, const std::vector<Observer*>& observers, RunControl& control);

}  // namespace sabo::sim
