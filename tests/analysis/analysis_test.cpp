// SPDX-License-Identifier: MIT
// The barrier analyses of SPEC §3 on synthetic inputs with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "analysis/crest_flux.h"
#include "analysis/flow_measures.h"
#include "analysis/stop_detector.h"
#include "core/error.h"
#include "io/json_writer.h"
#include "scenario/barrier.h"

namespace sabo::analysis {
namespace {

// An OB slit barrier across a 2.1 m channel, face at X = 8, 0.1 m thick, H_bar = 1.0 m, one outlet
// [1.0, 1.1], two piles; elements: one fixed sphere per pile at heights 0.25 (pile 0) and 0.75 (pile 1), the
// last two particles.
scenario::BarrierInfo slit() {
    scenario::BarrierInfo b;
    b.type = scenario::BarrierType::slit;
    b.orientation = scenario::BarrierOrientation::OB;
    b.face_x = 8.0;
    b.thickness = 0.1;
    b.height = 1.0;
    b.piles = {{0.0, 1.0}, {1.1, 2.1}};
    b.outlets = {{1.0, 1.1}};
    b.elements = {{true, 0, {8.05, 0.5, 0.25}, 0.25, 0}, {true, 1, {8.05, 1.6, 0.75}, 0.75, 1}};
    b.sphere_count = 2;  // the last two particles
    return b;
}

dem::Particles grains(const std::vector<Vec3>& x, const std::vector<Vec3>& v, double r = 0.05) {
    dem::Particles p;
    for (std::size_t i = 0; i < x.size(); ++i) p.add_mobile(x[i], r, 2500.0, v[i]);
    return p;
}

TEST(FlowMeasures, NonRetainedFractionIsTheMassDownstreamOfTheDownstreamFace) {
    const auto b = slit();
    // face plane X = 8, downstream face X = 8.1: only centres beyond 8.1 count
    dem::Particles p;
    p.add_mobile({7.0, 1.0, 0.1}, 0.05, 2500.0);
    p.add_mobile({8.09, 1.0, 0.1}, 0.05, 2500.0);  // inside the barrier thickness: retained
    p.add_mobile({8.2, 1.0, 0.1}, 0.10, 2500.0);   // 8× the mass of a 5 cm grain
    EXPECT_NEAR(non_retained_fraction(p, b), 8.0 / 10.0, 1e-12);
}

// The crest flux integrated over time counts a grain that crosses the barrier's thickness once, whatever its
// speed and step: above the crest as overtopping, below it as through the outlets; one that enters the slab
// and turns back counts nothing; grains outside the slab never count.
TEST(CrestFlux, ItsTimeIntegralIsTheMassThatCrossedTheBarrier) {
    const auto b = slit();  // face X = 8, 0.1 m thick, crest Z = 1.0
    // the flux over the candidates near the slab (found again each step, a margin of 5 cm)
    const auto flux_of = [](const dem::Particles& p, const scenario::BarrierInfo& barrier) {
        std::vector<std::uint32_t> near;
        crest_flux_candidates(p, p.n_mobile, barrier, 0.05, near);
        return crest_flux(p, near, barrier);
    };
    const auto crossed = [&](std::vector<Vec3> x, std::vector<Vec3> v, double dt, int steps) {
        dem::Particles p = grains(x, v);
        double over = 0.0, through = 0.0;
        for (int k = 0; k < steps; ++k) {
            for (std::size_t i = 0; i < p.n_mobile; ++i) p.x[i] += dt * p.v[i];
            const CrestFlux f = flux_of(p, b);
            over += f.over * dt, through += f.through * dt;
        }
        return std::pair{over, through};
    };
    const double m = 2500.0 * 4.0 / 3.0 * M_PI * std::pow(0.05, 3);
    // 1 m at 2 m/s in 1000 steps of 0.5 ms: 100 steps inside the slab
    const auto [over, through] =
        crossed({{7.6, 1.05, 1.2}, {7.6, 1.05, 0.5}}, {{2, 0, 0}, {2, 0, 0}}, 5e-4, 1000);
    EXPECT_NEAR(over, m, 1e-9 * m);
    EXPECT_NEAR(through, m, 1e-9 * m);
    // a step that is not a divisor of the slab: within one step's share
    const auto [coarse, none] = crossed({{7.6, 1.05, 1.2}}, {{3, 0, 0}}, 7e-3, 60);
    EXPECT_NEAR(coarse, m, 3.0 * 7e-3 / 0.1 * m);
    EXPECT_EQ(none, 0.0);
    // into the slab and back out upstream: nothing crossed, to within one step's share (v dt / t of the mass:
    // where the sampled positions fall at the slab's face)
    dem::Particles p = grains({{7.95, 1.05, 1.2}}, {{1, 0, 0}});
    double net = 0.0;
    for (int k = 0; k < 200; ++k) {
        if (k == 100) p.v[0] = {-1, 0, 0};
        p.x[0] += 1e-3 * p.v[0];
        net += flux_of(p, b).over * 1e-3;
    }
    EXPECT_NEAR(net, 0.0, 1.001 * m * 1e-3 / 0.1);
    EXPECT_LT(std::abs(net), 0.02 * m);
    // no barrier: nothing
    scenario::BarrierInfo none_there;
    EXPECT_EQ(flux_of(grains({{8.05, 1.0, 1.2}}, {{1, 0, 0}}), none_there).over, 0.0);
    // the candidates: within the margin of the slab along the face normal, nothing farther
    std::vector<std::uint32_t> near;
    crest_flux_candidates(
        grains({{7.9, 1.0, 0.5}, {7.96, 1.0, 0.5}, {8.05, 1.0, 1.5}, {8.14, 1.0, 0.5}, {8.2, 1.0, 0.5}},
               {{}, {}, {}, {}, {}}),
        5, b, 0.05, near);
    EXPECT_EQ(near, (std::vector<std::uint32_t>{1, 2, 3}));
}

TEST(FlowMeasures, VerticalBarrierUsesTheTiltedFace) {
    auto b = slit();
    const double theta = 30.0 * M_PI / 180.0;
    b.orientation = scenario::BarrierOrientation::VB;
    b.tan_tilt = std::tan(theta);
    b.face_normal = {std::cos(theta), 0.0, std::sin(theta)};
    // at height z the upstream face is at X = 8 − z tan θ
    EXPECT_NEAR(b.upstream_distance({8.0 - 1.0 * std::tan(theta) - 0.3, 1.0, 1.0}), 0.3, 1e-12);
    EXPECT_FALSE(b.downstream({8.0 - 1.0 * std::tan(theta) + 0.05, 1.0, 1.0}));
    EXPECT_TRUE(b.downstream({8.0 - 1.0 * std::tan(theta) + 0.2 / std::cos(theta), 1.0, 1.0}));
}

TEST(FlowMeasures, DownstreamEnergyIsTheMeanPerGrain) {
    const auto b = slit();
    auto p = grains({{9.0, 1.0, 0.1}, {9.5, 1.0, 0.1}, {5.0, 1.0, 0.1}}, {{2, 0, 0}, {0, 0, 0}, {10, 0, 0}});
    const auto d = downstream_energy(p, b);
    EXPECT_EQ(d.grains, 2u);
    EXPECT_NEAR(d.mean_J, 0.5 * (0.5 * p.m[0] * 4.0), 1e-12);
}

TEST(FlowMeasures, UpstreamFlowHeightAndVelocity) {
    const auto b = slit();
    // reach [0, 1] m upstream of X = 8; strips of 0.7 m across 2.1 m: three strips
    auto p = grains({{7.5, 0.3, 0.45}, {7.5, 0.3, 0.15}, {7.8, 1.0, 0.25}, {6.0, 2.0, 1.0}},
                    {{1, 0, 0}, {3, 0, 0}, {2, 0, 0}, {50, 0, 0}});
    const auto f = upstream_flow(p, b, 2.1, 1.0, 0.7);
    EXPECT_EQ(f.grains, 3u);
    EXPECT_NEAR(f.height, (0.5 + 0.3 + 0.0) / 3.0, 1e-12);  // tops 0.45+0.05 and 0.25+0.05; third strip empty
    EXPECT_NEAR(f.velocity, 2.0, 1e-12);                    // equal masses: mean of 1, 3, 2
    // three grains' volume over the reach's 1 m × 2.1 m × h
    EXPECT_NEAR(f.solid_fraction, 3.0 * dem::sphere_volume(p.r[0]) / (1.0 * 2.1 * f.height), 1e-12);
}

TEST(DesignCoefficients, MatchTheHydrostaticAndHydrodynamicForms) {
    // a triangular hydrostatic load p = k ρ g z over height h gives F/W = k ρ g h²/2: k_st (no ½) = k
    const double rho = 2500.0, g = 9.81, h = 0.8, k = 1.7;
    EXPECT_NEAR(k_static(k * rho * g * h * h, rho, g, h), k, 1e-12);
    EXPECT_NEAR(k_dynamic(2.0 * rho * 4.0 * 4.0 * h, rho, 4.0, h), 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(k_static(1.0, rho, g, 0.0)));
}

TEST(StopDetector, NeedsTheHoldTimeBelowTheThreshold) {
    StopDetector s(1.0, 0.5);
    EXPECT_FALSE(s.sample(0.0, 5.0));
    EXPECT_FALSE(s.sample(0.1, 0.5));
    EXPECT_FALSE(s.sample(0.5, 0.5));
    EXPECT_FALSE(s.sample(0.55, 2.0));  // moving again: the hold restarts
    EXPECT_FALSE(s.sample(0.6, 0.1));
    EXPECT_FALSE(s.sample(1.0, 0.1));
    EXPECT_TRUE(s.sample(1.1, 0.1));
    EXPECT_NEAR(s.quiet_since(), 0.6, 1e-12);
}

TEST(BarrierForceMonitor, MapsPeaksEnvelopeAndPiles) {
    const auto b = slit();
    BarrierForceMonitor m(b);
    std::vector<Vec3> pf(4), wf;
    m.record(0.1, pf, wf);  // nothing yet
    EXPECT_TRUE(std::isnan(m.first_impact_time()));
    pf[2] = {3, 0, 0};
    m.record(0.2, pf, wf);  // t1
    pf[2] = {10, 0, 0};
    pf[3] = {0, 4, 0};
    m.record(0.3, pf, wf);  // largest local force (10) → t2
    EXPECT_TRUE(m.new_normal_peak());
    pf[2] = {8, 0, 0};
    pf[3] = {6, 0, 0};
    m.record(0.4, pf, wf);  // largest global force |(14, 0, 0)| → t3
    pf[2] = {1, 0, 0};
    pf[3] = {1, 0, 0};
    m.record(0.5, pf, wf);
    EXPECT_FALSE(m.new_normal_peak());
    // a grain left the run: the fixed spheres moved one place down and are still found
    pf = {{}, {1, 0, 0}, {1, 0, 0}};
    m.record(0.5, pf, wf);
    EXPECT_NEAR(m.global().x, 2.0, 1e-12);
    m.finish(0.5);
    EXPECT_NEAR(m.first_impact_time(), 0.2, 1e-12);
    EXPECT_NEAR(m.map_t1().force[0].x, 3.0, 1e-12);
    EXPECT_NEAR(m.map_t2().time, 0.3, 1e-12);
    EXPECT_NEAR(m.max_local(), 10.0, 1e-12);
    EXPECT_NEAR(m.map_t3().time, 0.4, 1e-12);
    EXPECT_NEAR(m.max_global(), 14.0, 1e-12);
    EXPECT_NEAR(m.max_normal(), 14.0, 1e-12);
    EXPECT_NEAR(m.time_of_max_normal(), 0.4, 1e-12);
    EXPECT_NEAR(m.map_end().force[1].x, 1.0, 1e-12);
    EXPECT_NEAR(m.envelope()[0], 10.0, 1e-12);
    EXPECT_NEAR(m.envelope()[1], 6.0, 1e-12);
    // pile 1 element at height 0.75: max normal 6 at t = 0.4, moment 4.5
    EXPECT_NEAR(m.piles()[1].max_normal, 6.0, 1e-12);
    EXPECT_NEAR(m.piles()[1].max_moment, 4.5, 1e-12);
    EXPECT_NEAR(m.piles()[0].max_moment, 2.5, 1e-12);
    EXPECT_NEAR(m.take_interval_peak(), 14.0, 1e-12);
    EXPECT_NEAR(m.take_interval_peak(), 0.0, 1e-12);
    EXPECT_NEAR(m.tangential(), 0.0, 1e-12);
}

// The fluid is a separate component: the totals (maps, envelope, piles) are grains + fluid, the fluid_*
// accessors the fluid alone; a fluid-only run passes no solver forces.
TEST(BarrierForceMonitor, FluidIsASeparateComponentOfTheTotal) {
    const auto b = slit();
    BarrierForceMonitor m(b);
    std::vector<Vec3> pf(4), wf, fluid(2);
    pf[2] = {3, 0, 0};
    fluid[0] = {2, 1, 0};
    fluid[1] = {5, 0, 0};
    m.record(0.1, pf, wf, fluid);
    EXPECT_NEAR(m.global().x, 10.0, 1e-12);  // 3 + 2 + 5
    EXPECT_NEAR(m.global().y, 1.0, 1e-12);
    EXPECT_NEAR(m.fluid_global().x, 7.0, 1e-12);
    EXPECT_NEAR(m.fluid_normal(), 7.0, 1e-12);
    EXPECT_NEAR(m.map_t1().force[0].x, 5.0, 1e-12);
    EXPECT_NEAR(m.envelope()[0], std::hypot(5.0, 1.0), 1e-12);
    EXPECT_NEAR(m.fluid_envelope()[0], std::hypot(2.0, 1.0), 1e-12);
    EXPECT_NEAR(m.fluid_envelope()[1], 5.0, 1e-12);
    fluid[1] = {9, 0, 0};
    m.record(0.2, {}, {}, fluid);  // fluid only
    EXPECT_NEAR(m.global().x, 11.0, 1e-12);
    EXPECT_NEAR(m.max_fluid_normal(), 11.0, 1e-12);
    EXPECT_NEAR(m.time_of_max_fluid_normal(), 0.2, 1e-12);
    EXPECT_NEAR(m.piles()[1].max_normal, 9.0, 1e-12);
    m.record(0.3, pf, wf);  // grains only: the fluid component is zero
    EXPECT_NEAR(m.fluid_normal(), 0.0, 1e-12);
    EXPECT_NEAR(m.global().x, 3.0, 1e-12);
    EXPECT_NEAR(m.max_fluid_normal(), 11.0, 1e-12);
}

// Arching box: 4 r = 0.2 m upstream of X = 8, Y in [1.0, 1.1], 10 intervals of 0.1 m.
TEST(ArchingMonitor, HaltsIntervalsThatStayQuietAndReportsTheArch) {
    const auto b = slit();
    ArchingMonitor a(b, 0.2, 10, 1e-5);
    // grains at heights 0.05, 0.15, 0.35 inside the box; one outside (upstream beyond 0.2 m)
    auto p = grains({{7.9, 1.05, 0.05}, {7.9, 1.05, 0.15}, {7.9, 1.05, 0.35}, {7.5, 1.05, 0.75}},
                    {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}});
    a.sample(1.0, p);  // all moving
    p.v[0] = {};
    a.sample(1.5, p);  // the lowest halts at 1.5
    p.v[1] = {};
    p.v[2] = {};
    a.sample(2.0, p);  // the next ones at 2.0
    p.v[2] = {0.1, 0, 0};
    a.sample(2.5, p);  // the one at 0.35 moves again: not halted
    const auto& o = a.outlets()[0];
    EXPECT_EQ(o.intervals.size(), 10u);
    EXPECT_TRUE(o.intervals[0].halted());
    EXPECT_NEAR(o.intervals[0].below_since, 1.5, 1e-12);
    EXPECT_TRUE(o.intervals[1].halted());
    EXPECT_FALSE(o.intervals[3].halted());
    EXPECT_FALSE(o.intervals[7].halted());  // empty intervals never count
    EXPECT_EQ(o.halted_count(), 2);
    EXPECT_NEAR(o.arch_height_ratio(1.0), 0.2, 1e-12);
    EXPECT_NEAR(o.arch_stop_time(), 2.0, 1e-12);
}

OutletArching outlet_with_halts(const std::vector<double>& halt_times) {  // negative: not halted
    OutletArching o;
    for (std::size_t k = 0; k < 10; ++k) {
        ArchingInterval iv{0.1 * k, 0.1 * (k + 1)};
        iv.grains = 3;
        iv.below_since = k < halt_times.size() ? halt_times[k] : -1.0;
        o.intervals.push_back(iv);
    }
    return o;
}

TEST(ClogClassification, FollowsTheDocumentedRules) {
    const double t0 = 2.0;
    EXPECT_EQ(classify_clogging(outlet_with_halts({}), t0, 0.9), no_clogging);
    // 7 of 10 halt within 1 s of t0, 3 % passes
    EXPECT_EQ(classify_clogging(outlet_with_halts({2.3, 2.4, 2.5, 2.6, 2.7, 2.8, 2.9}), t0, 0.03),
              instant_high_arch);
    // same halts but 40 % passed: not "almost all retained"
    EXPECT_EQ(classify_clogging(outlet_with_halts({2.3, 2.4, 2.5, 2.6, 2.7, 2.8, 2.9}), t0, 0.4),
              progressive);
    // lower intervals first, upper later
    EXPECT_EQ(classify_clogging(outlet_with_halts({2.5, 3.5, 4.5, 5.5, 6.5}), t0, 0.3), progressive);
    // two low intervals, long after t0
    EXPECT_EQ(classify_clogging(outlet_with_halts({9.0, 10.0}), t0, 0.6), late_low_arch);
    EXPECT_EQ(classify_run({progressive, late_low_arch, progressive}), progressive);
    EXPECT_EQ(classify_run({progressive, late_low_arch}), late_low_arch);  // tie: the less clogged
    EXPECT_EQ(classify_run({}), no_clogging);
}

TEST(SectionalLayout, BoundaryPilesFollowTheFormula) {
    const auto cfg = Config::from_string("", "t.toml");
    for (const auto& layout : scenario::sectional_configurations()) {
        const auto piles = scenario::sectional_piles(cfg, "barrier.configuration", 2.10, layout);
        ASSERT_EQ(static_cast<int>(piles.size()), layout.piles) << layout.name;
        const double b =
            0.5 * (2.10 - (layout.piles - 2) * layout.pile_width - (layout.piles - 1) * layout.outlet_width);
        EXPECT_NEAR(piles.front().width(), b, 1e-12) << layout.name;
        EXPECT_NEAR(piles.back().hi, 2.10, 1e-12) << layout.name;
        EXPECT_NEAR(piles.back().width(), b, 1e-9) << layout.name;
        for (std::size_t k = 1; k < piles.size(); ++k) {
            EXPECT_NEAR(piles[k].lo - piles[k - 1].hi, layout.outlet_width, 1e-9) << layout.name;
            if (k + 1 < piles.size()) {
                EXPECT_NEAR(piles[k].width(), layout.pile_width, 1e-12) << layout.name;
            }
        }
        // CASES C3: b = P for C, D, G, H, I
        if (layout.name == "C" || layout.name == "D" || layout.name == "G" || layout.name == "H" ||
            layout.name == "I") {
            EXPECT_NEAR(b, layout.pile_width, 1e-9) << layout.name;
        }
    }
    scenario::SectionalLayout too_wide{"custom", 4, 0.5, 0.4};
    EXPECT_THROW((void)scenario::sectional_piles(cfg, "barrier.piles", 2.10, too_wide), InputError);
}

TEST(JsonWriter, NullForNonFiniteAndEscapedStrings) {
    io::JsonObject o;
    o.number("a", 1.5).number("b", std::nan("")).text("c", "say \"hi\"\n").integer("d", -3);
    EXPECT_EQ(o.dump(false), R"({"a": 1.5, "b": null, "c": "say \"hi\"\n", "d": -3})");
}

}  // namespace
}  // namespace sabo::analysis
