// SPDX-License-Identifier: MIT
#include "scenario/channel_case.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sabo::scenario {
namespace {

ChannelCase build(const std::string& extra) {
    const auto cfg =
        Config::from_string("[case]\nend_time_s = 1.0\n[channel]\nslope_deg = 35.0\n" + extra, "t.toml");
    return build_channel_case(cfg);
}

TEST(ChannelCase, ReferenceBlockHitsTheVolumeTargetWithoutOverlap) {
    const auto c =
        build("[barrier]\ntype = \"none\"\n[release]\nperturbation_m = 0.0\n");  // the lattice rule
    EXPECT_NEAR(c.release.solid_volume, 4.03, 0.002);
    EXPECT_NEAR(static_cast<double>(c.release.count), 7640.0, 60.0);
    EXPECT_NEAR(c.release.hi.x, 4.725, 1e-12);
    EXPECT_NEAR(0.5 * (c.release.lo.y + c.release.hi.y), 1.05, 1e-12);
    const auto& p = c.particles;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        EXPECT_GE(p.r[i], 0.0475 - 1e-12);
        EXPECT_LE(p.r[i], 0.0525 + 1e-12);
        EXPECT_GE(p.x[i].z - p.r[i], 0.0);
    }
    // lattice spacing = largest diameter: neighbours never overlap
    EXPECT_NEAR(p.x[1].x - p.x[0].x, 0.105, 1e-12);
    EXPECT_NEAR(c.gravity.x, 9.81 * std::sin(35.0 * 3.141592653589793 / 180.0), 1e-12);
}

