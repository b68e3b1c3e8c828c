// SPDX-License-Identifier: MIT
// The one run loop: when the observers are called, the end of a run (end time, complete stop, failure),
// and the clock against the solver's own time.
#include "sim/run_loop.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/error.h"
#include "dem/test_support.h"
#include "sim/simulation.h"

namespace sabo {
namespace {

// One grain falling freely: a simulation whose every step is cheap.
sim::Simulation falling_grain(double dt) {
    dem::Particles p;
    p.add_mobile({0, 0, 10}, 0.05, 2500.0, {});
    return sim::Simulation(
        dem::DemSolver(p, {}, test::same_everywhere(test::linear_law({})), {0, 0, -9.81}, dt, 0.01));
}

// Records the step of every call.
struct Recorder final : sim::Observer {
    std::vector<std::uint64_t> before, after, frames, samples;
    std::uint64_t stop_at = 0;   // sample returns true from this step on (0: never)
    std::uint64_t throw_at = 0;  // sample throws a RunError at this step (0: never)
    void before_step(sim::Simulation& s) override { before.push_back(s.steps()); }
    void after_step(sim::Simulation& s) override { after.push_back(s.steps()); }
    void frame(sim::Simulation& s) override { frames.push_back(s.steps()); }
    bool sample(sim::Simulation& s) override {
        samples.push_back(s.steps());
        if (throw_at != 0 && s.steps() == throw_at) throw RunError("blown up");
        return stop_at != 0 && s.steps() >= stop_at;
    }
};

sim::RunEnd run_quietly(sim::Simulation& s, const sim::Schedule& at, Recorder& r) {
    sim::RunControl control(1e9, 1);
    return sim::run(s, at, {&r}, control);
}

TEST(RunLoop, CallsObserversOnScheduleAndWritesTheLastStateOnce) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    sim::Schedule at = sim::make_schedule(dt, 0.0105, 3e-3, 4e-3);  // 11 steps, rows every 3, frames every 4
    at.sample_at_end = true;
    Recorder r;
    const sim::RunEnd end = run_quietly(s, at, r);
    EXPECT_EQ(end.exit_code, 0);
    EXPECT_EQ(end.ending, sim::RunEnding::end_time);
    EXPECT_EQ(s.steps(), 11u);
    EXPECT_EQ(r.before.size(), 11u);
    EXPECT_EQ(r.after, (std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
    EXPECT_EQ(r.frames, (std::vector<std::uint64_t>{0, 4, 8, 11}));
    EXPECT_EQ(r.samples, (std::vector<std::uint64_t>{0, 3, 6, 9, 11}));
    EXPECT_DOUBLE_EQ(end.work, 11.0);  // one grain, eleven steps
}

TEST(RunLoop, TheClockIsTheSolversTime) {
    const double dt = 1.3e-4;
    sim::Simulation s = falling_grain(dt);
    Recorder r;
    const sim::RunEnd end = run_quietly(s, sim::make_schedule(dt, 0.05, 1e-2, 1e-2), r);
    EXPECT_EQ(s.steps(), s.grains().steps());
    EXPECT_EQ(s.time(), s.grains().time());  // bit for bit: both are steps · Δt
    EXPECT_EQ(end.time, s.time());
    // free fall from rest: z = 10 − g t²/2 (velocity Verlet is exact for a constant force)
    EXPECT_NEAR(s.grains().particles().x[0].z, 10.0 - 0.5 * 9.81 * s.time() * s.time(), 1e-9);
}

TEST(RunLoop, ACompleteStopEndsTheRunAtThatSample) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    sim::Schedule at = sim::make_schedule(dt, 1.0, 5e-3, 7e-3);
    at.sample_at_end = true;
    Recorder r;
    r.stop_at = 12;
    const sim::RunEnd end = run_quietly(s, at, r);
    EXPECT_EQ(end.exit_code, 0);
    EXPECT_EQ(end.ending, sim::RunEnding::complete_stop);
    EXPECT_EQ(s.steps(), 15u);                                        // the first row at or after step 12
    EXPECT_EQ(r.samples.back(), 15u);                                 // no second row for the same state
    EXPECT_EQ(r.frames, (std::vector<std::uint64_t>{0, 7, 14, 15}));  // the last state as a frame
}

TEST(RunLoop, ARunErrorEndsTheRunAsAFailureWithItsMessage) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    bool checkpointed = false;
    sim::Schedule at = sim::make_schedule(dt, 1.0, 2e-3, 1.0);
    at.checkpoint = [&](double, const std::string&) { checkpointed = true; };
    Recorder r;
    r.throw_at = 6;
    const sim::RunEnd end = run_quietly(s, at, r);
    EXPECT_EQ(end.exit_code, 3);
    EXPECT_EQ(end.failure, "blown up");
    EXPECT_EQ(s.steps(), 6u);
    EXPECT_EQ(r.frames.back(), 6u);  // the failed state is still written
    EXPECT_FALSE(checkpointed);      // a failed state is not worth continuing from
}

TEST(RunLoop, AResumedRunStartsWithoutTheStartOutputsAndCheckpointsAtTheEnd) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    int checkpoints = 0;
    sim::Schedule at = sim::make_schedule(dt, 4e-3, 1e-3, 1e-3);
    at.start_outputs = false;
    at.checkpoint = [&](double work, const std::string& ended_by) {
        ++checkpoints;
        EXPECT_DOUBLE_EQ(work, 4.0);
        EXPECT_EQ(ended_by, "end time");
    };
    Recorder r;
    run_quietly(s, at, r);
    EXPECT_EQ(r.samples, (std::vector<std::uint64_t>{1, 2, 3, 4}));
    EXPECT_EQ(r.frames, (std::vector<std::uint64_t>{1, 2, 3, 4}));
    EXPECT_EQ(checkpoints, 1);
}

// Checkpoints every N steps are taken after that step's row and frame; the end's checkpoint before the
// end's extra row and frame (a run continued from it must not find them in its series).
TEST(RunLoop, CheckpointsComeAfterTheStepsOutputsAndBeforeTheEndsExtraOnes) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    sim::Schedule at = sim::make_schedule(dt, 15e-3, 2e-3, 7e-3);
    at.sample_at_end = true;
    at.checkpoint_every = 4;
    Recorder r;
    std::vector<std::pair<std::uint64_t, std::size_t>> taken;  // (step, rows so far)
    at.checkpoint = [&](double, const std::string&) { taken.emplace_back(s.steps(), r.samples.size()); };
    run_quietly(s, at, r);
    // rows at 0, 2, 4, ..., 14, then the end's at 15
    const std::vector<std::pair<std::uint64_t, std::size_t>> expected{{4, 3}, {8, 5}, {12, 7}, {15, 8}};
    EXPECT_EQ(taken, expected);
    EXPECT_EQ(r.samples.back(), 15u);
}

// A run resumed from the checkpoint of a run that had come to a complete stop takes no step.
TEST(RunLoop, AResumedStoppedRunTakesNoStep) {
    const double dt = 1e-3;
    sim::Simulation s = falling_grain(dt);
    sim::Schedule at = sim::make_schedule(dt, 4e-3, 1e-3, 1e-3);
    at.start_outputs = false;
    at.stopped = true;
    Recorder r;
    const sim::RunEnd end = run_quietly(s, at, r);
    EXPECT_EQ(s.steps(), 0u);
    EXPECT_EQ(end.ending, sim::RunEnding::complete_stop);
    EXPECT_TRUE(r.samples.empty());
}

}  // namespace
}  // namespace sabo
