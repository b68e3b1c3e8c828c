// SPDX-License-Identifier: MIT
#include "sim/run_loop.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/stopwatch.h"

namespace sabo::sim {

Schedule make_schedule(double dt, double end_time, double series_interval, double frame_interval) {
    Schedule at;
    at.end_time = end_time;
    at.series_every = std::max<std::uint64_t>(1, std::llround(series_interval / dt));
    at.frame_every = std::max<std::uint64_t>(1, std::llround(frame_interval / dt));
    return at;
}

RunEnd run(Simulation& sim, const Schedule& at, const std::vector<Observer*>& observers,
           RunControl& control) {
    RunEnd end;
    const parallel::Domain& domain = sim.domain();
    const auto total = static_cast<std::uint64_t>(std::ceil(at.end_time / sim.dt() - 1e-9));
    const std::uint64_t first = sim.steps();  // a resumed run starts where its checkpoint was
    // the last regular frame and row (a checkpoint is taken after them, before the end's)
    std::uint64_t last_frame = first - first % at.frame_every, last_sample = first - first % at.series_every;
    // f()'s wall time, added to the simulation's `phase`
    const auto timed = [&](Phase phase, auto&& f) {
        const auto start = std::chrono::steady_clock::now();
        struct Add {  // (also when f throws)
            Simulation& sim;
            Phase phase;
            std::chrono::steady_clock::time_point start;
            ~Add() { sim.add_time(phase, seconds_since(start)); }
        } add{sim, phase, start};
        return f();
    };
    const auto frame = [&] {
        timed(Phase::observers, [&] {
            for (Observer* o : observers) o->frame(sim);
        });
        last_frame = sim.steps();
    };
    const auto sample = [&] {
        const bool stop = timed(Phase::observers, [&] {
            sim.check_state();
            bool any = false;
            for (Observer* o : observers) any = o->sample(sim) || any;
            return any;
        });
        last_sample = sim.steps();
        return stop;
    };
    const auto checkpoint = [&](const std::string& ending) {
        timed(Phase::checkpoints, [&] { at.checkpoint(end.work, ending); });
    };
    control.set_rate_unit(sim.work_unit());
    const std::function<void()> after_grain_step = [&] {
        for (Observer* o : observers) o->after_grain_step(sim);
    };
    const std::function<void()> no_grains;
    auto last_checkpoint = std::chrono::steady_clock::now();
    try {
        if (at.start_outputs) {
            sample();
            frame();
        }
        if (at.stopped) end.ending = RunEnding::complete_stop;
        while (!at.stopped && sim.steps() < total) {
            timed(Phase::observers, [&] {
                for (Observer* o : observers) o->before_step(sim);
            });
            sim.step(sim.has_grains() ? after_grain_step : no_grains);
            end.work += sim.work_of_last_step();
            timed(Phase::observers, [&] {
                for (Observer* o : observers) o->after_step(sim);
            });
            if (sim.steps() % at.frame_every == 0) frame();
            if (sim.steps() % at.series_every == 0 && sample()) {
                end.ending = RunEnding::complete_stop;
                break;
            }
            // the ranks of a divided run stop, and take wall-clock checkpoints, at the same step: they agree
            // every 16 steps (each agreement is a wait for the slowest rank)
            const bool agree = !domain.divided() || sim.steps() % 16 == 0;
            if (agree && domain.any(control.interrupted(sim.time()))) {
                end.exit_code = 130;
                break;
            }
            if ((at.checkpoint_every > 0 && sim.steps() % at.checkpoint_every == 0) ||
                (at.checkpoint_wall_s > 0.0 && agree &&
                 domain.any(seconds_since(last_checkpoint) >= at.checkpoint_wall_s))) {
                checkpoint({});
                last_checkpoint = std::chrono::steady_clock::now();
            }
            if (sim.steps() % at.progress_every == 0) {
                const std::uint64_t done = sim.steps() - first;
                control.set_particles(static_cast<std::size_t>(end.work / static_cast<double>(done)));
                std::string phase;
                for (const Observer* o : observers)
                    if (phase.empty()) phase = o->phase();
                control.progress(sim.time(), at.end_time, done, total - first, phase);
            }
        }
    } catch (const RunError& e) {
        end.failure = e.what();
        spdlog::error("{}", end.failure);
        end.exit_code = 3;
    }
    end.time = sim.time();
    // the checkpoint before the end's extra row and frame: a run continued from it writes the rows and
    // frames of an uninterrupted run, no more
    if (end.exit_code != 3 && at.checkpoint)
        checkpoint(end.exit_code == 0 ? std::string(name(end.ending)) : "");
    try {
        if (at.sample_at_end && last_sample != sim.steps()) sample();
    } catch (const RunError& e) {  // the failed state's row is written; its check adds nothing
        if (end.exit_code == 0) {
            end.failure = e.what();
            end.exit_code = 3;
        }
    }
    if (last_frame != sim.steps()) frame();
    return end;
}

}  // namespace sabo::sim
