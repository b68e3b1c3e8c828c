// SPDX-License-Identifier: MIT
// Outlets of the free-surface lattice (an open channel's end, top and sides): the fluid that reaches an
// outlet leaves the domain and is counted, so that the lattice's mass plus the drained mass stays the
// starting mass to round-off; an outlet no fluid reaches changes nothing, bit for bit; fluid at an outlet at
// the start is refused. On both backends (tests/lbm/backends.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "lbm/backends.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {
namespace {

// A channel along x (periodic across y) with a block of water at its upstream end, `depth` cells deep and
// `length` long, under gravity `g` along x and down z: a dam break that runs to the end.
FluidLattice<double> dam_break(int nx, int length, int depth, const Vec3& g) {
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({nx, 2, 16, {false, true, false}}, rh);
    for (int z = 0; z < depth; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < length; ++x) l.set_fluid(x, y, z, 1.0, {});
    l.set_acceleration(g);
    return l;
}

double drained_total(const FluidLattice<double>& l) {
    double sum = 0.0;
    for (const double m : l.drained()) sum += m;
    return sum;
}

class LbmOutlets : public testing::TestWithParam<Backend> {};
SABO_ON_BOTH_BACKENDS(LbmOutlets);

TEST_P(LbmOutlets, FluidLeavingThroughTheEndIsCountedToRoundOff) {
    const int nx = 48;
    auto l = dam_break(nx, 12, 8, {2e-4, 0.0, -2e-4});
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 2; ++y) l.set_outlet(nx - 1, y, z, 0);  // the channel's end
    for (int x = 0; x < nx; ++x)
        for (int y = 0; y < 2; ++y) l.set_outlet(x, y, 15, 1);  // the top (nothing reaches it)
    l.prepare();
    const double m0 = l.total_mass();
    double worst = 0.0;
    Stepper<double> stepper(l, GetParam());
    for (int k = 250; k <= 4000; k += 250) {
        stepper.run(250);
        {
            worst = std::max(worst, std::abs(l.total_mass() + drained_total(l) - m0) / m0);
            for (int z = 0; z < 16; ++z)
                for (int y = 0; y < 2; ++y)
                    ASSERT_NE(l.type(l.index(nx - 1, y, z)), CellType::fluid) << "an outlet cell filled";
        }
    }
    const double left = l.drained()[0] / m0;
    std::printf("outlet at the end: %.3f of the fluid left, mass + drained drift %.2e, top outlet %.3e\n",
                left, worst, l.drained()[1]);
    EXPECT_GT(left, 0.5);  // most of the water ran out of the channel
    EXPECT_LT(worst, 1e-12);
    EXPECT_EQ(l.drained()[1], 0.0);
}

TEST_P(LbmOutlets, AnOutletNoFluidReachesChangesNothing) {
    // the sloshing dam break in a closed box, with and without an outlet layer at its top
    const auto run = [&](bool outlet) {
        auto l = dam_break(24, 8, 6, {0.0, 0.0, -2e-4});
        if (outlet)
            for (int x = 0; x < 24; ++x)
                for (int y = 0; y < 2; ++y) l.set_outlet(x, y, 15, 2);
        l.prepare();
        Stepper<double>(l, GetParam()).run(800);
        std::vector<double> state;
        for (std::size_t k = 0; k < FluidLattice<double>::stored_cells(l.shape()); ++k) {
            double rho = 0.0;
            Vec3 u;
            if (l.type(k) == CellType::fluid || l.type(k) == CellType::interface) l.moments(k, rho, u);
            state.insert(state.end(), {static_cast<double>(l.type(k)), l.fill(k), rho, u.x, u.z});
        }
        return state;
    };
    const auto with = run(true), without = run(false);
    ASSERT_EQ(with.size(), without.size());
    EXPECT_EQ(std::memcmp(with.data(), without.data(), with.size() * sizeof(double)), 0);
}

TEST(LbmOutlet, FluidAtAnOutletAtTheStartIsRefused) {
    auto l = dam_break(24, 8, 6, {0.0, 0.0, -2e-4});
    l.set_outlet(0, 0, 0, 0);
    EXPECT_THROW(l.prepare(), InputError);
    EXPECT_THROW(l.set_outlet(1, 0, 0, max_outlets), InputError);
}

}  // namespace
}  // namespace sabo::lbm
