// SPDX-License-Identifier: MIT
// Grain–fluid coupled throughput (bench/README.md): a box of fluid N x N x N (periodic in x and y, walls in
// z) holding grains of d = 4 Δx (C5's resolution) on a cubic lattice at a given solid fraction, under
// gravity along a 35° slope; S coupled steps (the lattice step with the exchange, then n_sub DEM steps),
// timed by phase: finding the grain cells and their velocities, the lattice step, the drag summed per
// grain, the DEM sub-steps. Also the same lattice without grains. Threads: OMP_NUM_THREADS. --psm: partially
// saturated cells (coupling.model = "psm") instead of the cell-centre rule.
//   coupled_throughput [--n N] [--steps S] [--fraction F] [--substeps K] [--float] [--psm]
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "coupling/grain_fluid_coupling.h"
#include "dem/dem_setup.h"
#include "lbm/fluid_lattice.h"
#include "lbm/units.h"

using namespace sabo;

namespace {

struct Options {
    int n = 96, steps = 200, substeps = 2;
    double fraction = 0.35;
    bool single = false, psm = false;
};

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> fluid_box(const Options& o, const lbm::UnitConverter& u,
                                                   const Vec3& g) {
    lbm::Rheology rh;
    rh.tau = 0.516;  // C5 Newtonian at Δt = 2.5e-4 s
    auto l =
        std::make_unique<lbm::FluidLattice<Real>>(lbm::GridShape{o.n, o.n, o.n, {true, true, false}}, rh);
    for (int z = 0; z < o.n; ++z)
        for (int y = 0; y < o.n; ++y)
            for (int x = 0; x < o.n; ++x) l->set_fluid(x, y, z, 1.0, {});
    l->prepare();
    l->set_acceleration({u.acceleration(g.x), 0.0, u.acceleration(g.z)});
    return l;
}

template <class Real>
void run(const Options& o) {
    const double dx = 0.025, dt = 2.5e-4, deg = 3.141592653589793 / 180.0;
    const lbm::UnitConverter u(dx, dt, 1500.0);
    const Vec3 g{9.81 * std::sin(35 * deg), 0.0, -9.81 * std::cos(35 * deg)};
    // grains: r = 2 Δx (d/Δx = 4) on a cubic lattice of spacing s with (4/3 π r³)/s³ = fraction
    const double r = 2.0 * dx, s = std::cbrt(4.0 / 3.0 * 3.141592653589793 * r * r * r / o.fraction);
    dem::Particles p;
    const double box = o.n * dx;
    for (double z = 0.5 * s; z + r < box; z += s)
        for (double y = 0.5 * s; y + r < box; y += s)
            for (double x = 0.5 * s; x + r < box; x += s) p.add_mobile({x, y, z}, r * 0.98, 2500.0);
    // C2's contact model (linear, k_n = 1e6 N/m, ζ = 0.2, φ = 30°) against the box's bed and lid
    std::vector<dem::Wall> walls{dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1}),
                                 dem::Wall::plane("lid", {0, 0, box}, {0, 0, -1})};
    dem::ContactLaw<dem::LinearNormal> l1;
    l1.normal.kn = 1e6;
    l1.normal.alpha_n = dem::damping_ratio_from_restitution(0.2);
    l1.normal.kt_ratio = 2.0 / 7.0;
    l1.normal.clip_attractive = true;
    l1.tangential = {1.0, 0.577, 0.9 * 0.577, dem::FrictionMemory::hysteresis};
    l1.rolling.mu_r = 0.0678;
    dem::DemSolver grains(p, walls, dem::ContactLawSet<dem::LinearNormal>{l1, l1, l1}, g, dt / o.substeps,
                          0.1 * r);
    grains.set_reorder_interval(20);
    auto lattice = fluid_box<Real>(o, u, g);
    coupling::CouplingSettings cs;
    cs.substeps = o.substeps;
    cs.gravity = g;
    if (o.psm) cs.model = coupling::CoverRule::psm;
    coupling::GrainFluidCoupling c(cs, u, {});
    double t_find = 0, t_fluid = 0, t_sum = 0, t_dem = 0, cells = 0, grain_cells = 0;
    const auto start = Clock::now();
    for (int k = 0; k < o.steps; ++k) {
        const auto a = Clock::now();
        c.before_fluid_step(grains.particles(), *lattice);
        const auto b = Clock::now();
        lattice->step();
        const auto d = Clock::now();
        c.after_fluid_step(*lattice, grains);
        const auto e = Clock::now();
        for (int q = 0; q < o.substeps; ++q) grains.step();
        const auto f = Clock::now();
        t_find += seconds(a, b);
        t_fluid += seconds(b, d);
        t_sum += seconds(d, e);
        t_dem += seconds(e, f);
        cells += static_cast<double>(lattice->updated_cells());
        grain_cells += static_cast<double>(c.last_exchange().cells);
    }
    const double total = seconds(start, Clock::now());
    // the same lattice without grains
    auto alone = fluid_box<Real>(o, u, g);
    const auto a0 = Clock::now();
    for (int k = 0; k < o.steps; ++k) alone->step();
    const double t_alone = seconds(a0, Clock::now());
    const double ms = 1e3 / o.steps;
    fmt::print(
        "coupled_throughput n={} steps={} threads={} storage={} model={} fraction={:.3f} grains={} "
        "grain_cells={:.0f} substeps={}\n",
        o.n, o.steps, omp_get_max_threads(), o.single ? "float32" : "float64", coupling::name(cs.model),
        grains.mobile_count() * 4.0 / 3.0 * 3.141592653589793 * std::pow(r * 0.98, 3) / (box * box * box),
        grains.mobile_count(), grain_cells / o.steps, o.substeps);
    fmt::print(
        "per step [ms]: total {:.2f} = grain cells {:.2f} + lattice {:.2f} + drag sums {:.2f} + DEM {:.2f}\n",
        total * ms, t_find * ms, t_fluid * ms, t_sum * ms, t_dem * ms);
    fmt::print(
        "coupled: {:.1f} MLUPS, {:.3g} particle-steps/s; lattice alone: {:.2f} ms/step, {:.1f} MLUPS; "
        "coupled / alone = {:.2f}\n",
        cells / total * 1e-6, grains.mobile_count() * static_cast<double>(o.substeps * o.steps) / total,
        t_alone * ms, cells / t_alone * 1e-6, total / t_alone);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + ": value missing");
            return argv[++i];
        };
        if (a == "--n")
            o.n = std::stoi(next());
        else if (a == "--steps")
            o.steps = std::stoi(next());
        else if (a == "--fraction")
            o.fraction = std::stod(next());
        else if (a == "--substeps")
            o.substeps = std::stoi(next());
        else if (a == "--float")
            o.single = true;
        else if (a == "--psm")
            o.psm = true;
        else {
            fmt::print(
                stderr,
                "usage: coupled_throughput [--n N] [--steps S] [--fraction F] [--substeps K] [--float] "
                "[--psm]\n");
            return 2;
        }
    }
    if (o.single)
        run<float>(o);
    else
        run<double>(o);
    return 0;
}
