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
#include <omp.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "dem/dem_solver.h"

using namespace sabo;

int main(int argc, char** argv) {
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
    const auto t0 = std::chrono::steady_clock::now();
    const bool phases = std::getenv("SABO_BENCH_PHASES") != nullptr;
    auto tp = t0;
    for (int k = 0; k < steps; ++k) {
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
    const double loop = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto ke = s.kinetic_energy();
    double xfront = -1e300, xm = 0.0, mass = 0.0;
    for (std::size_t i = 0; i < s.particles().n_mobile; ++i) {
        xfront = std::max(xfront, s.particles().x[i].x);
        xm += s.particles().m[i] * s.particles().x[i].x;
        mass += s.particles().m[i];
    }
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    std::printf(
        "sabo %s threads=%d steps=%d loop_s=%.3f particle_steps_per_s=%.4g peak_rss_MiB=%.1f "
        "solver_bytes_per_grain=%.0f list_builds=%zu\n",
        window.c_str(), omp_get_max_threads(), steps, loop, static_cast<double>(p.n_mobile) * steps / loop,
        ru.ru_maxrss / 1024.0, static_cast<double>(s.memory_bytes()) / static_cast<double>(p.n_mobile),
        s.list_builds());
    std::printf("RESULT code=sabo steps=%d dt=%g atoms=%zu ke=%.6g erot=%.6g xfront=%.4f xmean=%.4f\n", steps,
                dt, p.n_mobile, ke.translational, ke.rotational, xfront, xm / mass);
    return 0;
}
