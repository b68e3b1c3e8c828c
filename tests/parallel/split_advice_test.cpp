// SPDX-License-Identifier: MIT
#include "parallel/split_advice.h"

#include <gtest/gtest.h>

#include <limits>

namespace sabo::parallel {

constexpr double gib = 1024.0 * 1024.0 * 1024.0;

TEST(SplitAdvice, ARunThatFitsTakesOneProcessWithEveryCore) {
    const SplitAdvice a = advise_split(2.4 * gib, 2.0 * gib, 16, 100.0 * gib);
    EXPECT_EQ(a.machines, 1);
    EXPECT_EQ(a.threads, 16);
    EXPECT_NE(a.text.find("--threads 16"), std::string::npos) << a.text;
}

TEST(SplitAdvice, ARunLargerThanTheMachineIsDividedAmongAsManyMachinesAsItsMemoryNeeds) {
    // 80 % of 100 GiB per machine: 250 GiB of grains need 4 machines, 240 GiB 3
    EXPECT_EQ(advise_split(250.0 * gib, 0.0, 16, 100.0 * gib).machines, 4);
    const SplitAdvice a = advise_split(240.0 * gib, 0.0, 16, 100.0 * gib);
    EXPECT_EQ(a.machines, 3);
    EXPECT_EQ(a.threads, 16);
    EXPECT_NE(a.text.find("mpirun -np 3"), std::string::npos) << a.text;
}

TEST(SplitAdvice, AMachineWhoseMemoryIsUnknownKeepsOneProcess) {
    EXPECT_EQ(advise_split(1e15, 1e15, 2, std::numeric_limits<double>::infinity()).machines, 1);
    EXPECT_EQ(advise_split(1.0, 1.0, 0, 1.0 * gib).threads, 1);
}

TEST(SplitAdvice, ADividedRunCountsEachRanksSecondLattice) {
    // 200 GiB, 160 of them the lattice: each rank also keeps 1.25 × its slab's lattice for the faces'
    // moves, (200 + 200) / 80 = 5 machines where the run alone would need 3
    EXPECT_EQ(advise_split(200.0 * gib, 160.0 * gib, 16, 100.0 * gib).machines, 5);
}

}  // namespace sabo::parallel
