// SPDX-License-Identifier: MIT
// `sabo design` and `sabo design compare RUNDIR` (docs/design.md).
#include <spdlog/spdlog.h>

#include <cmath>
#include <iostream>

#include "analysis/design/run_comparison.h"
#include "app/commands.h"
#include "core/error.h"
#include "io/design_output.h"
#include "io/report_script.h"

namespace sabo::app {

namespace {

using analysis::design::MeasuredRun;

// The formulas' inputs from the command line: the flow (required), the barrier and grains (optional:
// their rows are left out without them).
MeasuredRun given_flow(const DesignRequest& r) {
    for (const auto& [name, value] : {std::pair{"--depth", r.depth}, std::pair{"--velocity", r.velocity},
                                      std::pair{"--density", r.density}, std::pair{"--width", r.width}}) {
        if (!(value > 0.0))
            throw InputError(fmt::format(
                "sabo design: {} is required (> 0): the flow depth (m), velocity (m/s), bulk density (kg/m3) "
                "and the barrier width (m); or `sabo design compare RUNDIR`",
                name));
    }
    MeasuredRun run;
    run.approach = {r.depth, r.velocity, r.density, 9.81};
    run.front_velocity = r.velocity;
    run.width = r.width;
    run.peak_normal_force = run.static_normal_force = std::nan("");
    run.deposit_depth = run.deposit_density = std::nan("");
    run.retained_fraction = std::nan("");
    run.peak_discharge = r.peak_discharge > 0.0 ? r.peak_discharge : r.depth * r.velocity * r.width;
    run.solid_fraction = r.solid_fraction;
    run.slope_deg = r.slope_deg;
    run.barrier_height = r.barrier_height;
    for (double s : r.openings) run.openings.push_back({s, r.barrier_height, true});
    run.d_max = r.d_max;
    run.d95 = r.d95 > 0.0 ? r.d95 : r.d_max;
    run.grain_density = r.grain_density;
    return run;
}

}  // namespace

int run_design(const DesignRequest& r) {
    const analysis::design::Materials materials{{r.boulder_modulus, r.boulder_poisson},
                                                {r.barrier_modulus, r.barrier_poisson}};
    if (!r.run_dir) {
        const MeasuredRun run = given_flow(r);
        std::cout << fmt::format(
                         "flow: h = {} m, v = {} m/s, rho = {} kg/m3, Fr = {:.3g}; barrier width {} m\n",
                         r.depth, r.velocity, r.density, run.approach.froude(), r.width)
                  << io::design_table(analysis::design::compare(run, materials), false);
        return 0;
    }
    const MeasuredRun run = io::read_design_inputs(*r.run_dir / "summary.json");
    const analysis::design::Comparison c = analysis::design::compare(run, materials);
    std::cout << fmt::format(
                     "run {}: approaching flow h = {:.3g} m, v = {:.3g} m/s (front {:.3g} m/s), "
                     "rho = {:.4g} kg/m3, Fr = {:.3g}; simulated peak normal force {:.4g} kN, {}\n",
                     r.run_dir->string(), run.approach.depth, run.approach.velocity, run.front_velocity,
                     run.approach.density, run.approach.froude(), run.peak_normal_force / 1000.0,
                     std::isnan(run.static_normal_force)
                         ? std::string("no static load (the run ended before the deposit came to rest)")
                         : fmt::format("static load {:.4g} kN (the deposit at rest)",
                                       run.static_normal_force / 1000.0))
              << io::design_table(c, true);
    io::write_design_comparison(*r.run_dir, c);
    spdlog::info("wrote {}", (*r.run_dir / "design_comparison.csv").string());
    if (io::run_python("design_report.py", {r.run_dir->string()}) != 0)
        spdlog::warn("the design chart was not drawn (python3 with matplotlib missing?)");
    return 0;
}

}  // namespace sabo::app
