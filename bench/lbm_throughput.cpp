// SPDX-License-Identifier: MIT
// Lattice Boltzmann throughput (bench/README.md), in million fluid-cell updates per second (MLUPS:
// fluid and interface cells the steps updated, gas and obstacle cells not counted), with the memory
// traffic that implies and the roofline it allows on a given bandwidth. Threads: OMP_NUM_THREADS.
//   lbm_throughput [--setup periodic|barrier|dam_break] [--n N] [--steps S] [--float] [--bingham]
//                  [--bandwidth GB_S]
// Set-ups:
//   periodic   N³ box, periodic on every axis, all fluid, a body force (the bulk kernel)
//   barrier    closed box 2N x N x N with a barrier-like block in the middle, body force
//   dam_break  N³ closed box, a column N/2 wide and N/2 high collapsing under gravity (the full
//              free-surface step: interface cells, mass exchange, conversions)
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cstring>
#include <string>

#include "lbm/fluid_lattice.h"

using namespace sabo;
using namespace sabo::lbm;

namespace {

struct Options {
    std::string setup = "barrier";
    int n = 48, steps = 100;
    bool single = false, bingham = false;
    double bandwidth = 0.0;  // GB/s for the roofline (memory_bandwidth's with-write-allocate figure)
};

template <class Real>
void build(FluidLattice<Real>& l, const Options& o) {
    const GridShape& s = l.shape();
    const int n = o.n;
    if (o.setup == "periodic") {
        for (int z = 0; z < s.nz; ++z)
            for (int y = 0; y < s.ny; ++y)
                for (int x = 0; x < s.nx; ++x) l.set_fluid(x, y, z, 1.0, {});
        l.set_acceleration({1e-6, 0.0, 0.0});
    } else if (o.setup == "barrier") {
        const auto barrier = l.add_element();
        for (int z = 0; z < s.nz; ++z)
            for (int y = 0; y < s.ny; ++y)
                for (int x = 0; x < s.nx; ++x) {
                    if (x >= n - 1 && x <= n && z < n / 2 && (y < n / 3 || y >= 2 * n / 3))
                        l.set_obstacle(x, y, z, barrier);
                    else
                        l.set_fluid(x, y, z, 1.0, {});
                }
        l.set_acceleration({1e-6, 0.0, -1e-7});
    } else {
        // column of water at hydrostatic density; prepare() makes its faces toward the gas interface cells
        const double g = 1e-4;
        const int h = n / 2;
        for (int z = 0; z < h; ++z)
            for (int y = 0; y < s.ny; ++y)
                for (int x = 0; x < n / 2; ++x) l.set_fluid(x, y, z, 1.0 + 3.0 * g * (h - 0.5 - z), {});
        l.set_acceleration({0.0, 0.0, -g});
    }
    l.prepare();
}

template <class Real>
void run(const Options& o) {
    Rheology rh;
    rh.tau = 0.6;
    rh.bingham = o.bingham;
    rh.nu_plastic = 0.02;
    rh.yield = 1e-6;
    const bool periodic = o.setup == "periodic";
    const GridShape shape{o.setup == "barrier" ? 2 * o.n : o.n, o.n, o.n, {periodic, periodic, periodic}};
    FluidLattice<Real> l(shape, rh);
    build(l, o);
    // warm-up (first touch); the dam break runs a while so the column is moving and the surface spread
    const int warm = o.setup == "dam_break" ? o.n : 2;
    for (int k = 0; k < warm; ++k) l.step();
    double updates = 0.0;
    // the AA pattern's two kinds of step (even: own slots; odd: the neighbours') timed apart
    double parity_s[2] = {0.0, 0.0};
    int parity_steps[2] = {0, 0};
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    for (int k = 0; k < o.steps; ++k) {
        const std::size_t parity = l.steps() % 2;
        l.step();
        updates += static_cast<double>(l.updated_cells());
        const auto now = std::chrono::steady_clock::now();
        parity_s[parity] += std::chrono::duration<double>(now - last).count();
        ++parity_steps[parity];
        last = now;
    }
    const double s = std::chrono::duration<double>(last - t0).count();
    const double mlups = updates / s / 1e6;
    // each update reads and writes 19 populations and reads the cell type and wall flag; Bingham also
    // reads and writes τ (the free surface's own traffic is extra, on the interface cells only)
    const double bytes = 2.0 * Q * sizeof(Real) + 2.0 + (o.bingham ? 2.0 * sizeof(Real) : 0.0);
    const double roofline = o.bandwidth > 0.0 ? o.bandwidth * 1e3 / bytes : 0.0;
    fmt::print(
        "RESULT lbm setup={} {} {} n={} cells={} updated_per_step={:.0f} interface={} threads={} steps={} "
        "time_s={:.3f} MLUPS={:.2f} GB_s={:.2f} bytes_per_update={:.0f} roofline_MLUPS={:.1f} "
        "fraction_of_roofline={:.2f} even_step_ms={:.1f} odd_step_ms={:.1f}\n",
        o.setup, sizeof(Real) == 4 ? "float32" : "float64", o.bingham ? "bingham" : "newtonian", o.n,
        shape.cells(), updates / o.steps, l.interface_count(), omp_get_max_threads(), o.steps, s, mlups,
        mlups * bytes / 1e3, bytes, roofline, roofline > 0.0 ? mlups / roofline : 0.0,
        1e3 * parity_s[0] / std::max(1, parity_steps[0]), 1e3 * parity_s[1] / std::max(1, parity_steps[1]));
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        if (arg == "--setup" && a + 1 < argc)
            o.setup = argv[++a];
        else if (arg == "--n" && a + 1 < argc)
            o.n = std::stoi(argv[++a]);
        else if (arg == "--steps" && a + 1 < argc)
            o.steps = std::stoi(argv[++a]);
        else if (arg == "--bandwidth" && a + 1 < argc)
            o.bandwidth = std::stod(argv[++a]);
        else if (arg == "--float")
            o.single = true;
        else if (arg == "--bingham")
            o.bingham = true;
        else
            o.n = 0;  // usage below
    }
    if ((o.setup != "periodic" && o.setup != "barrier" && o.setup != "dam_break") || o.n < 4) {
        fmt::print(stderr,
                   "usage: lbm_throughput [--setup periodic|barrier|dam_break] [--n N] [--steps S] [--float] "
                   "[--bingham] [--bandwidth GB_S]\n");
        return 2;
    }
    if (o.single)
        run<float>(o);
    else
        run<double>(o);
}
