// SPDX-License-Identifier: MIT
// Wall-clock seconds since a moment of the monotonic clock: what the run's time accounts (exchanges,
// stepping, checkpoints) add up.
#pragma once
#include <chrono>

namespace sabo {

[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace sabo
