// SPDX-License-Identifier: MIT
// Lattice Boltzmann throughput (bench/README.md), in million fluid-cell updates per second (MLUPS:
// fluid and interface cells the steps updated, gas and obstacle cells not counted), with the memory
// traffic that implies and the roofline it allows on a given bandwidth. Threads: OMP_NUM_THREADS.
//   lbm_throughput [--setup periodic|barrier|dam_break] [--n N] [--steps S] [--float] [--bingham]
//                  [--bandwidth GB_S | --paired-triad MIB] [--device cpu|opencl] [--opencl-device SPEC]
//                  [--profile]
// --device opencl: the steps on an OpenCL device (docs/lbm.md, "Backends"; SPEC as lattice.opencl_device:
// empty for the first GPU, an index or part of the name), timed from the first to the last step's end
// (the state set up and copied there before, not read back); --profile adds the device's time per kernel.
// Set-ups:
//   periodic   N³ box, periodic on every axis, all fluid, a body force (the bulk kernel)
//   barrier    closed box 2N x N x N with a barrier-like block in the middle, body force
//   dam_break  N³ closed box, a column N/2 wide and N/2 high collapsing under gravity (the full
//              free-surface step: interface cells, mass exchange, conversions)
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "lbm/fluid_lattice.h"
#include "lbm/opencl/opencl_lattice.h"
#include "triad.h"

using namespace sabo;
using namespace sabo::lbm;

