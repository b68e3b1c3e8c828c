// SPDX-License-Identifier: MIT
// The hydrograph (exact integrals of piecewise-linear columns, its file's checks) and the inflow's batches
// (the asked volume to within one grain, no overlap, inside the zone, at the section's velocity).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "dem/particles.h"
#include "scenario/grain_inflow.h"
#include "scenario/hydrograph.h"

namespace sabo::scenario {
namespace {

TEST(Hydrograph, InterpolatesAndIntegratesExactly) {
    // a triangle of Q (0 → 2 → 0 m³/s over 0 … 1 … 3 s) with c rising 0.2 → 0.4 → 0.4
    const Hydrograph h({0.0, 1.0, 3.0}, {0.0, 2.0, 0.0}, {0.2, 0.4, 0.4});
    EXPECT_DOUBLE_EQ(h.discharge(0.5), 1.0);
    EXPECT_DOUBLE_EQ(h.discharge(2.0), 1.0);
    EXPECT_DOUBLE_EQ(h.solid_fraction(0.5), 0.3);
    EXPECT_EQ(h.discharge(-0.1), 0.0);
    EXPECT_EQ(h.discharge(3.1), 0.0);
    EXPECT_NEAR(h.volume(0.0, 3.0), 3.0, 1e-14);
    EXPECT_NEAR(h.volume(-5.0, 50.0), 3.0, 1e-14) << "nothing before the first row or after the last";
    // ∫0^1 2t (0.2 + 0.2t) dt = 0.2 + 0.4/3; ∫1^3 (3 − t) 0.4 dt = 0.8
    EXPECT_NEAR(h.solid_volume(0.0, 3.0), 0.2 + 0.4 / 3.0 + 0.8, 1e-14);
    // a part across a row: ∫0.5^2 Q c dt as the sum of its pieces
    EXPECT_NEAR(h.solid_volume(0.5, 2.0), h.solid_volume(0.5, 1.0) + h.solid_volume(1.0, 2.0), 1e-15);
    EXPECT_NEAR(h.solid_volume(1.0, 2.0), 0.4 * 1.5, 1e-14);
    EXPECT_EQ(h.largest_discharge(), 2.0);
}

TEST(Hydrograph, RefusesWhatIsNotAHydrograph) {
    EXPECT_THROW(Hydrograph({0.0}, {1.0}, {0.3}), InputError);                  // one row
    EXPECT_THROW(Hydrograph({0.0, 0.0}, {1.0, 1.0}, {0.3, 0.3}), InputError);   // time not increasing
    EXPECT_THROW(Hydrograph({0.0, 1.0}, {1.0, -1.0}, {0.3, 0.3}), InputError);  // Q < 0
    EXPECT_THROW(Hydrograph({0.0, 1.0}, {1.0, 1.0}, {0.3, 1.5}), InputError);   // c > 1
    EXPECT_THROW(Hydrograph({-1.0, 1.0}, {1.0, 1.0}, {0.3, 0.3}), InputError);  // t < 0
    const auto file = std::filesystem::temp_directory_path() / "sabo_hydrograph_test.csv";
    const auto read_text = [&](const std::string& text) {
        std::ofstream(file) << text;
        return Hydrograph::read(file);
    };
    EXPECT_NO_THROW(read_text("time_s,discharge_m3_s,solid_fraction\n0,1,0.3\n2,1,0.3\n"));
    try {
        (void)read_text("time_s,discharge_m3_s,solid_fraction\n0,1,0.3\n2,1,0.3\n1,1,0.3\n");
        FAIL() << "accepted a time going back";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("line 4: time_s must increase"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)read_text("time,Q,c\n0,1,0.3\n2,1,0.3\n"), InputError);
    const Hydrograph graded =
        read_text("time_s,discharge_m3_s,solid_fraction,radius_mean_m\n0,1,0.3,0.05\n2,1,0.3,0.1\n");
    EXPECT_TRUE(graded.graded());
    EXPECT_NEAR(graded.radius(1.0, 0.0), 0.075, 1e-15);
    EXPECT_DOUBLE_EQ(graded.largest_radius(), 0.1);
    std::filesystem::remove(file);
}

InflowSettings settings() {
    InflowSettings s;
    s.hydrograph = Hydrograph({0.0, 10.0}, {1.0, 1.0}, {0.3, 0.3});
    s.x0 = 0.5;
    s.velocity = 4.0;
    s.length = 1.0;
    s.width = 1.0;
    s.height = 1.0;
    s.radius = 0.05;
    s.spread = 0.05;
    return s;
}

// A batch places the volume asked (overshooting by at most its last grain) inside the zone, apart from each
// other and from the grains already there, moving at u; the same batch number draws the same grains.
TEST(GrainInflow, ABatchPlacesTheVolumeApartInsideTheZone) {
    const InflowSettings s = settings();
    dem::Particles present;
    present.add_mobile({0.9, 0.5, 0.06}, 0.06, 2500.0);  // a grain still in the zone
    double placed = 0.0;
    const double asked = s.hydrograph.solid_volume(0.0, 0.25);  // 0.075 m³: about 143 grains
    const auto grains = inflow_batch(s, 0.125, asked, 7, present, placed);
    ASSERT_GT(grains.size(), 130u);
    const double largest = 4.0 / 3.0 * M_PI * std::pow(0.0525, 3);
    EXPECT_GE(placed, asked);
    EXPECT_LT(placed, asked + largest);
    double volume = 0.0;
    for (std::size_t i = 0; i < grains.size(); ++i) {
        const auto& g = grains[i];
        volume += 4.0 / 3.0 * M_PI * g.r * g.r * g.r;
        EXPECT_GE(g.x.x - g.r, s.x0 - 1e-12);
        EXPECT_LE(g.x.x + g.r, s.x0 + s.length + 1e-12);
        EXPECT_GE(g.x.y - g.r, -1e-12);
        EXPECT_LE(g.x.y + g.r, s.width + 1e-12);
        EXPECT_GE(g.x.z - g.r, -1e-12);
        EXPECT_EQ(g.vh.x, 4.0);
        EXPECT_GE(norm(g.x - present.x[0]), g.r + present.r[0]);
        for (std::size_t j = 0; j < i; ++j) EXPECT_GE(norm(g.x - grains[j].x), g.r + grains[j].r);
    }
    EXPECT_NEAR(volume, placed, 1e-12 * placed);
    double again = 0.0;
    const auto same = inflow_batch(s, 0.125, asked, 7, present, again);
    ASSERT_EQ(same.size(), grains.size());
    EXPECT_EQ(same.back().x.x, grains.back().x.x);
    // a zone already full takes what fits and leaves the rest to the next batch
    dem::Particles full;
    for (const auto& g : grains) full.add_mobile(g.x, g.r, 2500.0);
    double more = 0.0;
    (void)inflow_batch(s, 0.375, 10.0 * asked, 8, full, more);
    EXPECT_LT(more, 10.0 * asked);
}

// On the bed's relief (base: its highest level under the zone) the batch is the plane's batch lifted by it:
// the same draws, every grain above the relief and below the walls.
TEST(GrainInflow, OnRaisedReliefTheBatchIsLiftedByItsLevel) {
    InflowSettings flat = settings(), raised = settings();
    raised.base = 0.3;
    raised.height = flat.height + raised.base;
    const dem::Particles none;
    double a = 0.0, b = 0.0;
    const double asked = flat.hydrograph.solid_volume(0.0, 0.25);
    const auto on_plane = inflow_batch(flat, 0.125, asked, 3, none, a);
    const auto on_relief = inflow_batch(raised, 0.125, asked, 3, none, b);
    ASSERT_EQ(on_relief.size(), on_plane.size());
    EXPECT_EQ(a, b);
    for (std::size_t i = 0; i < on_plane.size(); ++i) {
        EXPECT_EQ(on_relief[i].x.x, on_plane[i].x.x);
        EXPECT_DOUBLE_EQ(on_relief[i].x.z, on_plane[i].x.z + 0.3);
        EXPECT_GE(on_relief[i].x.z - on_relief[i].r, 0.3 - 1e-12);
        EXPECT_LE(on_relief[i].x.z + on_relief[i].r, raised.height + 1e-12);
    }
    EXPECT_EQ(raised.depth(asked, 0.3), flat.depth(asked, 0.3));
}

}  // namespace
}  // namespace sabo::scenario
