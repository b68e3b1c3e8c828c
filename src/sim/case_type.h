// SPDX-License-Identifier: MIT
// What a case type (case.type: src/cases/<type>/) gives the one run skeleton (sim/run_case.h): its keys
// read and checked, its derived numbers, its domain and Simulation, its observers in checkpoint order, what
// it does with the state at the end, its files and summary keys, and its report script. The skeleton holds
// everything every run does around them (the output folder, the loop, checkpoints, the division's
// summary, the resume hint), so a new case type is its folder and one line in the registry
// (cases/registry.cpp) — the driver hooks of MercuryDPM, without deriving from the solver.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/config.h"
#include "io/json_writer.h"
#include "parallel/domain.h"
#include "sim/case_settings.h"
#include "sim/observer.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/simulation.h"

namespace sabo::sim {

// The progress line of a case type's runs.
struct ProgressLine {
    std::size_t grains = 0;         // scales the first rates (the loop counts the real ones)
    bool ends_at_end_time = false;  // a run that cannot stop early: the ETA drops its "at most"
};

// What summary.json's first keys name (docs/outputs.md): the case, its type, and its size as a count of
// "particles" or "lattice_cells".
struct SummaryHead {
    std::string case_name, type, count_key;
    std::size_t count = 0;
};

// What the skeleton measured of the whole run (every part of a resumed one).
struct RunTotals {
    double wall_s = 0.0;  // s
    double work = 0.0;    // particle-steps or cell updates, summed over the ranks
};

class CaseType {
  public:
    virtual ~CaseType() = default;

    // --- `sabo check` and `sabo run`: reads and checks every key (cfg.finish() included; a bad key is an
    // InputError naming it), then prints the derived numbers.
    virtual void prepare(const RunRequest& req, const Config& cfg) = 0;
    virtual void print_derived() const = 0;

    // --- the run, after prepare()
    [[nodiscard]] virtual const OutputSettings& output() const = 0;
    [[nodiscard]] virtual double end_time() const = 0;  // s
    [[nodiscard]] virtual ProgressLine progress() const = 0;
    // The domain, divided among the ranks of `world` when one is given.
    [[nodiscard]] virtual parallel::Domain domain(const MpiWorld* world) const = 0;
    // The simulation at its start (a resumed run's state then comes from its checkpoint), on `domain`;
    // nothing when a stop was requested while it was being prepared (`control`).
    [[nodiscard]] virtual std::optional<Simulation> build(const parallel::Domain& domain, RunControl& control,
                                                          bool resume) = 0;
    // Its observers, in their checkpoint order; they live as long as the case type.
    [[nodiscard]] virtual std::vector<Observer*> observers(const Simulation& sim) = 0;
    // A last series row for the final state at the end (unless one was just taken).
    [[nodiscard]] virtual bool sample_at_end() const { return false; }

    // --- after the loop. Every rank: what the end needs of the final state (in a divided run the
    // collective calls: grain views, sums).
    virtual void finish(Simulation& sim, const RunEnd& end) = 0;
    // The first rank only, in this order: the case type's end files; what the header names; its summary keys
    // (after the header), returning the run's exit code (end.exit_code unless an end analysis failed); the
    // summary's last keys (wall time and rate); the end's log lines.
    virtual void write_end_files(const Simulation& sim, const RunEnd& end) = 0;
    [[nodiscard]] virtual SummaryHead summary_head(const Simulation& sim) const = 0;
    [[nodiscard]] virtual int summarise(io::JsonObject& js, const Simulation& sim, const RunEnd& end) = 0;
    virtual void summarise_rate(io::JsonObject& js, const RunTotals& totals) const = 0;
    virtual void log_end(const Simulation& sim, const RunEnd& end, const RunTotals& totals) const = 0;
    // python/ script that writes report.md (io/report_script.h).
    [[nodiscard]] virtual std::string report_script() const = 0;
};

}  // namespace sabo::sim
