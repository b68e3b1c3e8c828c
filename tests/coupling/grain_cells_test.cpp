// SPDX-License-Identifier: MIT
// Which cells a grain covers: the cell-centre test, the rule for a cell inside two grains, the lattice's
// edges, the order.
#include "coupling/grain_cells.h"

#include <gtest/gtest.h>

#include <numbers>

#include "dem/particles.h"

namespace sabo {
namespace {

coupling::LatticeFrame frame(int n) {
    // rows padded to 16 cells, as a lattice of float64 with n ≤ 16 stores them
    return {{}, 0.01, n, n, n, 16, static_cast<std::size_t>(16 * n)};
}

TEST(GrainCells, CellsWhoseCentreIsInsideAscending) {
    dem::Particles p;
    p.add_mobile({0.1, 0.1, 0.1}, 0.043, 2500.0);
    coupling::GrainCellFinder f;
    const auto fr = frame(16);
    f.find(p.x, p.r, fr);
    const auto& cells = f.cells();
    std::size_t inside = 0;  // brute force over every cell
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) inside += norm(fr.centre(x, y, z) - p.x[0]) < 0.043 ? 1 : 0;
    EXPECT_EQ(cells.size(), inside);
    for (std::size_t g = 1; g < cells.size(); ++g) EXPECT_LT(cells[g - 1].cell, cells[g].cell);
    for (const auto& c : cells) {
        EXPECT_LT(norm(c.centre - p.x[0]), 0.043);
        const std::size_t z = c.cell / fr.plane, y = (c.cell % fr.plane) / fr.row, x = c.cell % fr.row;
        EXPECT_EQ(norm(fr.centre(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)) - c.centre),
                  0.0);
    }
    // the staircase volume is the sphere's within a few per cent at d/Δx = 8.6
    const double v = 4.0 / 3.0 * std::numbers::pi * 0.043 * 0.043 * 0.043;
    EXPECT_NEAR(static_cast<double>(cells.size()) * 1e-6 / v, 1.0, 0.1);
    f.find(p.x, p.r, fr);  // a second call finds the same (the scratch was cleared)
    EXPECT_EQ(f.cells().size(), inside);
}

TEST(GrainCells, ACellInTwoGrainsBelongsToTheDeeperOneAndTiesToTheLowerIndex) {
    dem::Particles p;
    p.add_mobile({0.075, 0.08, 0.08}, 0.03, 2500.0);  // overlapping along x
    p.add_mobile({0.115, 0.08, 0.08}, 0.03, 2500.0);
    coupling::GrainCellFinder f;
    f.find(p.x, p.r, frame(16));
    std::size_t shared_to_0 = 0, shared_to_1 = 0;
    for (const auto& c : f.cells()) {
        const double d0 = norm(c.centre - p.x[0]), d1 = norm(c.centre - p.x[1]);
        if (d0 < 0.03 && d1 < 0.03) {
            (c.grain == 0 ? shared_to_0 : shared_to_1) += 1;
            EXPECT_EQ(c.grain, d1 < d0 ? 1u : 0u);  // the deeper; a tie to the lower index
        }
    }
    EXPECT_GT(shared_to_0 + shared_to_1, 0u) << "the grains must share cells";
}

TEST(GrainCells, AGrainOutsideTheLatticeCoversOnlyItsCellsInside) {
    dem::Particles p;
    p.add_mobile({-0.01, 0.08, 0.08}, 0.03, 2500.0);  // centre beyond x = 0
    p.add_mobile({0.5, 0.5, 0.5}, 0.03, 2500.0);      // wholly outside
    coupling::GrainCellFinder f;
    f.find(p.x, p.r, frame(16));
    ASSERT_FALSE(f.cells().empty());
    for (const auto& c : f.cells()) {
        EXPECT_EQ(c.grain, 0u);
        EXPECT_GT(c.centre.x, 0.0);
    }
}

}  // namespace
}  // namespace sabo
