// SPDX-License-Identifier: MIT
// Which cells a grain covers: the cell-centre test, the solid fractions of partially saturated cells, the
// rule for a cell inside two grains, the lattice's edges, the order.
#include "coupling/grain_cells.h"

#include <gtest/gtest.h>

#include <cmath>
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

// A cube cut by a plane through its centre is half solid; a cube whose corner just touches the sphere or lies
// deep inside it is empty or full; a cube cut by a large sphere is the share of it the plane would give.
TEST(GrainCells, SolidFractionOfAUnitCell) {
    EXPECT_EQ(coupling::solid_fraction({0.0, 0.0, 0.0}, 3.0), 1.0);
    EXPECT_EQ(coupling::solid_fraction({4.0, 0.0, 0.0}, 3.0), 0.0);
    // a sphere of radius 10⁴ cells is a plane across the cell: centred at R − d, the cell is 0.5 + d inside
    // (to the half of one of the 89 strips of the columns)
    const double big = 1e4;
    for (const double d : {0.0, 0.2, -0.3}) {
        EXPECT_NEAR(coupling::solid_fraction({big - d, 0.0, 0.0}, big), 0.5 + d, 0.006) << d;
        EXPECT_NEAR(coupling::solid_fraction({0.0, 0.0, big - d}, big), 0.5 + d, 0.006) << d;
    }
    // diagonal plane through the centre: half again, by symmetry
    const double s = big / std::sqrt(3.0);
    EXPECT_NEAR(coupling::solid_fraction({s, s, s}, big), 0.5, 5e-3);
}

// Partially saturated cells: every cell the sphere cuts is found with its fraction, cells wholly inside have
// ε = 1, and the fractions add up to the sphere's volume (within 0.05 % at d/Δx = 8.6) wherever it lies,
// which cells_covered_alone() gives.
TEST(GrainCells, PartiallySaturatedCellsAddUpToTheSpheresVolume) {
    const auto fr = frame(16);
    const double r = 0.043, volume = 4.0 / 3.0 * std::numbers::pi * r * r * r / 1e-6;  // in cells
    coupling::GrainCellFinder f;
    for (int k = 0; k < 5; ++k) {
        dem::Particles p;
        const double shift = 0.0023 * k;
        p.add_mobile({0.08 + shift, 0.081 + 0.7 * shift, 0.079 + 0.3 * shift}, r, 2500.0);
        f.find(p.x, p.r, fr, coupling::CoverRule::psm);
        double sum = 0.0;
        std::size_t cut = 0;
        for (const auto& c : f.cells()) {
            const double d = norm(c.centre - p.x[0]) / 0.01;
            sum += c.fraction;
            EXPECT_GT(c.fraction, 0.0);
            EXPECT_LE(c.fraction, 1.0);
            if (d + 0.87 < r / 0.01) EXPECT_EQ(c.fraction, 1.0);
            cut += c.fraction < 1.0 ? 1 : 0;
        }
        EXPECT_GT(cut, 100U) << "the sphere's surface cuts many cells";
        EXPECT_NEAR(sum / volume, 1.0, 5e-4);
        EXPECT_NEAR(coupling::cells_covered_alone(p.x[0], r, fr, coupling::CoverRule::psm) / sum, 1.0, 5e-4);
        for (std::size_t g = 1; g < f.cells().size(); ++g)
            EXPECT_LT(f.cells()[g - 1].cell, f.cells()[g].cell);
    }
}

// A cell cut by two overlapping grains belongs to the one holding more of it.
TEST(GrainCells, APartialCellInTwoGrainsBelongsToTheOneHoldingMoreOfIt) {
    dem::Particles p;
    p.add_mobile({0.075, 0.08, 0.08}, 0.03, 2500.0);
    p.add_mobile({0.117, 0.08, 0.08}, 0.03, 2500.0);
    coupling::GrainCellFinder f;
    f.find(p.x, p.r, frame(16), coupling::CoverRule::psm);
    std::size_t shared = 0;
    for (const auto& c : f.cells()) {
        const Vec3 d0 = (c.centre - p.x[0]) / 0.01, d1 = (c.centre - p.x[1]) / 0.01;
        const double e0 = coupling::solid_fraction(d0, 3.0), e1 = coupling::solid_fraction(d1, 3.0);
        if (e0 > 0.0 && e1 > 0.0) {
            ++shared;
            EXPECT_EQ(c.fraction, std::max(e0, e1));
            if (e0 != e1) EXPECT_EQ(c.grain, e1 > e0 ? 1u : 0u);
        }
    }
    EXPECT_GT(shared, 0U) << "the grains must share cells";
}

}  // namespace
}  // namespace sabo
