// SPDX-License-Identifier: MIT
// The time loop every lattice run shares (dam break, debris): a step, the per-step hook, the series
// sample and the frame every N steps, Ctrl-C, the progress line; a RunError ends it as a failure
// (exit 3). The last state is always written as a frame.
#pragma once
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>

#include "app/run_control.h"
#include "core/config.h"
#include "core/error.h"
#include "io/json_writer.h"
#include "lbm/fluid_setup.h"

namespace sabo::app {

struct FluidLoopEnd {
    int exit_code = 0;  // 0 end time, 130 interrupted, 3 failed
    std::string failure;
    double time = 0.0;  // s
    // fluid and interface cells the loop's steps updated (gas and obstacle cells cost nothing, so they
    // do not count: the rate is the solver's, not the box's)
    double cell_updates = 0.0;
};

struct FluidLoopSchedule {
    double dt = 0.0, end_time = 0.0;  // s
    std::uint64_t series_every = 1, frame_every = 1;
    double checkpoint_wall_s = 0.0;  // wall-clock seconds between checkpoints (0: only at the end)
};

// Steps between series rows and between frames (at least one each).
inline FluidLoopSchedule fluid_schedule(double dt, double end_time, double series_interval,
                                        double frame_interval) {
    return {dt, end_time, std::max<std::uint64_t>(1, std::llround(series_interval / dt)),
            std::max<std::uint64_t>(1, std::llround(frame_interval / dt))};
}

// The progress line of a lattice run: rates in cell updates (run_fluid_loop keeps the mean count per step
// current), and no "at most" (it runs to its end time).
inline RunControl lattice_run_control(double progress_interval) {
    RunControl control(progress_interval, 0);
    control.set_rate_unit("cell updates");
    control.set_ends_at_end_time();
    return control;
}

// The summary.json keys every lattice run adds after its own: the lattice (dx_m, tau as the cells relax,
// tau_requested, mach, storage), the mass conservation, the wall time and the rate.
inline void add_lattice_summary(io::JsonObject& js, const lbm::FluidSettings& fs, double worst_mass_drift,
                                double wall_s, double cell_updates) {
    js.number("dx_m", fs.units.dx())
        .number("tau", fs.rheology.tau)
        .number("tau_requested", fs.numbers.tau)
        .number("mach", fs.numbers.mach)
        .text("storage", fs.single_precision ? "float32" : "float64")
        .number("max_relative_mass_drift", worst_mass_drift)
        .number("wall_time_s", wall_s)
        .number("cell_updates_per_s", cell_updates / wall_s);
}

// The resolved case without its end time and comments: what a checkpoint is checked against when a run
// resumes (the end time may change: a run is continued further).
inline std::string case_identity(const Config& cfg) {
    std::istringstream in(cfg.resolved_toml());
    std::string line, identity;
    while (std::getline(in, line))
        if (!line.starts_with("end_time_s") && !line.starts_with("#")) identity += line + '\n';
    return identity;
}

// Throws InputError naming the first line in which the checkpoint's case and this one differ (a key the
// user wrote before the [derived] values that follow from it).
inline void check_same_case(const std::filesystem::path& checkpoint, const std::string& stored,
                            const std::string& current) {
    if (stored == current) return;
    std::istringstream a(stored), b(current);
    std::string la, lb, table, found_a, found_b, found_table;
    while (std::getline(a, la) && std::getline(b, lb)) {
        if (la.starts_with("[")) table = la;
        if (la == lb || (!found_a.empty() && table == "[derived]")) continue;
        if (found_a.empty() || found_table == "[derived]") {
            found_a = la;
            found_b = lb;
            found_table = table;
            if (table != "[derived]") break;
        }
    }
    throw InputError(
        fmt::format("{} was written for another case: in {} it has '{}', this case '{}' (a resumed "
                    "run may change case.end_time_s only)",
                    checkpoint.string(), found_table.empty() ? "the case" : found_table, found_a, found_b));
}

// Throws RunError when the fluid has become unstable: mass no longer finite, or a lattice speed above
// 0.5 (BGK is far beyond its range there).
inline void check_fluid_stable(double time, double mass_drift, double lattice_speed) {
    if (!std::isfinite(mass_drift) || !(lattice_speed <= 0.5))
        throw RunError(
            fmt::format("t = {:.4g} s: the fluid became unstable (lattice speed {:.3g}): reduce dt", time,
                        lattice_speed));
}

// `checkpoint(t, cell_updates)` saves the run's state: every at.checkpoint_wall_s of wall time (0: never
// on the way), and at the end unless the run failed (its state is then not worth continuing from).
template <class Lattice, class PerStep, class Sample, class Frame, class Checkpoint>
FluidLoopEnd run_fluid_loop(Lattice& l, const FluidLoopSchedule& at, RunControl& control, PerStep per_step,
                            Sample sample, Frame frame, Checkpoint checkpoint) {
    FluidLoopEnd end;
    const auto total = static_cast<std::uint64_t>(std::ceil(at.end_time / at.dt - 1e-9));
    const std::uint64_t first = l.steps();  // a resumed run starts where its checkpoint was
    auto last_checkpoint = std::chrono::steady_clock::now();
    try {
        while (l.steps() < total) {
            l.step();
            end.cell_updates += static_cast<double>(l.updated_cells());
            const double t = static_cast<double>(l.steps()) * at.dt;
            per_step(t);
            if (l.steps() % at.series_every == 0) sample(t);
            if (l.steps() % at.frame_every == 0) frame(t);
            if (control.interrupted(t)) {
                end.exit_code = 130;
                break;
            }
            if (at.checkpoint_wall_s > 0.0 &&
                std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() >=
                    at.checkpoint_wall_s) {
                checkpoint(t, end.cell_updates);
                last_checkpoint = std::chrono::steady_clock::now();
            }
            if ((l.steps() & 15) == 0) {
                const std::uint64_t done = l.steps() - first;
                control.set_particles(
                    static_cast<std::size_t>(end.cell_updates / static_cast<double>(done)));  // mean per step
                control.progress(t, at.end_time, done, total - first);
            }
        }
    } catch (const RunError& e) {
        end.failure = e.what();
        spdlog::error("{}", end.failure);
        end.exit_code = 3;
    }
    end.time = static_cast<double>(l.steps()) * at.dt;
    if (l.steps() % at.frame_every != 0) frame(end.time);
    if (end.exit_code != 3) checkpoint(end.time, end.cell_updates);
    return end;
}

}  // namespace sabo::app