namespace {

struct Options {
    std::string setup = "barrier";
    int n = 48, steps = 100;
    bool single = false, bingham = false;
    double bandwidth = 0.0;  // GB/s for the roofline (memory_bandwidth's with-write-allocate figure)
    std::size_t paired_triad_mib = 0;  // > 0: a triad (arrays of this many MiB) around every pair of steps
    std::string device = "cpu", opencl_device;
    bool profile = false;  // --profile (OpenCL): the device's time per kernel
};

// The steps on an OpenCL device: one RESULT line as the CPU's (no per-parity times).
template <class Real>
void run_on_device(FluidLattice<Real>& l, const Options& o) {
    const auto device = opencl::choose_device(o.opencl_device, "--opencl-device");
    opencl::OpenClLattice<Real> d(l, device, o.profile);
    // warm-up: the kernels' first launch; the dam break runs a while, as on the CPU
    d.step(o.setup == "dam_break" ? static_cast<std::uint64_t>(o.n) : 2);
    d.wait();
    if (o.profile) (void)d.kernel_seconds();  // (the warm-up's)
    const auto start = std::chrono::steady_clock::now();
    d.step(static_cast<std::uint64_t>(o.steps));
    d.wait();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double updated = static_cast<double>(d.updated_cells());
    const double bytes = 2.0 * Q * sizeof(Real) + 2.0 + (o.bingham ? 2.0 * sizeof(Real) : 0.0);
    const double mlups = updated * o.steps / seconds / 1e6;
    fmt::print(
        "RESULT lbm setup={} {} {} n={} cells={} updated_per_step={:.0f} device=\"{}\" steps={} "
        "time_s={:.3f} "
        "MLUPS={:.2f} GB_s={:.2f} bytes_per_update={:.0f}\n",
        o.setup, sizeof(Real) == 4 ? "float32" : "float64", o.bingham ? "bingham" : "newtonian", o.n,
        l.shape().cells(), updated, device.name, o.steps, seconds, mlups, mlups * bytes / 1e3, bytes);
    if (!o.profile) return;
    double total = 0.0;
    const auto kernels = d.kernel_seconds();
    for (const auto& k : kernels) total += k.second;
    for (const auto& [name, s] : kernels)
        fmt::print("KERNEL {:<22} {:8.3f} ms/step {:5.1f} %\n", name, 1e3 * s / o.steps, 100.0 * s / total);
    fmt::print("KERNEL total {:.3f} ms/step of {:.3f} ms/step wall\n", 1e3 * total / o.steps,
               1e3 * seconds / o.steps);
}

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
    if (o.device == "opencl") {
        run_on_device(l, o);
        return;
    }
    // warm-up (first touch); the dam break runs a while so the column is moving and the surface spread
    const int warm = o.setup == "dam_break" ? o.n : 2;
    for (int k = 0; k < warm; ++k) l.step();
    // --paired-triad: every pair of steps (an even and an odd one) between two triad passes, so that the
    // pair's traffic is compared with the bandwidth of the same moment: a shared machine's bandwidth can
    // change within seconds, and a roofline measured apart from the run then says little. Pairs whose two
    // triads differ by more than 10 % (the bandwidth changed meanwhile) are set aside.
    std::unique_ptr<bench::Triad> triad;
    if (o.paired_triad_mib > 0) triad = std::make_unique<bench::Triad>(o.paired_triad_mib);
    std::vector<double> pair_fraction, pair_bandwidth;
    pair_fraction.reserve(static_cast<std::size_t>(o.steps));
    pair_bandwidth.reserve(static_cast<std::size_t>(o.steps));
    // each update reads and writes 19 populations and reads the cell type and wall flag; Bingham also
    // reads and writes τ (the free surface's own traffic is extra, on the interface cells only)
    const double bytes = 2.0 * Q * sizeof(Real) + 2.0 + (o.bingham ? 2.0 * sizeof(Real) : 0.0);
    double updates = 0.0, stepped_s = 0.0;
    const auto surface_before = l.surface_pass_seconds();
    // the AA pattern's two kinds of step (even: own slots; odd: the neighbours') timed apart
    double parity_s[2] = {0.0, 0.0};
    int parity_steps[2] = {0, 0};
    double pair_s = 0.0, pair_updates = 0.0, bandwidth_before = 0.0;
    for (int k = 0; k < o.steps; ++k) {
        if (triad && k % 2 == 0) bandwidth_before = triad->write_allocate_bytes() / triad->pass() / 1e9;
        const std::size_t parity = l.steps() % 2;
        const auto start = std::chrono::steady_clock::now();
        l.step();
        const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto updated = static_cast<double>(l.updated_cells());
        updates += updated;
        stepped_s += dt;
        parity_s[parity] += dt;
        ++parity_steps[parity];
        pair_s += dt;
        pair_updates += updated;
        if (triad && k % 2 == 1) {
            const double after = triad->write_allocate_bytes() / triad->pass() / 1e9;
            const double mean = 0.5 * (bandwidth_before + after);
            if (std::abs(after - bandwidth_before) <= 0.1 * std::max(after, bandwidth_before)) {
                pair_fraction.push_back(pair_updates * bytes / pair_s / 1e9 / mean);
                pair_bandwidth.push_back(mean);
            }
            pair_s = pair_updates = 0.0;
        }
    }
    const double mlups = updates / stepped_s / 1e6;
    const auto median = [](std::vector<double> v) {
        if (v.empty()) return 0.0;
        std::sort(v.begin(), v.end());
        return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
    };
    // the roofline: the bandwidth given, or the median of the paired triads (and then the fraction is the
    // median of the pairs' own fractions)
    const double bandwidth = triad ? median(pair_bandwidth) : o.bandwidth;
    const double roofline = bandwidth > 0.0 ? bandwidth * 1e3 / bytes : 0.0;
    const double fraction = triad ? median(pair_fraction) : (roofline > 0.0 ? mlups / roofline : 0.0);
    fmt::print(
        "RESULT lbm setup={} {} {} n={} cells={} updated_per_step={:.0f} interface={} threads={} steps={} "
        "time_s={:.3f} MLUPS={:.2f} GB_s={:.2f} bytes_per_update={:.0f} roofline_MLUPS={:.1f} "
        "fraction_of_roofline={:.2f} even_step_ms={:.1f} odd_step_ms={:.1f}",
        o.setup, sizeof(Real) == 4 ? "float32" : "float64", o.bingham ? "bingham" : "newtonian", o.n,
        shape.cells(), updates / o.steps, l.interface_count(), omp_get_max_threads(), o.steps, stepped_s,
        mlups, mlups * bytes / 1e3, bytes, roofline, fraction,
        1e3 * parity_s[0] / std::max(1, parity_steps[0]), 1e3 * parity_s[1] / std::max(1, parity_steps[1]));
    const auto& surface = l.surface_pass_seconds();
    fmt::print(" surface_exchange_s={:.3f} surface_conversions_s={:.3f} surface_prepare_s={:.3f}",
               surface.exchange - surface_before.exchange, surface.conversions - surface_before.conversions,
               surface.prepare - surface_before.prepare);
    if (triad)
        fmt::print(" paired_triad_GB_s={:.1f} pairs_used={}/{} triad_check={}", bandwidth,
                   pair_fraction.size(), o.steps / 2, triad->check() ? "ok" : "FAILED");
    fmt::print("\n");
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
        else if (arg == "--paired-triad" && a + 1 < argc)
            o.paired_triad_mib = std::stoul(argv[++a]);
        else if (arg == "--float")
            o.single = true;
        else if (arg == "--bingham")
            o.bingham = true;
        else if (arg == "--device" && a + 1 < argc)
            o.device = argv[++a];
        else if (arg == "--opencl-device" && a + 1 < argc)
            o.opencl_device = argv[++a];
        else if (arg == "--profile")
            o.profile = true;
        else
            o.n = 0;  // usage below
    }
    if ((o.setup != "periodic" && o.setup != "barrier" && o.setup != "dam_break") || o.n < 4 ||
        (o.device != "cpu" && o.device != "opencl")) {
        fmt::print(stderr,
                   "usage: lbm_throughput [--setup periodic|barrier|dam_break] [--n N] [--steps S] [--float] "
                   "[--bingham] [--bandwidth GB_S | --paired-triad MIB] [--device cpu|opencl] "
                   "[--opencl-device SPEC] [--profile]\n");
        return 2;
    }
    try {
        if (o.single)
            run<float>(o);
        else
            run<double>(o);
    } catch (const std::exception& e) {
        fmt::print(stderr, "lbm_throughput: {}\n", e.what());
        return 2;
    }
}
