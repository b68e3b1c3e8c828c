// SPDX-License-Identifier: MIT
// Memory bandwidth, STREAM-like (McCalpin's triad a = b + s c, triad.h), the roofline the lattice Boltzmann
// kernel is measured against (bench/README.md). The best of the repeats is reported, counted two ways:
// STREAM's convention (3 words per element) and the traffic the hardware really moves with write-allocate
// (4 words). Then a plain in-place update of 19 float32 streams (the AA lattice's memory pattern without its
// arithmetic): what an in-place kernel can reach here. Threads: OMP_NUM_THREADS.
//   memory_bandwidth [--mib M] [--repeats R]
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <memory>
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
    {
        sabo::bench::Triad triad(mib);
        double best = 1e300;
        for (int r = 0; r < repeats; ++r) best = std::min(best, triad.pass());
        fmt::print(
            "RESULT triad threads={} mib_per_array={} best_s={:.4f} GB_s_stream={:.2f} "
            "GB_s_with_write_allocate={:.2f} check={}\n",
            omp_get_max_threads(), mib, best, triad.stream_bytes() / best / 1e9,
            triad.write_allocate_bytes() / best / 1e9, triad.check() ? "ok" : "FAILED");
    }
    // What a plain in-place kernel with the lattice's 19 streams reaches (float32, no collision: each
    // cell's 19 values relax toward their mean): the pattern of an AA step without its arithmetic.
    const std::size_t cells = mib * 1024 * 1024 / 8 / sizeof(float);
    const std::size_t slot = (cells + 1023) / 1024 * 1024 + 48;  // staggered like the lattice's slots
    const std::unique_ptr<float[]> f(new float[19 * slot]);
    float* const pf = f.get();
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < cells; ++k)
        for (std::size_t q = 0; q < 19; ++q) pf[q * slot + k] = 1.0F;
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
        for (std::size_t block = 0; block < cells; block += 4096) {
            const std::size_t end = std::min(cells, block + 4096);
#pragma omp simd
            for (std::size_t k = block; k < end; ++k) {  // vectorised across cells, as the lattice's loop
                float mean = 0.0F;
#pragma GCC unroll 19
                for (std::size_t q = 0; q < 19; ++q) mean += pf[q * slot + k];
                mean *= 1.0F / 19.0F;
#pragma GCC unroll 19
                for (std::size_t q = 0; q < 19; ++q) pf[q * slot + k] = 0.5F * (pf[q * slot + k] + mean);
            }
        }
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const double bytes = 2.0 * 19.0 * sizeof(float) * static_cast<double>(cells);  // each line read, written
    fmt::print("RESULT inplace19 threads={} cells={} best_s={:.4f} GB_s={:.2f} MLUPS={:.1f} check={}\n",
               omp_get_max_threads(), cells, best, bytes / best / 1e9,
               static_cast<double>(cells) / best / 1e6,
               pf[0] == 1.0F && pf[18 * slot + cells - 1] == 1.0F ? "ok" : "FAILED");
    return 0;
}
