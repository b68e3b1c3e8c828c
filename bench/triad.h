// SPDX-License-Identifier: MIT
// McCalpin's triad a = b + s c over three arrays far larger than the caches, first touched by the threads
// that use them (OpenMP, static schedule): the memory bandwidth the lattice Boltzmann kernel is measured
// against (bench/README.md). One pass moves 3 words per element by STREAM's count and 4 with write-allocate
// (the destination line is read before it is written); an in-place kernel such as the AA-pattern LBM reads
// every line it writes, so its traffic compares with the second.
#pragma once

#include <omp.h>

#include <chrono>
#include <cstddef>
#include <memory>

namespace sabo::bench {

class Triad {
  public:
    explicit Triad(std::size_t mib_per_array)
        : n_(mib_per_array * 1024 * 1024 / sizeof(double)),
          a_(new double[n_]),
          b_(new double[n_]),
          c_(new double[n_]) {
        double* const a = a_.get();
        double* const b = b_.get();
        double* const c = c_.get();
        const std::size_t n = n_;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            a[i] = 0.0;
            b[i] = 1.0;
            c[i] = 2.0;
        }
    }

    // one pass, in seconds
    double pass() {
        double* const a = a_.get();
        const double* const b = b_.get();
        const double* const c = c_.get();
        const std::size_t n = n_;
        const double s = 3.0;
        const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    // bytes one pass moves: STREAM's count and with write-allocate
    [[nodiscard]] double stream_bytes() const {
        return 3.0 * static_cast<double>(n_) * sizeof(double);
    }
    [[nodiscard]] double write_allocate_bytes() const {
        return 4.0 * static_cast<double>(n_) * sizeof(double);
    }

    // whether the passes ran (and the compiler kept them): every a[i] is 1 + 3·2
    [[nodiscard]] bool check() const {
        for (std::size_t i = 0; i < n_; i += 4096)
            if (a_[i] != 7.0) return false;
        return true;
    }

  private:
    std::size_t n_;
    std::unique_ptr<double[]> a_, b_, c_;  // not value-initialised: the first touch places the pages
};

}  // namespace sabo::bench
