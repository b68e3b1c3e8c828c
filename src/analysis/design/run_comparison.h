// SPDX-License-Identifier: MIT
// A run beside the design formulas (`sabo design compare`, docs/design.md): every impact formula's force
// for the flow the gauge measured, the boulder impact of the largest grain, the trapping relations and
// guideline ranges for the barrier's openings, next to the simulated forces and retained fraction; and the
// simulated forces as the coefficients the literature back-calculates.
#pragma once
#include <string>
#include <vector>

#include "analysis/design/boulder_impact.h"
#include "analysis/design/impact_force.h"
#include "analysis/design/typology.h"

namespace sabo::analysis::design {

// What a run measured that the formulas need (the "design_inputs" of summary.json).
struct MeasuredRun {
    Flow approach;                   // at the gauge: the flow that reached the barrier at the largest force
    double front_velocity = 0.0;     // m/s, gauge to barrier
    double peak_discharge = 0.0;     // m³/s, Q_peak of the approaching flow
    double solid_fraction = 0.0;     // C_s of the approaching flow
    double width = 0.0;              // barrier (channel) width W, m
    double peak_normal_force = 0.0;  // N
    double static_normal_force =
        0.0;                       // N, of the deposit at rest (NaN: the run ended before it came to rest)
    double deposit_depth = 0.0;    // m, mean height of the deposit in the first metre upstream at the end
    double deposit_density = 0.0;  // kg/m³, its bulk density
    double slope_deg = 0.0;
    double barrier_height = 0.0;  // m
    std::vector<Opening> openings;
    double d95 = 0.0, d_max = 0.0;   // m, grain diameters (D95 by mass)
    double grain_density = 0.0;      // kg/m³
    double retained_fraction = 0.0;  // of the grains' mass, at the end
};

// Material constants of the boulder-impact estimate.
struct Materials {
    Elastic boulder = granite;
    Elastic barrier = concrete;
};

// One line of the comparison: a prediction (a range where the coefficient is one) and the simulated value
// it compares with, in the same unit.
struct DesignRow {
    std::string group;  // impact | boulder | trapping | guideline | typology
    std::string reference;
    std::string formula;
    std::string coefficient;  // "k = 2.5-7.5"
    double low = 0.0, high = 0.0;
    double simulated = 0.0;
    std::string unit;  // "kN" | "-"
    std::string note;
};
struct BackCalculated {
    std::string name, definition;
    double value = 0.0;
};
struct Comparison {
    std::vector<DesignRow> rows;
    std::vector<BackCalculated> coefficients;
    std::string typology;
};
[[nodiscard]] Comparison compare(const MeasuredRun& run, const Materials& materials = {});

}  // namespace sabo::analysis::design
