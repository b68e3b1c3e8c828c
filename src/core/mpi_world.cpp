// SPDX-License-Identifier: MIT
#include "core/mpi_world.h"

#include <cstdio>
#include <cstdlib>
#include <string_view>

#ifdef SABO_HAVE_MPI
#include <mpi.h>
#endif

extern char** environ;

namespace sabo {

namespace {

// Variables by which OpenMPI, MPICH/Slurm (PMI) and PMIx launchers tell a process its rank.
constexpr std::string_view launcher_prefixes[] = {"OMPI_", "PMIX_", "PMI_"};

bool launcher_variable(std::string_view entry) {
    for (const auto prefix : launcher_prefixes)
        if (entry.starts_with(prefix)) return true;
    return false;
}

}  // namespace

bool MpiWorld::built_with_mpi() {
#ifdef SABO_HAVE_MPI
    return true;
#else
    return false;
#endif
}

bool MpiWorld::started_by_launcher() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
           std::getenv("PMIX_RANK") != nullptr;
}

int MpiWorld::launcher_size() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
        if (const char* v = std::getenv(name)) {
            const int n = std::atoi(v);
            if (n > 0) return n;
        }
    }
    return 1;
}

std::vector<std::string> MpiWorld::environment_for_children() {
    std::vector<std::string> env;
    for (char** e = environ; *e != nullptr; ++e)
        if (!launcher_variable(*e)) env.emplace_back(*e);
    return env;
}

#ifdef SABO_HAVE_MPI

MpiWorld::MpiWorld(int& argc, char**& argv) {
    if (!started_by_launcher()) return;
    int provided = 0;
    // Only the main thread calls MPI; OpenMP threads inside a rank never do.
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    initialised_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local_size_);
    MPI_Comm_rank(node, &local_rank_);
    MPI_Comm_free(&node);
}

MpiWorld::~MpiWorld() {
    if (initialised_) MPI_Finalize();
}

void MpiWorld::barrier() const {
    if (initialised_) MPI_Barrier(MPI_COMM_WORLD);
}

void MpiWorld::abort(int code) const {
    std::fflush(nullptr);
    if (initialised_) MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
}

std::int64_t MpiWorld::sum(std::int64_t value) const {
    if (!initialised_) return value;
    std::int64_t total = 0;
    MPI_Allreduce(&value, &total, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    return total;
}

std::int64_t MpiWorld::max(std::int64_t value) const {
    if (!initialised_) return value;
    std::int64_t largest = 0;
    MPI_Allreduce(&value, &largest, 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
    return largest;
}

void MpiWorld::sum_reals(std::span<double> values) const {
    if (initialised_ && !values.empty())
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM,
                      MPI_COMM_WORLD);
}

void MpiWorld::max_reals(std::span<double> values) const {
    if (initialised_ && !values.empty())
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX,
                      MPI_COMM_WORLD);
}

void MpiWorld::send_receive(std::span<const std::byte> send, int to, std::span<std::byte> receive,
                            int from) const {
    if (!initialised_) return;
    MPI_Sendrecv(send.data(), static_cast<int>(send.size()), MPI_BYTE, to < 0 ? MPI_PROC_NULL : to, 0,
                 receive.data(), static_cast<int>(receive.size()), MPI_BYTE, from < 0 ? MPI_PROC_NULL : from,
                 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

void MpiWorld::all_gather(std::span<const std::byte> mine, std::vector<std::byte>& all) const {
    if (!initialised_) {
        all.assign(mine.begin(), mine.end());
        return;
    }
    counts_.resize(static_cast<std::size_t>(size_));
    offsets_.resize(static_cast<std::size_t>(size_));
    const int own = static_cast<int>(mine.size());
    MPI_Allgather(&own, 1, MPI_INT, counts_.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int total = 0;
    for (std::size_t r = 0; r < counts_.size(); ++r) {
        offsets_[r] = total;
        total += counts_[r];
    }
    all.resize(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), own, MPI_BYTE, all.data(), counts_.data(), offsets_.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
}

#else

MpiWorld::MpiWorld(int& /*argc*/, char**& /*argv*/) {}
void MpiWorld::send_receive(std::span<const std::byte> /*send*/, int /*to*/, std::span<std::byte> /*receive*/,
                            int /*from*/) const {}
MpiWorld::~MpiWorld() = default;
void MpiWorld::all_gather(std::span<const std::byte> mine, std::vector<std::byte>& all) const {
    all.assign(mine.begin(), mine.end());
}
void MpiWorld::barrier() const {}
void MpiWorld::abort(int code) const {
    std::fflush(nullptr);
    std::exit(code);
}
std::int64_t MpiWorld::sum(std::int64_t value) const {
    return value;
}
std::int64_t MpiWorld::max(std::int64_t value) const {
    return value;
}
void MpiWorld::sum_reals(std::span<double> /*values*/) const {}
void MpiWorld::max_reals(std::span<double> /*values*/) const {}

#endif

}  // namespace sabo
