// SPDX-License-Identifier: MIT
// Memory bandwidth, STREAM-like (McCalpin's triad a = b + s c, triad.h), the roofline the lattice Boltzmann
// kernel is measured against (bench/README.md). The best of the repeats is reported, counted two ways:
// STREAM's convention (3 words per element) and the traffic the hardware really moves with write-allocate
// (4 words). Threads: OMP_NUM_THREADS.
//   memory_bandwidth [--mib M] [--repeats R]
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <string>

#include "triad.h"

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
    sabo::bench::Triad triad(mib);
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) best = std::min(best, triad.pass());
    fmt::print(
        "RESULT triad threads={} mib_per_array={} best_s={:.4f} GB_s_stream={:.2f} "
        "GB_s_with_write_allocate={:.2f} check={}\n",
        omp_get_max_threads(), mib, best, triad.stream_bytes() / best / 1e9,
        triad.write_allocate_bytes() / best / 1e9, triad.check() ? "ok" : "FAILED");
    return 0;
}
