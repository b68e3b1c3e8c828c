// SPDX-License-Identifier: MIT
#include "cases/sandpile/sandpile_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "dem/grain_budget.h"
#include "sim/run_summary.h"

namespace sabo::cases {

PreparedSandpile prepare_sandpile(const sim::RunRequest& req, const Config& cfg) {
    PreparedSandpile pc;
    pc.scene = scenario::build_sandpile_case(cfg, req.place_grains);
    const auto& s = pc.scene;
    const double r = 0.5 * s.diameter;
    pc.dem = dem::read_dem_settings(cfg, {r, r, s.density, s.velocity_scale});
    const double end = s.end_time;
    pc.output = sim::read_output_settings(cfg, req, s.name, end / 50.0, end / 1000.0);
    if (pc.output.series_interval < pc.dem.dt)
        cfg.fail("output.series_interval_s",
                 fmt::format("must be at least the time step {:.4g} s", pc.dem.dt));
    pc.remove_drained = cfg.boolean_or("sandpile.remove_drained", true);
    // Complete stop: mean grain speed below ε sqrt(g d) (as kinetic energy) for a hold of h sqrt(d/g);
    // both scale with the grain size, so one setting serves d = 2 mm and d = 10 cm.
    const double g = std::abs(s.gravity.z);
    const double eps = cfg.real_or("stop.speed_over_sqrt_gd", 0.01, Range::positive());
    const double grain_mass = s.density * dem::sphere_volume(r);
    pc.stop_energy_per_grain = 0.5 * grain_mass * eps * eps * g * s.diameter;
    pc.stop_hold =
        cfg.real_or("stop.hold_over_sqrt_d_g", 20.0, Range::positive()) * std::sqrt(s.diameter / g);
    cfg.record("derived.particles", static_cast<std::int64_t>(s.count));
    cfg.record("derived.fill_height_over_d", s.fill_height / s.diameter);
    cfg.record("derived.fill_solid_fraction", s.fill_fraction);
    cfg.record("derived.stop_kinetic_energy_per_grain_J", pc.stop_energy_per_grain);
    cfg.record("derived.stop_hold_s", pc.stop_hold);
    cfg.finish();
    sim::check_memory(cfg, s.count);
    return pc;
}

void print_derived(const PreparedSandpile& pc) {
    const auto& s = pc.scene;
    const auto& d = pc.dem;
    spdlog::info(
        "case '{}': sandpile box {:.4f} x {:.4f} x {:.4f} m, plate X [{:.4f}, {:.4f}] m at Z = {:.4f} m, "
        "outlets {:.4f} m",
        s.name, s.length, s.width, s.height, s.plate_x_lo, s.plate_x_hi, s.plate_z, s.plate_x_lo);
    spdlog::info(
        "grains: {} spheres, d = {} m, rho = {} kg/m3, generated at random in {:.1f} d above the plate "
        "(solid fraction {:.3f})",
        s.count, s.diameter, s.density, s.fill_height / s.diameter, s.fill_fraction);
    spdlog::info("{}", dem::describe_contact(d));
    spdlog::info(
        "time step: t_c = {:.4e} s, dt = {:.4e} s, dt/t_c = 1/{:.1f}; at most {:.0f} steps to t = {:.3g} s",
        d.contact_time, d.dt, d.steps_per_contact, std::ceil(s.end_time / d.dt), s.end_time);
    sim::log_expected_overlap(s.velocity_scale, d.expected_max_overlap_ratio, "d");
    spdlog::info("memory estimate: {:.1f} MiB; neighbour skin {:.4g} m",
                 dem::memory_estimate_bytes(static_cast<double>(s.count)) / 1048576.0, d.skin);
    spdlog::info(
        "settling at most {:.3g} s, then the outlets open; complete stop: mean kinetic energy of the "
        "grains above the plate below {:.3g} J for {:.3g} s",
        s.settle_max_time, pc.stop_energy_per_grain, pc.stop_hold);
}

}  // namespace sabo::cases
