// SPDX-License-Identifier: MIT
// Memory bandwidth, STREAM-like (McCalpin's triad a = b + s c), the roofline the lattice Boltzmann
// kernel is measured against (bench/README.md). Three arrays far larger than the caches, first
// touched by the threads that use them; the best of the repeats is reported, counted two ways:
// STREAM's convention (3 words per element) and the traffic the hardware really moves with
// write-allocate (4 words: the destination line is read before it is written). An in-place kernel
// such as the AA-pattern LBM reads every line it writes, so its traffic compares with the second.
// Threads: OMP_NUM_THREADS.
//   memory_bandwidth [--mib M] [--repeats R]
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

int main(int argc, char** argv) {
    std::size_t mib = 512;  // per array
    int repeats = 10;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--mib" && a + 1 < argc)
            mib = std::stoul(argv[++a]);
        else if (arg == "--repeats" && a + 1 < argc)
            repeats = std::stoi(argv[++a]);
        else {
            fmt::print(stderr, "usage: memory_bandwidth [--mib M] [--repeats R]\n");
            return 2;
        }
    }
    const std::size_t n = mib * 1024 * 1024 / sizeof(double);
    // no value-initialisation here: the first touch below places the pages with the threads
    const std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
    double* const pa = a.get();
    double* const pb = b.get();
    double* const pc = c.get();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        pa[i] = 0.0;
        pb[i] = 1.0;
        pc[i] = 2.0;
    }
    const double s = 3.0;
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    // a check that the triad ran (and that the compiler kept it)
    double sum = 0.0;
    for (std::size_t i = 0; i < n; i += 4096) sum += pa[i];
    const double words = static_cast<double>(n) * sizeof(double);
    fmt::print(
        "RESULT triad threads={} mib_per_array={} best_s={:.4f} GB_s_stream={:.2f} "
        "GB_s_with_write_allocate={:.2f} "
        "check={}\n",
        omp_get_max_threads(), mib, best, 3.0 * words / best / 1e9, 4.0 * words / best / 1e9,
        sum == 7.0 * static_cast<double>((n + 4095) / 4096) ? "ok" : "FAILED");
    return 0;
}
