// SPDX-License-Identifier: MIT
// What a channel or debris run hands the design comparison (analysis/design/run_comparison.h): the
// approaching flow from the gauge, the barrier's peak and final normal forces, the deposit at the barrier,
// the grain sizes and the barrier's openings.
#pragma once
#include <filesystem>

#include "analysis/design/run_comparison.h"
#include "analysis/flow_gauge.h"
#include "analysis/flow_measures.h"
#include "io/design_output.h"
#include "io/json_writer.h"
#include "scenario/barrier.h"

namespace sabo::cases {

struct RunForces {
    double peak_normal = 0.0;  // N
    // N, the normal force of a deposit at rest (NaN: the run ended before it came to rest)
    double static_normal = 0.0;
};

// `fluid_density`: the pore fluid's (0 dry), for the deposit's bulk density; `retained`: the grains' mass
// fraction upstream of the barrier at the end.
[[nodiscard]] inline analysis::design::MeasuredRun measured_run(
    const analysis::ApproachFlow& a, const RunForces& forces, const analysis::UpstreamFlow& deposit,
    const dem::Particles& grains, double grain_density, double fluid_density, const scenario::BarrierInfo& b,
    double width, double slope_deg, double g, double retained) {
    analysis::design::MeasuredRun run;
    run.approach = {a.at_source.depth, a.at_source.velocity, a.at_source.bulk_density, g};
    run.front_velocity = a.front_velocity;
    run.peak_discharge = a.max_discharge;
    run.solid_fraction = a.at_source.solid_fraction;
    run.width = width;
    run.peak_normal_force = forces.peak_normal;
    run.static_normal_force = forces.static_normal;
    run.deposit_depth = deposit.height;
    run.deposit_density =
        deposit.solid_fraction * grain_density + (1.0 - deposit.solid_fraction) * fluid_density;
    run.slope_deg = slope_deg;
    run.barrier_height = b.height;
    for (const scenario::Span& o : b.outlets) run.openings.push_back({o.width(), b.height, true});
    run.d95 = analysis::mass_percentile_diameter(grains, 0.95);
    run.d_max = analysis::mass_percentile_diameter(grains, 1.0);
    run.grain_density = grain_density;
    run.retained_fraction = retained;
    return run;
}

// The comparison of the run with the design formulas: "design_inputs", the back-calculated coefficients
// and the typology into summary.json, and design_comparison.csv.
inline void add_design_comparison(io::JsonObject& js, const std::filesystem::path& out_dir,
                                  const analysis::design::MeasuredRun& run) {
    const analysis::design::Comparison c = analysis::design::compare(run);
    for (const auto& k : c.coefficients) js.number(k.name, k.value);
    js.text("barrier_typology", c.typology);
    js.object("design_inputs", io::design_inputs_json(run));
    io::write_design_comparison(out_dir, c);
}

}  // namespace sabo::cases
