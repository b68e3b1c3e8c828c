// SPDX-License-Identifier: MIT
// The gauge section upstream of the barrier: one reading from known grains and fluid, and the approaching
// flow from a synthetic record whose front speed, arrival and peak are known.
#include "analysis/flow_gauge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace sabo::analysis {
namespace {

// A 0.4 m slab centred at X = 6.5 across a 2.1 m channel, three 0.7 m strips.
GaugeSection section() {
    return {6.5, 0.4, 2.1, 0.7};
}

TEST(FlowGauge, OneReadingOfGrains) {
    dem::Particles p;
    p.add_mobile({6.4, 0.3, 0.45}, 0.05, 2500.0, {1, 0, 0});
    p.add_mobile({6.6, 0.3, 0.15}, 0.05, 2500.0, {3, 0, 0});
    p.add_mobile({6.69, 1.0, 0.25}, 0.05, 2500.0, {2, 0, 0});
    p.add_mobile({6.71, 2.0, 1.0}, 0.05, 2500.0, {50, 0, 0});  // just beyond the slab's downstream end
    p.add_mobile({6.3, 2.0, 0.05}, 0.05, 2500.0, {9, 0, 0});   // at its upstream end: inside
    GaugeTally tally(section());
    tally.add_grains(p);
    const GaugeReading g = tally.reading(1.25);
    EXPECT_EQ(g.time, 1.25);
    EXPECT_NEAR(g.depth, (0.5 + 0.3 + 0.1) / 3.0, 1e-12);  // strip tops 0.45+0.05, 0.25+0.05, 0.05+0.05
    EXPECT_NEAR(g.velocity, (1.0 + 3.0 + 2.0 + 9.0) / 4.0, 1e-12);  // equal masses
    EXPECT_NEAR(g.discharge, g.depth * g.velocity * 2.1, 1e-12);
    const double bulk = 0.4 * 2.1 * g.depth;
    EXPECT_NEAR(g.solid_fraction, 4.0 * dem::sphere_volume(0.05) / bulk, 1e-12);
    EXPECT_NEAR(g.bulk_density, 4.0 * p.m[0] / bulk, 1e-9);
}

TEST(FlowGauge, TheDepthIsMeasuredFromTheBedUnderEachCell) {
    // the same grains over a bed raised 0.1 m under the first strip and 0.2 m under the second (one bin
    // along X: 0.4 m of 0.7 m cells)
    GaugeSection raised = section();
    ASSERT_EQ(raised.bins(), 1U);
    ASSERT_EQ(raised.strips(), 3U);
    raised.bed = {0.1, 0.2, 0.0};
    dem::Particles p;
    p.add_mobile({6.4, 0.3, 0.45}, 0.05, 2500.0, {1, 0, 0});
    p.add_mobile({6.6, 1.0, 0.25}, 0.05, 2500.0, {2, 0, 0});
    p.add_mobile({6.6, 2.0, 0.05}, 0.05, 2500.0, {3, 0, 0});
    GaugeTally tally(raised);
    tally.add_grains(p);
    const GaugeReading g = tally.reading(0.0);
    EXPECT_NEAR(g.depth, (0.5 - 0.1 + 0.3 - 0.2 + 0.1) / 3.0, 1e-12);
    EXPECT_NEAR(g.solid_fraction, 3.0 * dem::sphere_volume(0.05) / (0.4 * 0.7 * (0.4 + 0.1 + 0.1)), 1e-12);
    raised.bed = {0.1, 0.2};  // not one level per cell
    EXPECT_THROW(GaugeTally{raised}, std::logic_error);
}

TEST(FlowGauge, FluidAndGrainsMixByMass) {
    GaugeTally tally(section());
    // 1 kg of grain at 2 m/s and 3 kg of fluid at 6 m/s: the mixture moves at 5 m/s
    tally.add(6.5, 0.1, 0.2, 4e-4, 1.0, 2.0, true);
    tally.add(6.5, 0.8, 0.2, 2e-3, 3.0, 18.0, false);
    tally.add(6.5, 1.5, 0.2, 2e-3, 0.0, 0.0, false);
    const GaugeReading g = tally.reading(0.0);
    EXPECT_NEAR(g.depth, 0.2, 1e-12);
    EXPECT_NEAR(g.velocity, 5.0, 1e-12);
    EXPECT_NEAR(g.solid_fraction, 4e-4 / (0.4 * 2.1 * 0.2), 1e-12);  // the fluid's volume is not solid
    EXPECT_NEAR(g.bulk_density, 4.0 / (0.4 * 2.1 * 0.2), 1e-9);
}

TEST(FlowGauge, AFrontPartWayIntoTheSectionHasItsOwnBulkDensity) {
    // 0.1 m cells: 4 along the 0.4 m slab, 21 across; fluid 0.2 m deep over the first cell row only
    GaugeTally tally({6.5, 0.4, 2.1, 0.1});
    for (int s = 0; s < 21; ++s)
        tally.add(6.65, 0.05 + 0.1 * s, 0.2, 0.1 * 0.1 * 0.2, 1500.0 * 0.002, 0.0, false);
    const GaugeReading g = tally.reading(0.0);
    EXPECT_NEAR(g.depth, 0.2, 1e-12);
    EXPECT_NEAR(g.bulk_density, 1500.0, 1e-9);  // not a quarter of it: the empty cells hold no bulk
}

TEST(FlowGauge, EmptySectionReadsZero) {
    const GaugeReading g = GaugeTally(section()).reading(0.5);
    EXPECT_EQ(g.depth, 0.0);
    EXPECT_EQ(g.velocity, 0.0);
    EXPECT_EQ(g.solid_fraction, 0.0);
    EXPECT_EQ(g.bulk_density, 0.0);
}

// A surge passing a gauge 1.5 m upstream of the barrier: depth 0 until t = 1.0, then rising 1 m/s to a
// plateau of 0.4 m; velocity 4 m/s in the flow; sampled every 0.1 s. With the front at the barrier at
// t = 1.5 (first impact) the front velocity is 1.5 / (1.5 − arrival).
std::vector<GaugeReading> surge() {
    std::vector<GaugeReading> r;
    for (int k = 0; k <= 40; ++k) {
        const double t = 0.1 * k;
        const double depth = std::clamp(t - 1.0, 0.0, 0.4);
        const double v = depth > 0.0 ? 4.0 : 0.0;
        r.push_back({t, depth, v, depth * v * 2.1, 0.55, 1375.0});
    }
    return r;
}

TEST(FlowGauge, ApproachFlowFromTheRecord) {
    const auto record = surge();
    // arrival at depth 0.05 (t = 1.05, between the samples 1.0 and 1.1)
    const ApproachFlow a = approach_flow(record, 0.05, 1.5, 1.55, 1.9);
    EXPECT_NEAR(a.arrival_time, 1.05, 1e-12);
    EXPECT_NEAR(a.front_velocity, 1.5 / 0.5, 1e-12);
    // the flow reaching the barrier at the peak (1.9) passed the gauge 0.5 s earlier
    EXPECT_NEAR(a.source_time, 1.4, 1e-12);
    EXPECT_NEAR(a.at_source.depth, 0.4, 1e-12);
    EXPECT_NEAR(a.at_source.velocity, 4.0, 1e-12);
    EXPECT_NEAR(a.at_source.discharge, 0.4 * 4.0 * 2.1, 1e-12);
    // maxima up to the source time only
    EXPECT_NEAR(a.max_depth, 0.4, 1e-12);
    EXPECT_NEAR(a.max_velocity, 4.0, 1e-12);
}

TEST(FlowGauge, SourceBetweenSamplesIsInterpolatedAndBoundsTheWindow) {
    const auto record = surge();
    // peak 0.15 s after the impact: source 1.05 + 0.15 = 1.2 → ... with arrival 1.05, v_f = 1.5/0.3 = 5
    const ApproachFlow a = approach_flow(record, 0.05, 1.5, 1.35, 1.57);
    EXPECT_NEAR(a.front_velocity, 5.0, 1e-12);
    EXPECT_NEAR(a.source_time, 1.27, 1e-12);
    EXPECT_NEAR(a.at_source.depth, 0.27, 1e-12);  // on the rising limb, between 1.2 and 1.3
    EXPECT_NEAR(a.max_depth, 0.27, 1e-12);        // the plateau (0.4) had not yet passed
    EXPECT_NEAR(a.max_discharge, 0.27 * 4.0 * 2.1, 1e-12);
}

TEST(FlowGauge, NoImpactGivesTheArrivalAndTheWholeRecordsMaxima) {
    const ApproachFlow a = approach_flow(surge(), 0.05, 1.5, std::nan(""), std::nan(""));
    EXPECT_NEAR(a.arrival_time, 1.05, 1e-12);
    EXPECT_TRUE(std::isnan(a.front_velocity));
    EXPECT_TRUE(std::isnan(a.source_time));
    EXPECT_TRUE(std::isnan(a.at_source.depth));
    EXPECT_NEAR(a.max_depth, 0.4, 1e-12);
}

TEST(FlowGauge, FrontThatNeverArrivesOrHitsTheBarrierFirst) {
    const ApproachFlow never = approach_flow(surge(), 0.5, 1.5, 1.5, 1.9);  // the surge is 0.4 m deep
    EXPECT_TRUE(std::isnan(never.arrival_time));
    EXPECT_TRUE(std::isnan(never.front_velocity));
    EXPECT_TRUE(std::isnan(never.max_depth));
    // a barrier hit before the gauge saw the arrival depth (stray grains ahead of the front)
    const ApproachFlow early = approach_flow(surge(), 0.05, 1.5, 0.9, 1.9);
    EXPECT_NEAR(early.arrival_time, 1.05, 1e-12);
    EXPECT_TRUE(std::isnan(early.front_velocity));
    EXPECT_TRUE(std::isnan(early.at_source.depth));
}

}  // namespace
}  // namespace sabo::analysis
