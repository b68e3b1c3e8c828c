// SPDX-License-Identifier: MIT
// What every time loop of `sabo run` shares: Ctrl-C / SIGTERM caught as a request to stop cleanly
// (outputs written, exit 130), and the progress line with simulated time, rates and ETA.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace sabo::app {

// "h:mm:ss"
[[nodiscard]] std::string format_duration(double seconds);

class RunControl {
  public:
    // Installs the signal handlers; `particles` scales the particle-steps rate of the progress line.
    RunControl(double progress_interval_s, std::size_t particles);
    // Non-zero once SIGINT or SIGTERM arrived (the signal number).
    [[nodiscard]] int stop_signal() const;
    // Logs the progress line if progress_interval_s of wall time passed since the last one. The ETA
    // assumes the run goes to `end_time` (runs that end at a complete stop say so: `at_most`).
    void progress(double time, double end_time, std::uint64_t steps, std::uint64_t total_steps,
                  const std::string& phase = {});
    [[nodiscard]] double elapsed_s() const;

  private:
    std::chrono::steady_clock::time_point start_, last_;
    double interval_;
    double particles_;
};

}  // namespace sabo::app
