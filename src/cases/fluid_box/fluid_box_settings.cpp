// SPDX-License-Identifier: MIT
#include "cases/fluid_box/fluid_box_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "cases/common/coupling_keys.h"
#include "core/memory.h"

namespace sabo::cases {

PreparedFluidBox prepare_fluid_box(const sim::RunRequest& req, const Config& cfg) {
    PreparedFluidBox pc;
    pc.fluid = lbm::read_fluid_settings(cfg);
    pc.scene = scenario::read_fluid_box_case(cfg, pc.fluid.units.density(), pc.fluid.viscosity);
    const auto& s = pc.scene;
    sim::check_memory(cfg, s.particles.n_mobile);
    const double dx = pc.fluid.units.dx();
    // the lattice's walls are the grains' walls: the box is a whole number of cells each way
    const auto cells = [&](const char* key, double length) {
        const double n = length / dx;
        if (std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n) || std::round(n) < 4.0)
            cfg.fail(key, fmt::format("{} m is not a whole number (at least 4) of lattice cells of {} m",
                                      length, dx));
        return static_cast<int>(std::lround(n));
    };
    pc.shape = {cells("box.length_m", s.size.x), cells("box.width_m", s.size.y),
                cells("box.height_m", s.size.z), s.periodic};
    // a held grain's cells do not wrap: it keeps a cell (and a partial one) off a periodic face
    for (std::size_t i = 0; i < s.particles.n_mobile; ++i)
        for (int a = 0; a < 3; ++a) {
            const double x = s.particles.x[i][a], r = s.particles.r[i], length = s.size[a];
            if (s.periodic[static_cast<std::size_t>(a)] && (x - r < 2.0 * dx || x + r > length - 2.0 * dx))
                cfg.fail(
                    "grains.file",
                    fmt::format("{}: grain {} reaches within two cells ({} m) of a periodic face along {}: "
                                "its cells would wrap, which held grains do not",
                                s.grains_file.string(), i + 1, 2.0 * dx, "XYZ"[a]));
        }
    lbm::check_fluid_settings(cfg, pc.fluid,
                              {s.velocity_scale, s.gravity, s.size.z, pc.shape, 2.0 * s.r_mean, 2.0 * s.r_min,
                               "box.velocity_scale_m_s"},
                              memory_of_all_machines_bytes());
    pc.dem = dem::read_dem_settings(cfg, {s.r_min, s.r_max, s.density, s.velocity_scale});
    if (s.held) pc.dem.reorder_interval = 0;  // held grains are put back by index
    pc.coupling = read_coupling_settings(cfg, pc.fluid, pc.dem, {0.0, 0.0, -s.gravity}, s.density);
    pc.output = sim::read_output_settings(cfg, req, s.name, s.end_time / 20.0, s.end_time / 200.0);
    pc.average_from = 0.8 * s.end_time;
    cfg.finish();
    return pc;
}

void print_derived(const PreparedFluidBox& pc) {
    const auto& s = pc.scene;
    spdlog::info(
        "case '{}': a closed box {:.4g} x {:.4g} x {:.4g} m full of fluid, gravity {} m/s2 along -Z; {} "
        "grains "
        "from {} (r in [{:.4g}, {:.4g}] m, rho = {} kg/m3)",
        s.name, s.size.x, s.size.y, s.size.z, s.gravity, s.particles.n_mobile, s.grains_file.string(),
        s.r_min, s.r_max, s.density);
    spdlog::info("{}; t_c = {:.4e} s", dem::describe_contact(pc.dem), pc.dem.contact_time);
    spdlog::info(
        "coupling: {}; {} DEM sub-steps of {:.4e} s per lattice step (t_c / {:.1f}); d / dx from {:.1f} "
        "to {:.1f}; buoyancy {}",
        describe_model(pc.coupling), pc.coupling.substeps, pc.dem.dt, pc.dem.steps_per_contact,
        2.0 * s.r_min / pc.fluid.units.dx(), 2.0 * s.r_max / pc.fluid.units.dx(),
        describe_buoyancy(pc.coupling));
    for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
    for (const auto& w : lbm::warnings(pc.fluid)) spdlog::warn("{}", w);
    spdlog::info("velocity scale {:.4g} m/s; {} steps to t = {} s; velocities averaged from t = {:.4g} s",
                 s.velocity_scale, static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time,
                 pc.average_from);
}

}  // namespace sabo::cases
