// SPDX-License-Identifier: MIT
// The processes this program runs among when an MPI launcher (mpirun, srun) starts it: their number and
// this one's rank, a barrier and a sum (docs/distributed.md). Without MPI at build time, or when no
// launcher started the program, it is one process, rank 0 of 1, and every call is local.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace sabo {

class MpiWorld {
  public:
    // Initialises MPI when an MPI launcher started this process; finalises it on destruction.
    MpiWorld(int& argc, char**& argv);
    ~MpiWorld();
    MpiWorld(const MpiWorld&) = delete;
    MpiWorld& operator=(const MpiWorld&) = delete;

    [[nodiscard]] int rank() const { return rank_; }
    [[nodiscard]] int size() const { return size_; }
    // The ranks on this machine (sharing its cores), this one included.
    [[nodiscard]] int local_size() const { return local_size_; }
    // This one's place among them (0 … local_size() − 1).
    [[nodiscard]] int local_rank() const { return local_rank_; }
    void barrier() const;
    // Ends every rank's process with `code` (a failure on one rank that the others would wait for).
    [[noreturn]] void abort(int code) const;
    [[nodiscard]] std::int64_t sum(std::int64_t value) const;
    [[nodiscard]] std::int64_t max(std::int64_t value) const;
    // The same for reals (a sum's rounding depends on the number of ranks).
    [[nodiscard]] double sum_real(double value) const {
        sum_reals(std::span(&value, 1));
        return value;
    }
    [[nodiscard]] double max_real(double value) const {
        max_reals(std::span(&value, 1));
        return value;
    }
    // Element by element over the ranks, in place.
    void sum_reals(std::span<double> values) const;
    void max_reals(std::span<double> values) const;
    // Each vector's components summed over the ranks, in place, through `scratch` (x y z per vector).
    void sum_vectors(std::span<Vec3> values, std::vector<double>& scratch) const {
        scratch.resize(3 * values.size());
        for (std::size_t k = 0; k < values.size(); ++k)
            for (int a = 0; a < 3; ++a) scratch[3 * k + static_cast<std::size_t>(a)] = values[k][a];
        sum_reals(scratch);
        for (std::size_t k = 0; k < values.size(); ++k)
            values[k] = {scratch[3 * k], scratch[3 * k + 1], scratch[3 * k + 2]};
    }
    // Sends `send` to rank `to` while receiving `receive` from rank `from` (either may be -1: none), as
    // bytes; the two ranks must agree on the sizes. With one process, to and from must be -1.
    void send_receive(std::span<const std::byte> send, int to, std::span<std::byte> receive, int from) const;
    // The same for blocks of any size: the size goes first, and `receive` takes the size of what `from`
    // sends (nothing when from is -1).
    void send_receive_block(std::span<const std::byte> send, int to, std::vector<std::byte>& receive,
                            int from) const {
        std::uint64_t size = send.size(), incoming = 0;
        send_receive(std::as_bytes(std::span(&size, 1)), to, std::as_writable_bytes(std::span(&incoming, 1)),
                     from);
        receive.resize(from >= 0 ? incoming : 0);
        send_receive(to >= 0 ? send : std::span<const std::byte>(), to, std::span(receive), from);
    }
    // Every rank's `mine` (any size each), concatenated in rank order into `all` on every rank (its capacity
    // is reused).
    void all_gather(std::span<const std::byte> mine, std::vector<std::byte>& all) const;

    // Whether Sabo was built with MPI.
    [[nodiscard]] static bool built_with_mpi();
    // Whether an MPI launcher started this process (its environment names a rank).
    [[nodiscard]] static bool started_by_launcher();
    // The number of processes the launcher says it started (1 when it does not say).
    [[nodiscard]] static int launcher_size();
    // This process's environment without the launcher's variables, for child processes that must not
    // take themselves for ranks ("NAME=value" strings).
    [[nodiscard]] static std::vector<std::string> environment_for_children();

  private:
    int rank_ = 0, size_ = 1, local_size_ = 1, local_rank_ = 0;
    mutable std::vector<int> counts_, offsets_;  // all_gather's per-rank sizes
    bool initialised_ = false;
};

}  // namespace sabo
