// SPDX-License-Identifier: MIT
#include "sim/run_checkpoint.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/stopwatch.h"
#include "io/checkpoint.h"

namespace sabo::sim {

namespace {

std::filesystem::path checkpoint_file(const std::filesystem::path& out_dir, const parallel::Domain& domain) {
    return out_dir /
           (domain.divided() ? fmt::format("checkpoint.rank{}.bin", domain.world->rank()) : "checkpoint.bin");
}

}  // namespace

RunCheckpoint::RunCheckpoint(const std::filesystem::path& out_dir, const Config& cfg,
                             const parallel::Domain& domain)
    : domain_(domain),
      file_(checkpoint_file(out_dir, domain)),
      identity_((domain.divided() ? fmt::format("mpi_ranks = {}\n", domain.ranks()) : std::string()) +
                io::case_identity(cfg)) {}

void RunCheckpoint::load(Simulation& sim, const std::vector<Observer*>& observers) {
    // the ranks of a divided run refuse together (one left alone would wait for the others)
    std::string refused;
    try {
        read(sim, observers);
    } catch (const InputError& e) {
        refused = e.what();
    }
    if (domain_.divided()) {
        if (domain_.any(!refused.empty()))
            throw InputError(!refused.empty() ? refused
                                              : fmt::format("{}: another rank's checkpoint was refused (its "
                                                            "message says why)",
                                                            file_.string()));
        const auto step = static_cast<double>(sim.steps());
        if (domain_.max(step) != -domain_.max(-step))
            throw InputError(
                fmt::format("{}: the ranks' checkpoints are of different steps (the run stopped while "
                            "they were being written); the run cannot continue from them",
                            file_.parent_path().string()));
    } else if (!refused.empty()) {
        throw InputError(refused);
    }
    spdlog::info("resumed from {} at t = {:.4f} s (step {})", file_.string(), sim.time(), sim.steps());
}

void RunCheckpoint::read(Simulation& sim, const std::vector<Observer*>& observers) {
    if (!std::filesystem::exists(file_)) {
        const std::filesystem::path dir = file_.parent_path();
        int ranks = 0;
        while (std::filesystem::exists(dir / fmt::format("checkpoint.rank{}.bin", ranks))) ++ranks;
        if (domain_.divided() && std::filesystem::exists(dir / "checkpoint.bin"))
            throw InputError(
                fmt::format("{}: the run ran as one process (checkpoint.bin): resume it as one, "
                            "without mpirun",
                            dir.string()));
        if (ranks > 0 && !domain_.divided())
            throw InputError(
                fmt::format("{}: the run was divided among {} MPI ranks (checkpoint.rank*.bin): resume "
                            "it with as many, `mpirun -np {} sabo resume {}`",
                            dir.string(), ranks, ranks, dir.string()));
        throw InputError(fmt::format(
            "no checkpoint {} to resume from (a run writes one every output.checkpoint_interval_wall_s, when "
            "interrupted and at its end{})",
            file_.string(),
            domain_.divided()
                ? fmt::format("; a run divided among ranks resumes with as many ranks, and this "
                              "folder has {} rank checkpoints",
                              ranks)
                : ""));
    }
    io::CheckpointIn in(file_);
    std::string identity;
    in(identity);
    io::check_same_case(file_, identity, identity_);
    in(wall_before_, work_before_, ended_by_, sim);
    for (Observer* o : observers) o->load(in);
    in.expect_end();
}

void RunCheckpoint::save(Simulation& sim, const std::vector<Observer*>& observers, double wall_s, double work,
                         const std::string& ended_by) {
    const auto start = std::chrono::steady_clock::now();
    io::CheckpointOut out(file_);
    const double wall = wall_before_ + wall_s, all_work = work_before_ + work;
    out(identity_, wall, all_work, ended_by, sim);
    for (Observer* o : observers) o->save(out);
    out.commit();
    spdlog::debug("checkpoint at t = {:.4f} s (step {}): {:.1f} MB in {:.3f} s", sim.time(), sim.steps(),
                  static_cast<double>(std::filesystem::file_size(file_)) / 1e6, seconds_since(start));
}

void RunCheckpoint::schedule(Schedule& at, const OutputSettings& every, Simulation& sim,
                             const std::vector<Observer*>& observers, const RunControl& control,
                             bool resumed) {
    at.start_outputs = !resumed;
    at.stopped = resumed && ended_by_ == name(RunEnding::complete_stop);
    at.checkpoint_wall_s = every.checkpoint_wall_s;
    at.checkpoint_every =
        every.checkpoint_sim_s > 0.0
            ? std::max<std::uint64_t>(
                  1, static_cast<std::uint64_t>(std::llround(every.checkpoint_sim_s / sim.dt())))
            : 0;
    at.checkpoint = [this, &sim, observers, &control](double work, const std::string& ended_by) {
        save(sim, observers, control.elapsed_s(), work, ended_by);
    };
}

void RunCheckpoint::tell_how_to_resume(int exit_code) const {
    if (exit_code != 130) return;
    spdlog::warn("the state is in {}: continue the run with `{}sabo resume {}`", file_.string(),
                 domain_.divided() ? fmt::format("mpirun -np {} ", domain_.ranks()) : "",
                 file_.parent_path().string());
}

}  // namespace sabo::sim
