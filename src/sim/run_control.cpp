// SPDX-License-Identifier: MIT
#include "sim/run_control.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>

#include "core/stopwatch.h"

namespace sabo::sim {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
// The first signal asks the run to stop cleanly (checkpoint, outputs); a second one ends the process at
// once (what a user pressing Ctrl-C twice means). Only async-signal-safe calls here.
extern "C" void on_signal(int sig) {
    if (g_stop_signal != 0) {
        constexpr char message[] =
            "\nsecond stop signal: exiting at once (state since the last checkpoint lost)\n";
        [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
        std::_Exit(130);
    }
    g_stop_signal = sig;
}

}  // namespace

std::string format_duration(double seconds) {
    const auto s = static_cast<long>(std::max(0.0, seconds));
    return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

RunControl::RunControl(double progress_interval_s, std::size_t particles)
    : start_(std::chrono::steady_clock::now()),
      last_(start_),
      interval_(progress_interval_s),
      particles_(static_cast<double>(particles)) {
    g_stop_signal = 0;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
}

bool RunControl::interrupted(double time) const {
    if (g_stop_signal == 0) return false;
    spdlog::warn(
        "signal {} received at t = {:.4f} s: writing the checkpoint and the outputs, then stopping (a second "
        "signal exits at once)",
        int(g_stop_signal), time);
    return true;
}

bool RunControl::stop_requested() const {
    return g_stop_signal != 0;
}

double RunControl::elapsed_s() const {
    return seconds_since(start_);
}

void RunControl::progress(double time, double end_time, std::uint64_t steps, std::uint64_t total_steps,
                          const std::string& phase) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < interval_) return;
    last_ = now;
    const double rate = static_cast<double>(steps) / elapsed_s();
    spdlog::info("{}t = {:.3f} / {:.3f} s ({:4.1f} %)  {:.0f} steps/s  {:.3g} {}/s  ETA {}{}",
                 phase.empty() ? std::string() : phase + ": ", time, end_time, 100.0 * time / end_time, rate,
                 rate * particles_, rate_unit_,
                 format_duration(static_cast<double>(total_steps - std::min(steps, total_steps)) / rate),
                 ends_early_ ? " (at most: the run ends at complete stop)" : "");
}

}  // namespace sabo::sim
