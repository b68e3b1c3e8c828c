// SPDX-License-Identifier: MIT
#include "analysis/moving_average.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sabo::analysis {

MovingAverage::MovingAverage(double window, double dt)
    : window_(window), values_(static_cast<std::size_t>(std::max(1.0, std::round(window / dt))), 0.0) {}

void MovingAverage::add(double time, double value) {
    sum_ += value - values_[next_];
    values_[next_] = value;
    next_ = next_ + 1 == values_.size() ? 0 : next_ + 1;
    if (++since_exact_ == values_.size()) {  // once per window: the exact sum, so round-off never piles up
        sum_ = std::accumulate(values_.begin(), values_.end(), 0.0);
        since_exact_ = 0;
    }
    if (mean() > max_mean_ || std::isnan(time_of_max_)) {
        max_mean_ = std::max(max_mean_, mean());
        time_of_max_ = time;
    }
}

}  // namespace sabo::analysis
