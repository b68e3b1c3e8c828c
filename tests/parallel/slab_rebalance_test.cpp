// SPDX-License-Identifier: MIT
// Where the slab faces move (parallel/slab_rebalance.h), on one process standing for every rank: the costs it
// "gathers" are then the whole channel's.
#include "parallel/slab_rebalance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/mpi_world.h"

namespace {

using sabo::parallel::rebalanced_cuts;

sabo::MpiWorld& one_process() {
    static int argc = 1;
    static char name[] = "test";
    static char* args[] = {name, nullptr};
    static char** argv = args;
    static sabo::MpiWorld world(argc, argv);
    return world;
}

// A channel of `planes` planes whose work sits in [from, to) (cost 1 a plane, else 0.01).
std::vector<double> block(int planes, int from, int to) {
    std::vector<double> cost(static_cast<std::size_t>(planes), 0.01);
    for (int x = from; x < to; ++x) cost[static_cast<std::size_t>(x)] = 1.0;
    return cost;
}

}  // namespace

TEST(SlabRebalance, FacesMoveToEqualCostsWhenTheOldFacesAllowIt) {
    // 2 slabs of 100 planes, the work in the first 40 (cost 40 + 160 · 0.01 = 41.6): the balanced face is
    // after the first plane where the running cost reaches 20.8, plane 20
    const std::vector<int> cuts = rebalanced_cuts(one_process(), {0, 100, 200}, block(200, 0, 40), 14);
    ASSERT_EQ(cuts.size(), 3U);
    EXPECT_EQ(cuts.front(), 0);
    EXPECT_EQ(cuts.back(), 200);
    EXPECT_EQ(cuts[1], 21);
}

TEST(SlabRebalance, AFaceStopsAtTheOldFacesBesideIt) {
    // 3 slabs; the work at the far end: the balanced faces lie past the old middle face, so the first face
    // stops there (the planes it gains must come from the neighbour that holds them)
    const std::vector<int> old{0, 60, 120, 180};
    const std::vector<int> cuts = rebalanced_cuts(one_process(), old, block(180, 150, 180), 14);
    ASSERT_EQ(cuts.size(), 4U);
    for (std::size_t r = 1; r + 1 < cuts.size(); ++r) {
        EXPECT_GE(cuts[r], old[r - 1]) << r;
        EXPECT_LE(cuts[r], old[r + 1]) << r;
        EXPECT_GE(cuts[r] - cuts[r - 1], 14) << r;  // two ghost depths
    }
    EXPECT_GE(cuts[3] - cuts[2], 14);
    EXPECT_GT(cuts[1], old[1]);  // they did move toward the work
}

TEST(SlabRebalance, NoMoveForTooSmallAGain) {
    // the first slab's planes cost 1.15, the second's 1: the dearest slab 115, balanced ~107.5, a gain of
    // 6.5 %: within the price model's error and less than a move costs
    std::vector<double> cost(200, 1.0);
    std::fill(cost.begin(), cost.begin() + 100, 1.15);
    const std::vector<int> old{0, 100, 200};
    EXPECT_EQ(rebalanced_cuts(one_process(), old, cost, 14), old);
}

TEST(SlabRebalance, AMoveForAGainOfTenPerCentOrMore) {
    // the first slab's planes cost 1.3: the dearest slab 130, balanced ~115, a gain of 11.5 %
    std::vector<double> cost(200, 1.0);
    std::fill(cost.begin(), cost.begin() + 100, 1.3);
    const std::vector<int> cuts = rebalanced_cuts(one_process(), {0, 100, 200}, cost, 14);
    EXPECT_LT(cuts[1], 100);
    EXPECT_GT(cuts[1], 80);
}

TEST(SlabRebalance, SlabsStayTwoGhostDepthsThick) {
    // all the work in 6 planes: the balanced face would leave a slab thinner than 14 planes (the face at 14
    // still lowers the dearest slab's cost from 6.94 to 6.08)
    const std::vector<int> cuts = rebalanced_cuts(one_process(), {0, 100, 200}, block(200, 0, 6), 14);
    EXPECT_EQ(cuts[1], 14);
}
