// SPDX-License-Identifier: MIT
#include "app/run_control.h"

#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <csignal>

#include "core/log.h"
#include "io/atomic_file.h"
#include "sabo/version.h"

namespace sabo::app {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_signal(int sig) {
    g_stop_signal = sig;
}

}  // namespace

void open_run_folder(const std::filesystem::path& out_dir, const std::filesystem::path& case_file,
                     const Config& cfg, bool resume) {
    std::filesystem::create_directories(out_dir);
    add_log_file(out_dir / "sabo.log", resume);  // a resumed run continues the log
    spdlog::info("sabo {} — {} — {} threads — output in {}", version_string, case_file.string(),
                 omp_get_max_threads(), out_dir.string());
    io::write_text_atomically(out_dir / "case_resolved.toml", cfg.resolved_toml());
}

std::string run_status(int exit_code) {
    return exit_code == 0 ? "completed" : (exit_code == 130 ? "interrupted" : "failed");
}

io::JsonObject summary_header(const std::string& case_name, const std::string& type, int exit_code,
                              const std::string& failure, const std::string& ending, double time,
                              std::uint64_t steps, double dt, const std::string& count_key,
                              std::size_t count) {
    io::JsonObject js;
    js.text("sabo_version", version_string)
        .text("case", case_name)
        .text("type", type)
        .text("status", run_status(exit_code))
        .text("failure", failure)
        .text("ended_by", exit_code == 0 ? ending : run_status(exit_code))
        .number("simulated_time_s", time)
        .integer("steps", static_cast<std::int64_t>(steps))
        .number("dt_s", dt)
        .integer("threads", omp_get_max_threads())
        .integer(count_key, static_cast<std::int64_t>(count));
    return js;
}

io::JsonObject summary_header(const std::string& case_name, const std::string& type, int exit_code,
                              const std::string& failure, const std::string& ending,
                              const dem::DemSolver& solver, std::size_t particles) {
    return summary_header(case_name, type, exit_code, failure, ending, solver.time(), solver.steps(),
                          solver.dt(), "particles", particles);
}

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
    spdlog::warn("signal {} received at t = {:.4f} s: writing outputs and stopping", int(g_stop_signal),
                 time);
    return true;
}

double RunControl::elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
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

}  // namespace sabo::app
