// SPDX-License-Identifier: MIT
// Micro-benchmark of one contact evaluation (normal + Luding tangential), linear and Hertz.
#include <benchmark/benchmark.h>

#include "dem/contact_law.h"

using namespace sabo;
using namespace sabo::dem;

template <class Normal>
static void contact(benchmark::State& state, const Normal& normal) {
    ContactLaw<Normal> law{normal, {1.0, 0.577, 0.52, FrictionMemory::hysteresis}, {0.0678}};
    TangentialState h;
    const Vec3 n{0.6, 0.0, 0.8};
    double delta = 1e-4;
    for (auto _ : state) {
        const auto pf =
            pair_force(law, h, n, delta, {0.1, 0.02, -0.05}, {0.01, 0.03, 0.0}, 0.65, 0.025, 1e-4);
        benchmark::DoNotOptimize(pf);
        delta += 1e-12;
    }
}

static void BM_LinearContact(benchmark::State& s) {
    contact(s, LinearNormal{1e6, 0.456, 2.0 / 7.0, true});
}
static void BM_HertzContact(benchmark::State& s) {
    HertzNormal h;
    h.e_star = 3e7;
    h.g_star = 1.2e7;
    h.beta = 0.456;
    contact(s, h);
}
BENCHMARK(BM_LinearContact);
BENCHMARK(BM_HertzContact);
