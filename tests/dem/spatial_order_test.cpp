// SPDX-License-Identifier: MIT
#include "dem/spatial_order.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "dem/dem_solver.h"
#include "test_support.h"

namespace sabo::dem {
namespace {

// A block of grains 12 cells long in y, 3 wide in x, 2 deep in z, numbered x fastest and z slowest (as
// a release lattice numbers them, which cuts a contiguous half of the indices along the block's length):
// the sort must put slabs of 4 cells across y, the longest extent, one after the other (inside each,
// z slowest and x fastest), so that a contiguous range of the new order is a run of slabs across y.
TEST(SpatialOrder, SlabsAcrossTheLongestExtentComeOneAfterTheOther) {
    std::vector<Vec3> x;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 12; ++y)
            for (int ix = 0; ix < 3; ++ix) x.push_back({ix + 0.5, y + 0.5, z + 0.5});
    std::vector<std::uint32_t> order, start, histogram;
    spatial_order(x, x.size(), 1.0, order, start, histogram);
    ASSERT_EQ(order.size(), x.size());
    const auto key = [&](std::uint32_t i) {
        const Vec3& p = x[i];
        return std::array<double, 4>{std::floor(p.y / 4.0), p.z, p.y, p.x};
    };
    for (std::size_t k = 1; k < order.size(); ++k)
        EXPECT_LT(key(order[k - 1]), key(order[k])) << "entry " << k;
    // the first half of the order lies in the first two slabs (y < 8), whatever its z
    for (std::size_t k = 0; k < order.size() / 2; ++k) EXPECT_LT(x[order[k]].y, 8.0);
}

// No grain (a rank of a divided run may hold none): an empty order, and a list of no particle built and
// stepped (its bounding box was empty: the cell grid's size came from −1e300 and the build threw).
TEST(SpatialOrder, NoGrainGivesAnEmptyOrderAndAnEmptyList) {
    std::vector<Vec3> x;
    std::vector<std::uint32_t> order{7}, start, histogram;
    spatial_order(x, 0, 1.0, order, start, histogram);
    EXPECT_TRUE(order.empty());
    DemSolver none(Particles{}, {}, test::same_everywhere(test::linear_law({})), {0.0, 0.0, -9.81}, 1e-4,
                   0.01);
    none.rebuild_lists_now();
    none.step();
    EXPECT_EQ(none.list_pairs(), 0U);
    EXPECT_EQ(none.steps(), 1U);
}

}  // namespace
}  // namespace sabo::dem
