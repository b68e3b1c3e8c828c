// SPDX-License-Identifier: MIT
#include "dem/walls.h"

#include <gtest/gtest.h>

namespace sabo::dem {

TEST(Walls, PlaneIsOneSided) {
    const auto w = Wall::plane("bed", {0, 0, 0}, {0, 0, 2});
    WallTouch t;
    ASSERT_TRUE(touches(w, {1, 1, 0.04}, 0.05, t));
    EXPECT_NEAR(t.delta, 0.01, 1e-15);
    EXPECT_DOUBLE_EQ(t.n.z, -1.0);  // from the sphere towards the wall
    EXPECT_FALSE(touches(w, {0, 0, 0.06}, 0.05, t));
    EXPECT_FALSE(touches(w, {0, 0, -0.06}, 0.05, t));  // fully behind
}

TEST(Walls, BoxClosestPointEdgeAndInside) {
    const auto b =
        Wall::box("pile", {0, 0, 0}, {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}, {0.05, 0.5, 1.0});
    WallTouch t;
    ASSERT_TRUE(touches(b, {0.09, 0, 0}, 0.05, t));  // face
    EXPECT_NEAR(t.delta, 0.01, 1e-15);
    EXPECT_NEAR(t.n.x, -1.0, 1e-15);
    ASSERT_TRUE(touches(b, {0.08, 0.53, 0}, 0.05, t));  // edge: distance sqrt(0.03² + 0.03²)
    EXPECT_NEAR(t.delta, 0.05 - std::sqrt(0.0018), 1e-12);
    EXPECT_FALSE(touches(b, {0.09, 0.54, 0}, 0.05, t));
    ASSERT_TRUE(touches(b, {0.04, 0, 0}, 0.05, t));  // centre inside, near the +x face
    EXPECT_NEAR(t.delta, 0.06, 1e-15);
    EXPECT_NEAR(t.n.x, -1.0, 1e-15);
}

TEST(Walls, RotatedBox) {
    const double c = std::cos(0.3), s = std::sin(0.3);
    const auto b =
        Wall::box("vb", {0, 0, 0}, {Vec3{c, 0, s}, Vec3{0, 1, 0}, Vec3{-s, 0, c}}, {0.05, 1.0, 1.0});
    WallTouch t;
    ASSERT_TRUE(touches(b, Vec3{c, 0, s} * 0.09, 0.05, t));
    EXPECT_NEAR(t.delta, 0.01, 1e-12);
    EXPECT_NEAR(t.n.x, -c, 1e-12);
    EXPECT_NEAR(t.n.z, -s, 1e-12);
}

TEST(Walls, InactiveWallsDoNotTouch) {
    auto w = Wall::plane("gate", {0, 0, 0}, {1, 0, 0});
    w.active = false;
    WallTouch t;
    EXPECT_FALSE(touches(w, {0.01, 0, 0}, 0.05, t));
}

}  // namespace sabo::dem
