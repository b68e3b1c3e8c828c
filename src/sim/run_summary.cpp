// SPDX-License-Identifier: MIT
#include "sim/run_summary.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <omp.h>
#include <spdlog/spdlog.h>
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/log.h"
#include "core/thread_waiting.h"
#include "io/atomic_file.h"
#include "io/folder_lock.h"
#include "io/run_folder_contents.h"
#include "sabo/version.h"

namespace sabo::sim {

namespace {

void open_folder(const std::filesystem::path& out_dir, const std::filesystem::path& case_file,
                 const Config& cfg, FolderUse use) {
    // An output folder that cannot be made or written is bad input: said before anything runs.
    const auto refuse = [&](const std::string& why) {
        throw InputError(fmt::format("{}: the output folder {} (--out or output.dir) {}", cfg.source(),
                                     out_dir.string(), why));
    };
    std::error_code error;
    std::filesystem::create_directories(out_dir, error);
    if (error) refuse("cannot be created: " + error.message());
    io::lock_run_folder(out_dir);  // held until this process ends: no second run writes here meanwhile
    const bool resume = use == FolderUse::resume;
    if (use == FolderUse::new_run && io::holds_run_outputs(out_dir))
        refuse(
            fmt::format("holds another run's outputs: `sabo resume {0}` continues that run, `--overwrite` "
                        "replaces its outputs with this run's, or give this run another --out",
                        out_dir.string()));
    // a new run's files are never mixed with an earlier run's (a shorter run left the other's frames behind)
    const int removed = resume ? 0 : io::clear_run_outputs(out_dir);
    const auto probe = out_dir / ".sabo_write_test";
    if (!std::ofstream(probe)) refuse("is not writable");
    std::filesystem::remove(probe, error);
    add_log_file(out_dir / "sabo.log", resume);  // a resumed run continues the log
    spdlog::info("sabo {} — {} — {} threads (waiting: {}) — output in {}", version_string, case_file.string(),
                 omp_get_max_threads(), thread_waiting(), out_dir.string());
    if (removed > 0)
        spdlog::info("removed the earlier run's outputs from {} ({} files and folders)", out_dir.string(),
                     removed);
    io::write_text_atomically(out_dir / "case_resolved.toml", cfg.resolved_toml());
    // the case as given (its text and --set overrides): `sabo resume OUTDIR` needs nothing else
    toml::array overrides;
    for (const auto& o : cfg.overrides()) overrides.push_back(o);
    const toml::table request{{"case_file", cfg.source()}, {"overrides", overrides}, {"case", cfg.text()}};
    std::ostringstream text;
    text << "# how this run was started: `sabo resume` continues it from here\n" << request << '\n';
    io::write_text_atomically(out_dir / resume_file_name, text.str());
}

}  // namespace

void open_run_folder(const std::filesystem::path& out_dir, const std::filesystem::path& case_file,
                     const Config& cfg, FolderUse use, const parallel::Domain& domain) {
    if (!domain.divided()) return open_folder(out_dir, case_file, cfg, use);
    std::string refused;
    if (domain.writes_outputs()) {
        try {
            open_folder(out_dir, case_file, cfg, use);
        } catch (const InputError& e) {
            refused = e.what();
        }
    }
    if (domain.world->max(refused.empty() ? 0 : 1) != 0)
        throw InputError(refused.empty() ? "the first rank could not open the output folder" : refused);
    if (!domain.writes_outputs()) spdlog::set_level(spdlog::level::warn);
}

DivisionSummary summarise_division(const Simulation& sim, double work, double wall_s) {
    const parallel::Domain& d = sim.domain();
    if (!d.divided()) return {};
    DivisionSummary out;
    out.ranks = d.ranks();
    const auto imbalance = [&](double own) {
        const double mean = d.sum(own) / out.ranks;
        return mean > 0.0 ? d.max(own) / mean : 1.0;
    };
    out.time_imbalance = imbalance(sim.stepping_seconds());
    out.work_imbalance = imbalance(work);
    out.exchange_fraction = d.max(wall_s > 0.0 ? sim.exchange_seconds() / wall_s : 0.0);
    out.face_moves = sim.rebalances();
    out.cuts = d.cuts;
    out.grain_faces = sim.grain_faces();
    const std::string faces = out.cuts.empty() ? fmt::format("x = {:.3f} m", fmt::join(out.grain_faces, ", "))
                                               : fmt::format("planes {}", fmt::join(out.cuts, " "));
    spdlog::info(
        "{} ranks: stepping time imbalance {:.2f} (largest over mean; {} {:.2f}), exchanges up to {:.0f} % "
        "of "
        "a rank's time; the slab faces moved {} times, now at {}",
        out.ranks, out.time_imbalance, sim.work_unit(), out.work_imbalance, 100.0 * out.exchange_fraction,
        out.face_moves, faces);
    return out;
}

void add_division_summary(io::JsonObject& js, const DivisionSummary& d) {
    if (d.ranks < 2) return;
    js.integer("mpi_ranks", d.ranks)
        .number("mpi_time_imbalance", d.time_imbalance)
        .number("mpi_work_imbalance", d.work_imbalance)
        .number("mpi_exchange_fraction", d.exchange_fraction)
        .integer("mpi_face_moves", static_cast<std::int64_t>(d.face_moves))
        .text("mpi_slab_faces", d.cuts.empty() ? fmt::format("{}", fmt::join(d.grain_faces, " "))
                                               : fmt::format("{}", fmt::join(d.cuts, " ")));
}

void add_timing(io::JsonObject& js, const Simulation& sim, double wall_s) {
    const PhaseTimes t = sim.timing();
    io::JsonObject timing;
    for (std::size_t p = 0; p < phase_count; ++p)
        timing.number(std::string(phase_names[p]) + "_s", t[static_cast<Phase>(p)]);
    timing.number("other_s", std::max(0.0, wall_s - t.sum()))
        .number("wall_s", wall_s)
        .number("lattice_free_surface_s", t.parts.free_surface)
        .number("grains_neighbour_lists_s", t.parts.neighbour_lists)
        .number("exchanges_lattice_s", t.parts.lattice_exchanges)
        .number("exchanges_grains_s", t.parts.grain_exchanges)
        .number("exchanges_face_moves_s", t.parts.face_moves);
    js.object("timing", timing);
}

void log_timing(const Simulation& sim, double wall_s) {
    const PhaseTimes t = sim.timing();
    std::string line;
    for (std::size_t p = 0; p < phase_count; ++p)
        if (const double s = t[static_cast<Phase>(p)]; s > 0.005 * wall_s)
            line += fmt::format("{} {:.0f} %, ", phase_names[p], 100.0 * s / wall_s);
    spdlog::info("where the time went: {}other {:.0f} % of {:.1f} s", line,
                 wall_s > 0.0 ? 100.0 * std::max(0.0, wall_s - t.sum()) / wall_s : 0.0, wall_s);
}

std::string run_status(int exit_code) {
    return exit_code == 0 ? "completed" : (exit_code == 130 ? "interrupted" : "failed");
}

io::JsonObject summary_header(const std::string& case_name, const std::string& type, const RunEnd& end,
                              const Simulation& sim, const std::string& count_key, std::size_t count) {
    const int exit_code = end.exit_code;
    io::JsonObject js;
    js.text("sabo_version", version_string)
        .text("case", case_name)
        .text("type", type)
        .text("status", run_status(exit_code))
        .text("failure", end.failure)
        .text("ended_by", ended_by(end))
        .number("simulated_time_s", sim.time())
        .integer("steps", static_cast<std::int64_t>(sim.steps()))
        .number("dt_s", sim.dt())
        .integer("threads", omp_get_max_threads())
        .integer(count_key, static_cast<std::int64_t>(count));
    return js;
}

void add_lattice_summary(io::JsonObject& js, const lbm::FluidSettings& fs, double worst_mass_drift,
                         double wall_s, double cell_updates) {
    js.number("dx_m", fs.units.dx())
        .number("tau", fs.rheology.tau)
        .number("tau_requested", fs.numbers.tau)
        .number("mach", fs.numbers.mach)
        .text("storage", fs.single_precision ? "float32" : "float64")
        .text("lattice_device", fs.on_opencl ? "opencl" : "cpu")
        .text("opencl_device", fs.on_opencl ? fs.opencl_device.platform + ": " + fs.opencl_device.name : "")
        .number("max_relative_mass_drift", worst_mass_drift)
        .number("wall_time_s", wall_s)
        .number("cell_updates_per_s", cell_updates / wall_s);
}

std::string ended_by(const RunEnd& end) {
    return end.exit_code == 0 ? std::string(name(end.ending)) : run_status(end.exit_code);
}

void add_grain_rate(io::JsonObject& js, std::size_t list_builds, double wall_s, double particle_steps) {
    js.integer("neighbor_list_builds", static_cast<std::int64_t>(list_builds))
        .number("wall_time_s", wall_s)
        .number("particle_steps_per_s", particle_steps / wall_s);
}

void log_expected_overlap(double velocity_scale, double overlap_over_d, std::string_view d_what) {
    const std::string text =
        fmt::format("expected max overlap (grain at {:.2f} m/s on a fixed one): {:.2f} % of {}",
                    velocity_scale, 100.0 * overlap_over_d, d_what);
    if (overlap_over_d > 0.02)
        spdlog::warn(
            "{}, above the recommended 2 % (stiffer contacts, or accept it: docs/dem.md, \"Overlap\")", text);
    else
        spdlog::info("{} (recommended < 2 %)", text);
}

void warn_large_overlap(double max_overlap_over_d, std::string_view remedy) {
    if (max_overlap_over_d > 0.02)
        spdlog::warn("max overlap {:.2f} % of a diameter exceeded the recommended 2 % ({})",
                     100.0 * max_overlap_over_d, remedy);
}

}  // namespace sabo::sim
