// SPDX-License-Identifier: MIT
#include "analysis/moving_average.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sabo::analysis {
namespace {

// A spike of a few steps is diluted by the window; a pulse longer than the window keeps its height.
TEST(MovingAverage, DilutesASpikeAndKeepsAPulse) {
    const double dt = 1e-3;
    MovingAverage spike(0.05, dt), pulse(0.05, dt);  // 50 samples
    for (int k = 0; k < 500; ++k) {
        const double t = k * dt;
        spike.add(t, k >= 100 && k < 105 ? 1000.0 : 0.0);  // 5 steps of 1000
        pulse.add(t, k >= 100 && k < 300 ? 1000.0 : 0.0);  // 0.2 s of 1000
    }
    EXPECT_NEAR(spike.max_mean(), 1000.0 * 5 / 50, 1e-9);
    EXPECT_NEAR(spike.time_of_max_mean(), 104 * dt, 1e-12);  // the window first holding all of it
    EXPECT_NEAR(pulse.max_mean(), 1000.0, 1e-9);
    EXPECT_NEAR(pulse.time_of_max_mean(), 149 * dt, 1e-12);  // the first full window
    EXPECT_NEAR(pulse.mean(), 0.0, 1e-9);                    // the window has moved past it
}

// A running sum would lose the small samples added while a huge one was in the window and keep the
// loss after it has left; the sum is recomputed once per window, so the mean comes back exact.
TEST(MovingAverage, AHugeSampleLeavesNoTraceOnceOutOfTheWindow) {
    MovingAverage m(0.1, 1e-3);  // 100 samples
    m.add(0.0, 1e17);
    for (int k = 1; k < 250; ++k) m.add(k * 1e-3, 1.0);
    EXPECT_EQ(m.mean(), 1.0);
    EXPECT_EQ(m.max_mean(), 1e15);
}

}  // namespace
}  // namespace sabo::analysis
