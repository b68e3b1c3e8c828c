// SPDX-License-Identifier: MIT
// The design formulas on hand-computed values (docs/design.md): a 1.2 m deep flow of 2000 kg/m³ at 5 m/s,
// a 1 m granite boulder at 5 m/s on concrete, a laboratory slit dam, and the barrier typology.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/design/boulder_impact.h"
#include "analysis/design/impact_force.h"
#include "analysis/design/run_comparison.h"
#include "analysis/design/trapping.h"
#include "analysis/design/typology.h"

namespace sabo::analysis::design {
namespace {

const Flow flow{1.2, 5.0, 2000.0, 9.81};  // g h = 11.772 m²/s², Fr = 5 / sqrt(11.772) = 1.45729

TEST(ImpactFormulas, HydrostaticAndHydrodynamic) {
    EXPECT_NEAR(flow.froude(), 1.4572863, 1e-6);
    // ½ 5 · 2000 · 9.81 · 1.44 = 70 632 N/m; 2 · 2000 · 25 · 1.2 = 120 000 N/m
    EXPECT_NEAR(hydrostatic_force_per_width(flow, 5.0), 70632.0, 1e-6);
    EXPECT_NEAR(hydrodynamic_force_per_width(flow, 2.0), 120000.0, 1e-6);
}

TEST(ImpactFormulas, KherkheulidzeInTechnicalUnits) {
    // γ = 2 tf/m³: p = 0.1 · 2 · (6 + 25) = 6.2 tf/m² = 6.2 · 9806.65 Pa
    EXPECT_NEAR(kherkheulidze_pressure(flow), 6.2 * 9806.65, 1e-6);
}

TEST(ImpactFormulas, MixedForms) {
    // 5 · 2000 · 5^0.8 · 11.772^0.6
    EXPECT_NEAR(hubl_holzinger_pressure(flow, 5.0), 159105.853, 1e-3);
    // ½ · 2000 · 9.81 · 1.44 · (1 + √2 · 1.45729)²
    EXPECT_NEAR(zanuttigh_lamberti_force_per_width(flow, 1.0), 132352.992, 1e-3);
    // ρ q v + ½ ρ g h² = 2000 · 6 · 5 + 14 126.4
    EXPECT_NEAR(arattano_franzi_force_per_width(flow), 74126.4, 1e-6);
}

TEST(ImpactFormulas, CatalogueRangesGrowWithTheCoefficient) {
    for (const ImpactFormula& f : impact_formulas()) {
        EXPECT_LE(f.k_low, f.k_high) << f.reference;
        EXPECT_LE(f.force_per_width(flow, f.k_low), f.force_per_width(flow, f.k_high)) << f.reference;
    }
    // Scotton & Deganutti: k 2.5–7.5 on the hydrostatic form
    const auto& sd = impact_formulas()[2];
    EXPECT_EQ(sd.reference, "Scotton & Deganutti (1997)");
    EXPECT_NEAR(sd.force_per_width(flow, sd.k_high), 70632.0 * 7.5 / 5.0, 1e-6);
}

TEST(ImpactFormulas, BackCalculatedCoefficientsInvertTheForms) {
    EXPECT_NEAR(back_calculated_hydrostatic_k(70632.0, flow), 5.0, 1e-12);
    EXPECT_NEAR(back_calculated_hydrodynamic_k(120000.0, flow), 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(back_calculated_hydrodynamic_k(1.0, Flow{0.0, 5.0, 2000.0})));
}

TEST(BoulderImpact, HertzOfAGraniteBoulderOnConcrete) {
    const Boulder b{0.5, 2650.0, 5.0};
    EXPECT_NEAR(b.mass(), 1387.53676, 1e-4);
    // k_c = 0.96/(π 30 GPa), k_B = 0.9375/(π 60 GPa): n = 4 sqrt(0.5) / (3π (k_B + k_c))
    const HertzImpact h = hertz_impact(b, granite, concrete);
    EXPECT_NEAR(h.stiffness / 1.97965153e10, 1.0, 1e-8);
    EXPECT_NEAR(h.indentation, 5.44756357e-3, 1e-11);
    EXPECT_NEAR(h.elastic_force / 7.95961773e6, 1.0, 1e-8);
    // the closed form: F = C r² v^1.2 with C ≈ 4615 kN for these materials (K_c = 0.1: K ≈ 461 kN)
    const double c = hertz_closed_form_constant(2650.0, granite, concrete);
    EXPECT_NEAR(c / 4.61517525e6, 1.0, 1e-8);
    EXPECT_NEAR(c * 0.25 * std::pow(5.0, 1.2), h.elastic_force, 1e-6 * h.elastic_force);
}

TEST(BoulderImpact, ClosedFormsInTheirUnits) {
    const auto& forms = hertz_closed_forms();
    ASSERT_EQ(forms.size(), 6u);
    EXPECT_NEAR(forms[1].force(1.0, 1.0), 48.2 * 9806.65, 1e-6);  // 48.2 tf
    EXPECT_NEAR(forms[2].force(2.0, 0.5), 426e3 * std::pow(2.0, 1.2) * 0.25, 1e-6);
    // each implies a load reduction factor of 0.05–0.2 for concrete and granite
    const double c = hertz_closed_form_constant(2650.0, granite, concrete);
    for (const ClosedForm& k : forms) {
        const double k_c = k.k_hat * k.newtons_per_unit / c;
        EXPECT_GT(k_c, 0.04) << k.k_hat;
        EXPECT_LT(k_c, 0.2) << k.k_hat;
    }
}

TEST(Trapping, SilvaAndMizuyama) {
    // ΣS/W = 0.1, S/D95 = 1.5, Q = 0.005 m³/s, θ = 10°: v_d = 2.1 · 0.005^0.33 · 10^0.33 = 0.78141
    EXPECT_NEAR(silva_trapping_efficiency({0.1, 1.5, 0.005, 10.0}), 0.37360382, 1e-7);
    EXPECT_EQ(silva_trapping_efficiency({0.0, 0.5, 0.0, 10.0}), 1.0);  // 1.55 / 0.5^1.4 > 1: clamped
    // 0.11 · 2^0.36 · 0.4^−0.96
    EXPECT_NEAR(mizuyama_peak_discharge_ratio(2.0, 0.4), 0.34024041, 1e-7);
    EXPECT_EQ(mizuyama_peak_discharge_ratio(4.0, 0.05), 1.0);  // dilute flow: no reduction
}

TEST(Trapping, GuidelineRanges) {
    const auto& ranges = slit_width_ranges();
    ASSERT_EQ(ranges.size(), 5u);
    EXPECT_EQ(place_in_range(1.2, ranges[1]), "below");
    EXPECT_EQ(place_in_range(1.5, ranges[1]), "within");
    EXPECT_EQ(place_in_range(3.0, ranges[1]), "above");
    EXPECT_EQ(place_in_range(1.0, ranges[2]), "within");  // the 2007 standard: the opening equals D_max
    EXPECT_EQ(place_in_range(1.5, ranges[2]), "above");
}

TEST(Typology, FromTheOpenings) {
    const double h = 1.35;
    const std::vector<Opening> slit{{0.15, h, true}};
    EXPECT_EQ(barrier_typology(slit, h), "slit");
    const std::vector<Opening> wide{{1.0, h, true}};
    EXPECT_EQ(barrier_typology(wide, h), "sectional");
    const std::vector<Opening> hole{{0.5, 0.5, false}};
    EXPECT_EQ(barrier_typology(hole, h), "slot");
    const std::vector<Opening> grid(5, Opening{0.2, 0.2, false});
    EXPECT_EQ(barrier_typology(grid, h), "lattice");
    const std::vector<Opening> mixed{{0.15, h, true}, {0.5, 0.5, false}};
    EXPECT_EQ(barrier_typology(mixed, h), "compound");
    EXPECT_EQ(barrier_typology({}, h), "closed");
}

TEST(RunComparison, RowsAndCoefficients) {
    MeasuredRun run;
    run.approach = flow;
    run.front_velocity = 5.0;
    run.peak_discharge = 15.0;
    run.solid_fraction = 0.4;
    run.width = 2.0;
    run.peak_normal_force = 2.0 * 120000.0;  // k_hydrodynamic = 2
    run.static_normal_force = 2.0 * 70632.0;
    run.deposit_depth = 1.2;
    run.deposit_density = 2000.0;
    run.slope_deg = 10.0;
    run.barrier_height = 1.35;
    run.openings = {{0.3, 1.35, true}};
    run.d95 = 0.15;
    run.d_max = 0.2;
    run.grain_density = 2650.0;
    run.retained_fraction = 0.8;
    const Comparison c = compare(run);
    EXPECT_EQ(c.typology, "slit");
    EXPECT_NEAR(c.coefficients[0].value, 240000.0 / 2.0 / 14126.4, 1e-9);  // hydrostatic
    EXPECT_NEAR(c.coefficients[1].value, 2.0, 1e-12);
    EXPECT_NEAR(c.coefficients[3].value, 5.0, 1e-12);  // the static load as ½ k ρ g h²
    // Watanabe & Ikeya (k = 2) predicts exactly the simulated peak
    bool found = false;
    for (const DesignRow& r : c.rows)
        if (r.reference == "Watanabe & Ikeya (1981)") {
            found = true;
            EXPECT_NEAR(r.low, 240.0, 1e-9);
            EXPECT_NEAR(r.simulated, 240.0, 1e-9);
        }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace sabo::analysis::design
