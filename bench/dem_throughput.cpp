// SPDX-License-Identifier: MIT
// End-to-end DEM throughput on the peer benchmark of ../shared/peers/dem: 7640 spheres from
// particles.txt, CASES C2 contact parameters with the peers' simplifications (no tangential
// damping, μ_d = μ_s, μ_r = 0.0678 on every contact), seven plane walls including a closed barrier
// plane at X = 8 m, slope 35°.
//   dem_throughput PARTICLES.txt early|impact [--threads N] [--steps N] [--skin M] [--clip 0|1] [--mu-r X]
//   [--rolling-sweeps K] [--reorder BUILDS]
//   (defaults: skin 0.01 m as the peers; clip 1 as SPEC — the peers' hooke laws do not clip)
// Prints one line: window, threads, steps, loop seconds, particle-steps/s, peak RSS, and the end
// state in the peers' RESULT format (ke, erot, xfront = max centre X, xmean = mass-centre X).
// Under mpiexec the grains are divided into slabs along X (parallel::GrainHalo), the faces where the released
// grains' count is equal at the start (they stay there); rank 0 prints, the end state summed over ranks.
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/mpi_world.h"
#include "dem/dem_solver.h"
#include "parallel/grain_halo.h"

using namespace sabo;

int main(int argc, char** argv) {
    const MpiWorld world(argc, argv);
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s PARTICLES.txt early|impact [--threads N] [--steps N]\n", argv[0]);
        return 2;
    }
    const std::string window = argv[2];
    int steps = 20000;
    double skin = 0.01;  // the peers' neighbor 0.01 bin
    bool clip = true;    // SPEC clips attractive normal forces; the peers' hooke models do not
    double mu_r = 0.0678;
    int sweeps = 1;
    int reorder =
        20;  // list builds between spatial sorts (as sabo run; LIGGGHTS sorts atoms every 1000 steps)
    for (int a = 3; a + 1 < argc; a += 2) {
        const std::string opt = argv[a];
        if (opt == "--threads") omp_set_num_threads(std::atoi(argv[a + 1]));
        if (opt == "--steps") steps = std::atoi(argv[a + 1]);
        if (opt == "--skin") skin = std::atof(argv[a + 1]);
        if (opt == "--clip") clip = std::atoi(argv[a + 1]) != 0;
        if (opt == "--mu-r") mu_r = std::atof(argv[a + 1]);
        if (opt == "--rolling-sweeps") sweeps = std::atoi(argv[a + 1]);
        if (opt == "--reorder") reorder = std::atoi(argv[a + 1]);
    }
    double dt = 0.0;
    if (window == "early")
        dt = 1e-5;
    else if (window == "impact")
        dt = 1e-4;
    else {
        std::fprintf(stderr, "window must be early or impact\n");
        return 2;
    }
    dem::Particles p;
    std::ifstream in(argv[1]);
    double x, y, z, r;
    while (in >> x >> y >> z >> r) p.add_mobile({x, y, z}, r, 2500.0);
    if (p.n_mobile == 0) {
        std::fprintf(stderr, "no particles read from %s\n", argv[1]);
        return 2;
    }
    std::vector<dem::Wall> walls{dem::Wall::plane("x0", {0, 0, 0}, {1, 0, 0}),
                                 dem::Wall::plane("barrier", {8, 0, 0}, {-1, 0, 0}, true),
                                 dem::Wall::plane("x1", {20, 0, 0}, {-1, 0, 0}),
                                 dem::Wall::plane("y0", {0, 0, 0}, {0, 1, 0}),
                                 dem::Wall::plane("y1", {0, 2.1, 0}, {0, -1, 0}),
                                 dem::Wall::plane("z0", {0, 0, 0}, {0, 0, 1}),
                                 dem::Wall::plane("z1", {0, 0, 1.35}, {0, 0, -1})};
    dem::ContactLaw<dem::LinearNormal> law;
    law.normal.kn = 1e6;
    law.normal.alpha_n = dem::damping_ratio_from_restitution(0.2);
    law.normal.kt_ratio = 2.0 / 7.0;
    law.normal.clip_attractive = clip;
    law.tangential = {0.0, 0.577, 0.577, dem::FrictionMemory::hysteresis};
    law.rolling.mu_r = mu_r;
    const double th = 35.0 * M_PI / 180.0;
    dem::DemSolver s(p, walls, dem::ContactLawSet<dem::LinearNormal>{law, law, law},
                     {9.81 * std::sin(th), 0, -9.81 * std::cos(th)}, dt, skin);
    s.set_rolling_sweeps(sweeps);
    s.set_reorder_interval(reorder);
    std::vector<double> faces, xs;
    for (std::size_t i = 0; i < p.n_mobile; ++i) xs.push_back(p.x[i].x);
    std::sort(xs.begin(), xs.end());
    for (int r = 1; r < world.size(); ++r)
        faces.push_back(xs[xs.size() * static_cast<std::size_t>(r) / world.size()]);
    parallel::GrainHalo halo(world, s, faces);
    if (world.size() > 1) halo.divide();
    world.barrier();
    const auto t0 = std::chrono::steady_clock::now();
    const bool phases = std::getenv("SABO_BENCH_PHASES") != nullptr;
    auto tp = t0;
    for (int k = 0; k < steps; ++k) {
        if (world.size() > 1)
            halo.step();
        else
            s.step();
        if (phases && (k + 1) % 2000 == 0) {
            const auto now = std::chrono::steady_clock::now();
            std::fprintf(
                stderr,
                "  steps %6d: %.3g particle-steps/s, contacts %llu, list pairs %zu, list builds %zu\n", k + 1,
                2000.0 * static_cast<double>(p.n_mobile) / std::chrono::duration<double>(now - tp).count(),
                static_cast<unsigned long long>(s.stats().contacts), s.list_pairs(), s.list_builds());
            tp = now;
        }
    }
    world.barrier();
    const double loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<double> sums(5, 0.0);  // ke, erot, xm, mass, xfront (negated, summed: one rank's max)
    double xfront = -1e300;
    const auto& q = s.particles();
    for (std::size_t i = 0; i < s.own_count(); ++i) {
        sums[0] += 0.5 * q.m[i] * norm2(q.v[i]);
        sums[1] += 0.5 / q.inv_j[i] * norm2(q.w[i]);
        sums[2] += q.m[i] * q.x[i].x;
        sums[3] += q.m[i];
        xfront = std::max(xfront, q.x[i].x);
    }
    world.sum_reals(sums);
    xfront = world.max_real(xfront);
    const dem::KineticEnergy ke{sums[0], sums[1]};
    const double xm = sums[2], mass = sums[3];
    if (world.size() > 1) {
        std::fprintf(stderr,
                     "  rank %d: %zu own grains at the end, exchanges %.3f s, re-partitions %.3f s (%zu)\n",
                     world.rank(), s.own_count(), halo.exchange_seconds(), halo.repartition_seconds(),
                     halo.repartitions());
    }
    if (world.rank() != 0) return 0;
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    std::printf(
        "sabo %s ranks=%d threads=%d steps=%d loop_s=%.3f particle_steps_per_s=%.4g peak_rss_MiB=%.1f "
        "solver_bytes_per_grain=%.0f list_builds=%zu\n",
        window.c_str(), world.size(), omp_get_max_threads(), steps, loop,
        static_cast<double>(p.n_mobile) * steps / loop, ru.ru_maxrss / 1024.0,
        static_cast<double>(s.memory_bytes()) / static_cast<double>(p.n_mobile), s.list_builds());
    std::printf("RESULT code=sabo steps=%d dt=%g atoms=%zu ke=%.6g erot=%.6g xfront=%.4f xmean=%.4f\n", steps,
                dt, p.n_mobile, ke.translational, ke.rotational, xfront, xm / mass);
    return 0;
}
