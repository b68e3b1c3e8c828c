// SPDX-License-Identifier: MIT
// Lattice Boltzmann throughput (bench/README.md): a closed box 2N x N x N with an obstacle block in
// the middle (a barrier), every other cell fluid, driven by a body force; reports million fluid-cell
// updates per second (MLUPS) and the memory traffic that implies. Threads: OMP_NUM_THREADS.
//   lbm_throughput [--n N] [--steps S] [--float] [--bingham]
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cstring>
#include <string>

#include "lbm/fluid_lattice.h"

using namespace sabo;
using namespace sabo::lbm;

template <class Real>
void run(int n, int steps, bool bingham) {
    Rheology rh;
    rh.tau = 0.6;
    rh.bingham = bingham;
    rh.nu_plastic = 0.02;
    rh.yield = 1e-6;
    const GridShape shape{2 * n, n, n, {false, false, false}};
    FluidLattice<Real> l(shape, rh);
    const auto barrier = l.add_element();
    std::size_t fluid = 0;
    for (int z = 0; z < shape.nz; ++z)
        for (int y = 0; y < shape.ny; ++y)
            for (int x = 0; x < shape.nx; ++x) {
                if (x >= n - 1 && x <= n && z < n / 2 && (y < n / 3 || y >= 2 * n / 3)) {
                    l.set_obstacle(x, y, z, barrier);
                } else {
                    l.set_fluid(x, y, z, 1.0, {});
                    ++fluid;
                }
            }
    l.prepare();
    l.set_acceleration({1e-6, 0.0, -1e-7});
    for (int k = 0; k < 2; ++k) l.step();  // warm-up (first touch)
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) l.step();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double mlups = static_cast<double>(fluid) * steps / s / 1e6;
    // each update reads and writes 19 populations and reads/writes τ, reads the cell type
    const double bytes = 2.0 * Q * sizeof(Real) + 2.0 * sizeof(Real) + 2.0;
    fmt::print(
        "RESULT lbm {} {} n={} cells={} fluid={} threads={} steps={} time_s={:.3f} MLUPS={:.2f} GB_s={:.2f} "
        "barrier_fx={:.6e}\n",
        sizeof(Real) == 4 ? "float32" : "float64", bingham ? "bingham" : "newtonian", n, shape.cells(), fluid,
        omp_get_max_threads(), steps, s, mlups, mlups * bytes / 1e3, l.element_forces()[barrier].x);
}

int main(int argc, char** argv) {
    int n = 48, steps = 100;
    bool single = false, bingham = false;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--n" && a + 1 < argc)
            n = std::stoi(argv[++a]);
        else if (arg == "--steps" && a + 1 < argc)
            steps = std::stoi(argv[++a]);
        else if (arg == "--float")
            single = true;
        else if (arg == "--bingham")
            bingham = true;
        else {
            fmt::print(stderr, "usage: lbm_throughput [--n N] [--steps S] [--float] [--bingham]\n");
            return 2;
        }
    }
    if (single)
        run<float>(n, steps, bingham);
    else
        run<double>(n, steps, bingham);
}
