// SPDX-License-Identifier: MIT
#include "parallel/slab_partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "core/error.h"

using sabo::parallel::SlabPartition;

TEST(SlabPartition, EqualSlabsCoverTheChannelInOrder) {
    const SlabPartition p(10, 3, 1);
    EXPECT_EQ(p.begin(0), 0);
    EXPECT_EQ(p.end(0), 3);
    EXPECT_EQ(p.end(1), 6);
    EXPECT_EQ(p.end(2), 10);
    EXPECT_EQ(p.owner(0), 0);
    EXPECT_EQ(p.owner(5), 1);
    EXPECT_EQ(p.owner(6), 2);
    EXPECT_EQ(p.owner(9), 2);
}

TEST(SlabPartition, UniformCostGivesEqualSlabs) {
    const std::vector<double> cost(120, 2.5);
    const auto p = SlabPartition::balanced(cost, 4, 2);
    for (int r = 0; r < 4; ++r) EXPECT_EQ(p.end(r) - p.begin(r), 30) << r;
    EXPECT_DOUBLE_EQ(p.imbalance(cost), 1.0);
}

// A released mass: ten dear planes in a long cheap channel. Equal slabs put it all on the first rank.
TEST(SlabPartition, ConcentratedCostIsShared) {
    std::vector<double> cost(100, 1.0);
    std::fill(cost.begin() + 10, cost.begin() + 20, 100.0);
    const double mean = (90.0 + 1000.0) / 4.0;
    EXPECT_DOUBLE_EQ(SlabPartition(100, 4, 1).imbalance(cost), (10.0 + 1000.0 + 5.0) / mean);
    const auto p = SlabPartition::balanced(cost, 4, 1);
    EXPECT_LE(p.imbalance(cost), 1.0 + 100.0 / mean);
    EXPECT_LT(p.end(2), 20);  // three ranks share the mass, the fourth takes the rest of the channel
}

TEST(SlabPartition, NoSlabThinnerThanItsGhostReach) {
    std::vector<double> cost(40, 0.0);
    cost[20] = 1.0;  // all the work in one plane
    const auto p = SlabPartition::balanced(cost, 5, 3);
    EXPECT_EQ(p.begin(0), 0);
    EXPECT_EQ(p.end(4), 40);
    for (int r = 0; r < 5; ++r) EXPECT_GE(p.end(r) - p.begin(r), 3) << r;
}

TEST(SlabPartition, LargestSlabWithinTheMeanPlusTheDearestPlane) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<double> cost(200);
        for (double& c : cost) c = u(rng) < 0.3 ? 20.0 * u(rng) : 0.1 * u(rng);
        const int ranks = 2 + trial % 15;
        const auto p = SlabPartition::balanced(cost, ranks, 1);
        const auto slabs = p.slab_costs(cost);
        double total = 0.0;
        for (double c : cost) total += c;
        const double dearest = *std::max_element(cost.begin(), cost.end());
        EXPECT_LE(*std::max_element(slabs.begin(), slabs.end()), total / ranks + dearest + 1e-9) << trial;
    }
}

TEST(SlabPartition, TooManyRanksForTheChannelIsRefused) {
    try {
        (void)SlabPartition(20, 8, 3);
        FAIL() << "accepted 8 slabs of 3 planes in 20 planes";
    } catch (const sabo::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("use at most 6 ranks"), std::string::npos) << e.what();
    }
}
