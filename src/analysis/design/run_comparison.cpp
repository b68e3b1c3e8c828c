// SPDX-License-Identifier: MIT
#include "analysis/design/run_comparison.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "analysis/design/trapping.h"

namespace sabo::analysis::design {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string coefficient_text(double low, double high) {
    return low == high ? fmt::format("k = {:g}", low) : fmt::format("k = {:g}-{:g}", low, high);
}

}  // namespace

Comparison compare(const MeasuredRun& run, const Materials& materials) {
    Comparison c;
    const double w = run.width;
    const double peak_kN = run.peak_normal_force / 1000.0;
    for (const ImpactFormula& f : impact_formulas()) {
        c.rows.push_back({"impact", f.reference, f.formula, coefficient_text(f.k_low, f.k_high),
                          f.force_per_width(run.approach, f.k_low) * w / 1000.0,
                          f.force_per_width(run.approach, f.k_high) * w / 1000.0, peak_kN, "kN",
                          f.approach + ", peak normal force"});
    }
    // the largest grain as the boulder, at the front's speed (none in a run of the fluid alone)
    if (run.d_max > 0.0) {
        const Boulder boulder{0.5 * run.d_max, run.grain_density, run.front_velocity};
        const HertzImpact hertz = hertz_impact(boulder, materials.boulder, materials.barrier);
        for (const ReductionFactor& r : load_reduction_factors()) {
            const double f = r.k_c * hertz.elastic_force / 1000.0;
            c.rows.push_back({"boulder", r.reference, "F = K_c n alpha^1.5 (Hertz)",
                              fmt::format("K_c = {:g}", r.k_c), f, f, peak_kN, "kN",
                              "one grain of D_max at the front velocity"});
        }
        for (const ClosedForm& k : hertz_closed_forms()) {
            const double f = k.force(boulder.velocity, boulder.radius) / 1000.0;
            c.rows.push_back({"boulder", "closed form", "F = K v^1.2 r^2",
                              fmt::format("K = {:g} (F in {}; v in m/s, r in m)", k.k_hat, k.unit), f, f,
                              peak_kN, "kN", "one grain of D_max at the front velocity"});
        }
    }
    // trapping
    double total_open = 0.0, widest = 0.0;
    for (const Opening& o : run.openings) total_open += o.width, widest = std::max(widest, o.width);
    if (!run.openings.empty() && run.d95 > 0.0) {
        const double e =
            silva_trapping_efficiency({total_open / w, widest / run.d95, run.peak_discharge, run.slope_deg});
        c.rows.push_back({"trapping", "Silva et al. (2016)",
                          "E_tr = 1.55 (1 - sum S/W)^0.7 / ((S/D95)^1.4 e^v_d)", "", e, e,
                          run.retained_fraction, "-",
                          "trapping efficiency E_tr: the fraction of the grains retained (0-1); laboratory "
                          "regression"});
        const double q = mizuyama_peak_discharge_ratio(widest / run.d_max, run.solid_fraction);
        c.rows.push_back({"trapping", "Mizuyama (1995)", "Q_down/Q_up = 0.11 (S/D_max)^0.36 C_s^-0.96", "",
                          1.0 - q, 1.0 - q, nan, "-", "peak-discharge reduction 1 - Q_down/Q_up"});
        for (const SlitRange& r : slit_width_ranges()) {
            const double ratio = widest / (r.ratio == "S/D" ? run.d95 : run.d_max);
            c.rows.push_back({"guideline", r.source, r.ratio + " for retention", "", r.low, r.high, ratio,
                              "-",
                              fmt::format("this barrier's {} = {:.3g}: {} the range", r.ratio, ratio,
                                          place_in_range(ratio, r))});
        }
    }
    c.typology = barrier_typology(run.openings, run.barrier_height);
    // the simulated forces as the literature's coefficients
    const double peak_w = run.peak_normal_force / w, static_w = run.static_normal_force / w;
    Flow front = run.approach;
    front.velocity = run.front_velocity;
    const Flow deposit{run.deposit_depth, 0.0, run.deposit_density, run.approach.g};
    c.coefficients = {
        {"k_hydrostatic", "F_peak / (1/2 rho g h^2 W), gauge h and rho",
         back_calculated_hydrostatic_k(peak_w, run.approach)},
        {"k_hydrodynamic", "F_peak / (rho v^2 h W), gauge h, v and rho",
         back_calculated_hydrodynamic_k(peak_w, run.approach)},
        {"k_hydrodynamic_front", "F_peak / (rho v_front^2 h W)",
         back_calculated_hydrodynamic_k(peak_w, front)},
        {"k_static_deposit", "F_static / (1/2 rho_dep g h_dep^2 W), the deposit at the barrier",
         back_calculated_hydrostatic_k(static_w, deposit)},
        {"froude", "v / sqrt(g h) of the approaching flow", run.approach.froude()},
    };
    return c;
}

}  // namespace sabo::analysis::design
