// SPDX-License-Identifier: MIT
// What every run writes around its time loop: the output folder with its log and resolved case, and the
// keys every summary.json starts and ends with (docs/outputs.md).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/config.h"
#include "io/json_writer.h"
#include "lbm/fluid_setup.h"
#include "sim/run_loop.h"
#include "sim/simulation.h"

namespace sabo::sim {

// In a run folder: the case as it was given (`sabo resume` reads it).
inline constexpr const char* resume_file_name = "resume.toml";

// How a run takes its output folder: a new run refuses a folder holding another run's outputs unless told
// to overwrite them (then it removes them first: io/run_folder_contents.h); a resumed run continues them.
enum class FolderUse { new_run, overwrite, resume };

// Creates the output folder, locks it, starts its sabo.log, logs the start line and writes case_resolved.toml
// and resume.toml.
// A run divided among ranks (`domain`): the first rank makes the folder and writes the run's files, the
// others wait for it and from then on log warnings and errors only; a refusal reaches every rank.
void open_run_folder(const std::filesystem::path& out_dir, const std::filesystem::path& case_file,
                     const Config& cfg, FolderUse use, const parallel::Domain& domain = {});

// The keys every summary.json starts with (docs/outputs.md): version, case, type, status (from the
// exit code: 0 completed, 130 interrupted, else failed), failure, ended_by, time, steps, Δt, threads,
// and the count `count_key` names ("particles", "lattice_cells").
[[nodiscard]] io::JsonObject summary_header(const std::string& case_name, const std::string& type,
                                            const RunEnd& end, const Simulation& sim,
                                            const std::string& count_key, std::size_t count);
[[nodiscard]] std::string run_status(int exit_code);
// How the run ended, as summary.json's ended_by says it: "end time" or "complete stop", else its status.
[[nodiscard]] std::string ended_by(const RunEnd& end);
// The summary.json keys a run of grains ends with: neighbor_list_builds, wall_time_s, particle_steps_per_s.
void add_grain_rate(io::JsonObject& js, std::size_t list_builds, double wall_s, double particle_steps);
// Warns when the largest overlap seen passed 2 % of a diameter (`remedy`: what to change).
void warn_large_overlap(double max_overlap_over_d, std::string_view remedy);
// Before a run: the overlap the contact law gives a grain at `velocity_scale` on a fixed one (of `d_what`,
// e.g. "d_min"), as information below the recommended 2 % and as a warning above it (the same rule as the
// largest overlap seen, warn_large_overlap).
void log_expected_overlap(double velocity_scale, double overlap_over_d, std::string_view d_what);

// A run divided among ranks: how many; how unequal the ranks' measured stepping time was (the largest over
// the mean: the parallel efficiency the division allowed is its inverse; their cell updates are a poor
// measure, an interface cell costing several bulk ones); the same for their cell updates; and the largest
// share of its wall time a rank spent in the halo exchange (waiting for a neighbour included). Collective:
// every rank calls it, with its own work.
struct DivisionSummary {
    int ranks = 1;
    double time_imbalance = 1.0, work_imbalance = 1.0, exchange_fraction = 0.0;
    std::uint64_t face_moves = 0;  // how often the slab faces moved
    std::vector<int> cuts;         // the faces at the end (global planes: rank r's are [cuts[r], cuts[r+1]))
    std::vector<double> grain_faces;  // grains alone: the faces at the end, x in m
};
[[nodiscard]] DivisionSummary summarise_division(const Simulation& sim, double work, double wall_s);
// Its keys (mpi_ranks, mpi_time_imbalance, mpi_work_imbalance, mpi_exchange_fraction, mpi_face_moves,
// mpi_slab_faces: lattice planes, or x in m for grains alone), none for a run on one process.
void add_division_summary(io::JsonObject& js, const DivisionSummary& d);

// summary.json's "timing" block (seconds this process spent in each phase of its steps, "other_s" the
// rest of `wall_s`, and "wall_s"; sim/phase_times.h; a divided run writes the first rank's), and the log
// line that says it in percent ("where the time went").
void add_timing(io::JsonObject& js, const Simulation& sim, double wall_s);
void log_timing(const Simulation& sim, double wall_s);

// The summary.json keys every lattice run adds after its own: the lattice (dx_m, tau as the cells relax,
// tau_requested, mach, storage), the mass conservation, the wall time and the rate.
void add_lattice_summary(io::JsonObject& js, const lbm::FluidSettings& fs, double worst_mass_drift,
                         double wall_s, double cell_updates);

}  // namespace sabo::sim
