// SPDX-License-Identifier: MIT
// The mean of a quantity sampled every time step over a sliding window of fixed duration, and the largest
// such mean: tells a pulse (a peak that survives averaging over 0.05-0.1 s) from a spike of a few steps.
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

namespace sabo::analysis {

class MovingAverage {
  public:
    MovingAverage() = default;
    // A window of `window` seconds for samples every `dt` seconds: round(window/dt) samples, at least one.
    MovingAverage(double window, double dt);

    // One step's value at `time`; before the window has filled, the missing samples count as 0.
    void add(double time, double value);
    [[nodiscard]] double mean() const { return sum_ / static_cast<double>(values_.size()); }
    [[nodiscard]] double max_mean() const { return max_mean_; }
    // end of the window of the largest mean, s (NaN before any sample)
    [[nodiscard]] double time_of_max_mean() const { return time_of_max_; }
    [[nodiscard]] double window() const { return window_; }

    template <class Archive>
    void transfer(Archive& a) {
        a(values_, next_, sum_, since_exact_, max_mean_, time_of_max_);
    }

  private:
    double window_ = 0.0;
    std::vector<double> values_;  // ring buffer of the last samples
    std::size_t next_ = 0;
    double sum_ = 0.0;
    std::size_t since_exact_ = 0;  // samples since the sum was last recomputed (no drift of the running sum)
    double max_mean_ = 0.0;
    double time_of_max_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace sabo::analysis
