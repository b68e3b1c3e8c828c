// SPDX-License-Identifier: MIT
// The grain cells found on the lattice's device are the host finder's (coupling/grain_cells.h), by both
// rules, grains overlapping each other and the lattice's edges, and again after the grains move (the
// device releases the cells of the last call).
#include "coupling/opencl/device_grain_cells.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "lbm/backends.h"
#include "lbm/opencl/device_view.h"

namespace sabo::coupling {
namespace {

void expect_same_cells(CoverRule rule) {
    using lbm::FluidLattice;
    FluidLattice<double> l({30, 20, 24, {false, false, false}}, lbm::Rheology{});
    for (int z = 0; z < 24; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 30; ++x) l.set_fluid(x, y, z, 1.0, {});
    l.prepare();
    lbm::opencl::OpenClLattice<double> lattice(l, lbm::test_device());
    const double dx = 0.01;
    const LatticeFrame frame{{0.1, -0.02, 0.0}, dx, 30, 20, 24, l.index(0, 1, 0), l.index(0, 0, 1)};
    opencl::DeviceGrainCells device(lattice.view(), l.cell_types().size(), rule);
    GrainCellFinder host;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> along(-0.02, 0.32), across(-0.04, 0.2), up(-0.02, 0.26),
        radius(0.012, 0.035);
    std::vector<Vec3> x(80);
    std::vector<double> r(80);
    for (int round = 0; round < 2; ++round) {
        for (std::size_t g = 0; g < x.size(); ++g) {
            x[g] = {along(random), across(random), up(random)};
            r[g] = radius(random);
        }
        host.find(x, r, frame, rule);
        device.find(x, r, frame);
        const std::vector<CoveredCell> found = device.read_cells(frame);
        const std::vector<CoveredCell>& expected = host.cells();
        ASSERT_GT(expected.size(), 2000u);
        ASSERT_EQ(found.size(), expected.size()) << "round " << round;
        std::size_t differ = 0;
        double worst = 0.0;
        for (std::size_t c = 0; c < found.size(); ++c) {
            differ += found[c].cell != expected[c].cell || found[c].grain != expected[c].grain ? 1 : 0;
            worst = std::max(worst, std::abs(found[c].fraction - expected[c].fraction));
            ASSERT_EQ(found[c].centre.x, expected[c].centre.x);
        }
        EXPECT_EQ(differ, 0u) << "round " << round;
        EXPECT_LT(worst, 1e-13);  // the fractions' 89 columns summed in another order
    }
}

TEST(DeviceGrainCells, TheCellCentreRuleFindsTheHostsCells) {
    expect_same_cells(CoverRule::cell_centre);
}

TEST(DeviceGrainCells, PartialSaturationFindsTheHostsCellsAndFractions) {
    expect_same_cells(CoverRule::psm);
}

}  // namespace
}  // namespace sabo::coupling