// Realizations: release.perturbation_m moves every centre by at most p along each axis (by default 0.2 % of
// the smallest radius), keeps the radii of release.seed, and its own seed picks the displacement; p above
// 1 % of the smallest radius is refused.
TEST(ChannelCase, PerturbationDisplacesTheCentresOnlyWithinItsBound) {
    const std::string none = "[barrier]\ntype = \"none\"\n[release]\nsolid_volume_m3 = 0.5\n";
    const auto base = build(none + "perturbation_m = 0.0\n");
    const auto one = build(none + "perturbation_m = 0.0004\n");
    const auto by_default = build(none);  // 0.2 % of the smallest radius
    double largest_default = 0.0;
    for (std::size_t i = 0; i < base.particles.n_mobile; ++i) {
        const Vec3 d = by_default.particles.x[i] - base.particles.x[i];
        largest_default = std::max({largest_default, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    EXPECT_LE(largest_default, 0.002 * 0.0475 + 1e-15);
    EXPECT_GT(largest_default, 0.0015 * 0.0475);
    const auto two = build(none + "perturbation_m = 0.0004\nperturbation_seed = 2\n");
    ASSERT_EQ(one.particles.n_mobile, base.particles.n_mobile);
    double largest = 0.0, differ = 0.0;
    for (std::size_t i = 0; i < base.particles.n_mobile; ++i) {
        EXPECT_EQ(one.particles.r[i], base.particles.r[i]);
        const Vec3 d = one.particles.x[i] - base.particles.x[i];
        largest = std::max({largest, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        differ = std::max(differ, norm(two.particles.x[i] - one.particles.x[i]));
        EXPECT_GE(one.particles.x[i].z - one.particles.r[i], 0.0);
    }
    EXPECT_LE(largest, 0.0004);
    EXPECT_GT(largest, 0.0003);  // the draws span the range
    EXPECT_GT(differ, 0.0003);   // another perturbation seed, another realization
    EXPECT_THROW((void)build(none + "perturbation_m = 0.001\n"), InputError);  // > 0.01 r_min
}

TEST(ChannelCase, SphereSlitLeavesTheOutletClear) {
    const auto c = build("[barrier]\ntype = \"slit\"\noutlet_width_over_r = 4.0\n");
    const auto& p = c.particles;
    ASSERT_GT(p.n_fixed(), 0u);
    const double y_lo = 1.05 - 0.1, y_hi = 1.05 + 0.1;
    for (std::size_t i = p.n_mobile; i < p.size(); ++i) {
        EXPECT_TRUE(p.x[i].y + p.r[i] <= y_lo + 1e-9 || p.x[i].y - p.r[i] >= y_hi - 1e-9) << p.x[i].y;
        EXPECT_NEAR(p.x[i].x, 8.05, 1e-12);  // plane 5 cm downstream of the face
    }
    EXPECT_NEAR(c.barrier.face_x + c.barrier.thickness, 8.10, 1e-12);
}

// A barrier of its own height (barrier.height_m) below the channel's walls: its spheres and boxes end at its
// crest, the flow can overtop it; by default it reaches the ceiling (the closed box); never above it.
TEST(ChannelCase, ABarrierOfItsOwnHeightEndsAtItsCrest) {
    const auto crest = [](const ChannelCase& c) {
        double top = 0.0;
        for (std::size_t i = c.particles.n_mobile; i < c.particles.size(); ++i)
            top = std::max(top, c.particles.x[i].z);
        return top;
    };
    const auto low = build("[barrier]\ntype = \"closed\"\nheight_m = 0.8\n");
    EXPECT_DOUBLE_EQ(low.barrier.height, 0.8);
    EXPECT_NEAR(crest(low), 0.8, 0.05 + 1e-9);  // sphere centres one radius apart up to the crest
    EXPECT_LT(crest(low), 0.8 + 1e-9);
    const auto full = build("[barrier]\ntype = \"closed\"\n");
    EXPECT_DOUBLE_EQ(full.barrier.height, 1.35);  // channel.height_m's default: the lid at the crest
    const auto boxes = build("[barrier]\ntype = \"closed\"\nmodel = \"boxes\"\nheight_m = 0.8\n");
    const auto& box = boxes.walls[boxes.barrier.first_wall];
    EXPECT_NEAR(box.point.z + box.half.z, 0.8, 1e-12);  // an OB box: its axis along the bed normal
    EXPECT_THROW(build("[barrier]\ntype = \"closed\"\nheight_m = 2.0\n"), InputError);  // above the walls
}

TEST(ChannelCase, VerticalBoxBarrierFollowsGravity) {
    const auto c = build("[barrier]\ntype = \"closed\"\nmodel = \"boxes\"\norientation = \"VB\"\n");
    ASSERT_EQ(c.barrier.wall_count, 1u);
    const auto& box = c.walls[c.barrier.first_wall];
    // the face normal is perpendicular to gravity: a vertical face
    EXPECT_NEAR(dot(box.axes[0], c.gravity), 0.0, 1e-12);
    dem::WallTouch t;
    // at height Z the upstream face is at X = 8 − Z tan θ
    const double z = 1.0, xf = 8.0 - z * std::tan(35.0 * 3.141592653589793 / 180.0);
    const double cs = std::cos(35.0 * 3.141592653589793 / 180.0);  // normal distance = X offset × cos θ
    EXPECT_TRUE(dem::touches(box, {xf - 0.049 / cs, 1.0, z}, 0.05, t));
    EXPECT_FALSE(dem::touches(box, {xf - 0.051 / cs, 1.0, z}, 0.05, t));
}

}  // namespace
}  // namespace sabo::scenario

namespace sabo::scenario {
namespace {

TEST(ChannelCase, BidisperseReleaseHitsVolumeAndSmallFraction) {
    const auto c = build(
        "[release]\nmixture = \"bidisperse\"\nradius_large_m = 0.10\nradius_small_m = 0.05\nphi_small = 0.3\n"
        "perturbation_m = 0.0\n"
        "[barrier]\ntype = \"slit\"\noutlet_width_over_r = 4.0\n");
    const auto& p = c.particles;
    double v_small = 0.0, v_all = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const double v = 4.0 / 3.0 * M_PI * p.r[i] * p.r[i] * p.r[i];
        const bool small = p.r[i] < 0.075;
        EXPECT_NEAR(p.r[i], small ? 0.05 : 0.10, (small ? 0.05 : 0.10) * 0.05 + 1e-12);
        v_all += v;
        v_small += small ? v : 0.0;
    }
    EXPECT_NEAR(v_all, 4.03, 0.03);  // counts rounded to whole grains; radii ±5 %
    EXPECT_NEAR(v_small / v_all, 0.3, 0.01);
    EXPECT_NEAR(c.release.equivalent_radius, std::cbrt(0.7 * 1e-3 + 0.3 * 1.25e-4), 1e-12);
    EXPECT_NEAR(c.barrier.outlet_width, 0.40, 1e-12);  // S/R with R the large radius
    // lattice spacing = largest large diameter, small grains in 2x2x2 clusters: no overlap anywhere
    int overlaps = 0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        for (std::size_t j = i + 1; j < p.n_mobile; ++j)
            overlaps += norm(p.x[j] - p.x[i]) < p.r[i] + p.r[j] - 1e-12;
    }
    EXPECT_EQ(overlaps, 0);
    EXPECT_LE(c.release.hi.z, 1.35);
}

TEST(ChannelMesh, PartsNamedBedAreTheBedsReliefAndSetItsLevel) {
    EXPECT_TRUE(is_bed_part("bed_sill"));
    EXPECT_TRUE(is_bed_part("Bedrock"));
    EXPECT_FALSE(is_bed_part("side_wall"));
    EXPECT_FALSE(is_bed_part("be"));
    // a ramp rising to 0.3 m along x over [0, 1] (one triangle each side, in the x–z plane extruded across
    // y: its top only matters here) and a wall part above everything
    geometry::TriangleMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0.3}, {1, 1, 0.3}, {0, 1, 0}, {0, 0, 2}, {1, 0, 2}, {1, 1, 2}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
    m.part = {0, 0, 1};
    m.part_names = {"bed_ramp", "wall"};
    EXPECT_NEAR(bed_level(&m, 0.5, 0.5), 0.15, 1e-12);
    EXPECT_NEAR(bed_level(&m, 0.25, 0.9), 0.075, 1e-12);
    EXPECT_EQ(bed_level(&m, 1.5, 0.5), 0.0);  // past it: the plane
    EXPECT_EQ(bed_level(nullptr, 0.5, 0.5), 0.0);
    // its highest over a rectangle: at its side x = 0.5 (an edge crossing and the corners), at the ramp's top
    // vertices (x = 1) for one reaching past them, the plane for one beside it; the wall never counts
    EXPECT_NEAR(highest_bed_level(&m, 0.0, 0.5, 0.0, 1.0), 0.15, 1e-12);
    EXPECT_NEAR(highest_bed_level(&m, 0.2, 2.0, 0.1, 0.2), 0.3, 1e-12);
    EXPECT_NEAR(highest_bed_level(&m, 0.25, 0.75, 0.4, 0.6), 0.225, 1e-12);  // inside one triangle's face
    EXPECT_EQ(highest_bed_level(&m, 1.5, 2.0, 0.0, 1.0), 0.0);
    EXPECT_EQ(highest_bed_level(nullptr, 0.0, 1.0, 0.0, 1.0), 0.0);
}

}  // namespace
}  // namespace sabo::scenario
