// SPDX-License-Identifier: MIT
// Ctrl-C / SIGTERM caught as a request to stop a run cleanly (outputs written, exit 130), and the progress
// line with simulated time, rates and ETA.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace sabo::sim {

// "h:mm:ss"
[[nodiscard]] std::string format_duration(double seconds);

class RunControl {
  public:
    // Installs the signal handlers; `particles` scales the particle-steps rate of the progress line.
    RunControl(double progress_interval_s, std::size_t particles);
    // True (and logged, with the simulated time) once SIGINT or SIGTERM arrived: write outputs, exit 130.
    [[nodiscard]] bool interrupted(double time) const;
    // The same, quietly: a stop was requested.
    [[nodiscard]] bool stop_requested() const;
    // Logs the progress line if progress_interval_s of wall time passed since the last one. The ETA
    // assumes the run goes to `end_time` (runs that end at a complete stop say so: `at_most`).
    void progress(double time, double end_time, std::uint64_t steps, std::uint64_t total_steps,
                  const std::string& phase = {});
    [[nodiscard]] double elapsed_s() const;
    // The grain count changed (grains removed from the run).
    void set_particles(std::size_t particles) { particles_ = static_cast<double>(particles); }
    // What the count stands for in the rate ("particle-steps" by default; "cell updates" for a lattice).
    void set_rate_unit(std::string unit) { rate_unit_ = std::move(unit); }
    // Runs that always go to their end time (the fluid cases) drop the "at most" of the ETA.
    void set_ends_at_end_time() { ends_early_ = false; }

  private:
    std::chrono::steady_clock::time_point start_, last_;
    double interval_;
    double particles_;
    std::string rate_unit_ = "particle-steps";
    bool ends_early_ = true;
};

}  // namespace sabo::sim
