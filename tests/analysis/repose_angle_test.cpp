// SPDX-License-Identifier: MIT
// Angle-of-repose measurement (CASES C1) on synthetic heaps of known slope.
#include "analysis/repose_angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.h"

namespace sabo::analysis {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Grains of diameter d filling a heap on the plate [0, L] at z = 0: columns one diameter apart, each
// filled up to the heap surface h(x) = min(top, tan(left) x, tan(right) (L − x)), with a random
// jitter of the column positions and the top grain.
struct Heap {
    std::vector<Vec3> x;
    std::vector<double> r;
};
Heap make_heap(double left_deg, double right_deg, double length, double d, double top, unsigned seed) {
    Heap h;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.2 * d, 0.2 * d);
    for (double cx = 0.5 * d; cx < length; cx += d) {
        const double x = cx + jitter(rng);
        const double surface =
            std::min({top, std::tan(left_deg * deg) * x, std::tan(right_deg * deg) * (length - x)});
        for (double z = 0.5 * d; z + 0.5 * d <= surface + 1e-12; z += d) {
            h.x.push_back({x, 0.0, z});
            h.r.push_back(0.5 * d);
        }
    }
    // grains below the plate (drained) and beside it are ignored
    h.x.push_back({0.5 * length, 0.0, -1.0});
    h.r.push_back(0.5 * d);
    h.x.push_back({-0.1, 0.0, 0.5});
    h.r.push_back(0.5 * d);
    return h;
}

TEST(ReposeAngle, FitLineRecoversExactSlope) {
    HeapSide side;
    for (int k = 0; k < 10; ++k) side.points.push_back({0.1 * k, 0.3 + 0.5 * 0.1 * k});
    fit_line(side);
    EXPECT_NEAR(side.slope, 0.5, 1e-12);
    EXPECT_NEAR(side.intercept, 0.3, 1e-12);
    EXPECT_NEAR(side.r2, 1.0, 1e-12);
    EXPECT_NEAR(side.rms, 0.0, 1e-12);
}

TEST(ReposeAngle, PeakedHeapsOfKnownSlopes) {
    const double d = 0.002, length = 0.2;  // 100 d plate: a fine staircase
    for (const auto& [left, right] : {std::pair{20.0, 20.0}, {26.0, 30.0}, {35.0, 18.0}}) {
        const Heap h = make_heap(left, right, length, d, 1.0, 3);
        const HeapAngle a = measure_heap(h.x, h.r, h.x.size(), {0.0, length, 0.0, d, 10});
        // the staircase of one-diameter steps and the ±0.2 d jitter: within 1°
        EXPECT_NEAR(a.left.angle_deg, left, 1.0) << left << "/" << right;
        EXPECT_NEAR(a.right.angle_deg, right, 1.0) << left << "/" << right;
        EXPECT_NEAR(a.angle_deg, 0.5 * (left + right), 1.0);
        EXPECT_EQ(a.left.points.size(), 10U);
        EXPECT_GT(a.left.r2, 0.98);
        EXPECT_FALSE(a.flat_top);
        EXPECT_EQ(a.on_plate, h.x.size() - 2);
    }
}

TEST(ReposeAngle, FlatTopIsExcludedFromTheSides) {
    const double d = 0.002, length = 0.2;
    // a 25° heap cut at 60 % of its peak height: the sides end at the plateau
    const double peak = std::tan(25.0 * deg) * 0.5 * length;
    const Heap h = make_heap(25.0, 25.0, length, d, 0.6 * peak, 5);
    const HeapAngle a = measure_heap(h.x, h.r, h.x.size(), {0.0, length, 0.0, d, 10});
    EXPECT_TRUE(a.flat_top);
    EXPECT_NEAR(a.angle_deg, 25.0, 1.5);
    EXPECT_LT(a.left.x_to, 0.5 * length);
    // counting the plateau as side would have flattened the line by several degrees
    HeapSide whole;
    for (std::size_t i = 0; i + 2 < h.x.size(); ++i) {
        if (h.x[i].x < 0.5 * length) whole.points.push_back({h.x[i].x, h.x[i].z + h.r[i]});
    }
    fit_line(whole);
    EXPECT_LT(std::atan(whole.slope) / deg, 22.0);
}

TEST(ReposeAngle, AThinLayerHasASmallAngle) {
    // low-friction outcome: one layer of grains over the whole plate (a steep heap cut at 1.5 d)
    const double d = 0.002, length = 0.2;
    const Heap h = make_heap(60.0, 60.0, length, d, 1.5 * d, 9);
    const HeapAngle a = measure_heap(h.x, h.r, h.x.size(), {0.0, length, 0.0, d, 10});
    EXPECT_LT(std::abs(a.angle_deg), 1.0);
    EXPECT_NEAR(a.left.x_to, 0.5 * length, 1e-12);  // the half plate
}

TEST(ReposeAngle, NoHeapIsAnError) {
    const std::vector<Vec3> x{{0.01, 0.0, 0.001}, {0.02, 0.0, 0.001}};
    const std::vector<double> r{0.001, 0.001};
    EXPECT_THROW((void)measure_heap(x, r, x.size(), {0.0, 0.2, 0.0, 0.002, 10}), RunError);
}

}  // namespace
}  // namespace sabo::analysis
