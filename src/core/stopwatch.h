// SPDX-License-Identifier: MIT
// Wall-clock seconds since a moment of the monotonic clock: what the run's time accounts (exchanges,
// stepping, checkpoints) add up.
#pragma once
#include <chrono>

namespace sabo {

[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Adds the wall-clock seconds of its scope to `seconds`, however the scope is left (a return, an exception).
class ScopeSeconds {
  public:
    explicit ScopeSeconds(double& seconds) : seconds_(seconds) {}
    ~ScopeSeconds() { seconds_ += seconds_since(start_); }
    ScopeSeconds(const ScopeSeconds&) = delete;
    ScopeSeconds& operator=(const ScopeSeconds&) = delete;

  private:
    double& seconds_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace sabo
