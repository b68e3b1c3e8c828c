// SPDX-License-Identifier: MIT
#include "cases/common/coupling_keys.h"

#include <fmt/format.h>

#include <cmath>

namespace sabo::cases {

coupling::CouplingSettings read_coupling_settings(const Config& cfg, lbm::FluidSettings& fluid,
                                                  dem::DemSettings& dem, const Vec3& gravity,
                                                  double grain_density) {
    coupling::CouplingSettings c;
    // DEM sub-steps: Δt_DEM = Δt_LBM / n_sub no longer than the contact's step t_c / n
    const double dt = fluid.units.dt();
    const double needed = std::ceil(dt / dem.dt - 1e-9);  // compared before it is made an integer
    if (!(needed <= max_substeps))
        cfg.fail(
            "lattice.dt_s",
            fmt::format("one lattice step ({} s) would take {:.4g} DEM steps of at most {:.4g} s (t_c / {}): "
                        "more than {}; reduce lattice.dt_s",
                        dt, needed, dem.dt, dem.steps_per_contact, max_substeps));
    const auto fewest = static_cast<std::int64_t>(needed);
    const std::int64_t n_sub = cfg.integer_or("coupling.substeps", fewest, fewest, max_substeps);
    c.substeps = static_cast<int>(n_sub);
    c.model = cfg.enum_or("coupling.model", coupling::CoverRule::cell_centre, coupling::cover_rule_names);
    c.buoyancy = cfg.boolean_or("coupling.buoyancy", true);
    if (c.buoyancy)
        c.volume = cfg.enum_or("coupling.buoyancy_volume", coupling::BuoyancyVolume::sphere,
                               coupling::buoyancy_volume_names);
    else
        cfg.accept_unused({"coupling.buoyancy_volume"});
    c.gravity = gravity;
    if (grain_density <= fluid.units.density())
        fluid.numbers.warnings.push_back(fmt::format(
            "the grains ({} kg/m3) are no denser than the fluid ({} kg/m3): {}", grain_density,
            fluid.units.density(),
            c.buoyancy ? "they float" : "without buoyancy (coupling.buoyancy = false) they sink"));
    dem.dt = dt / static_cast<double>(n_sub);
    dem.steps_per_contact = dem.contact_time / dem.dt;
    cfg.record("derived.substeps", n_sub);
    cfg.record("derived.dem_dt_s", dem.dt);
    return c;
}

const char* describe_model(const coupling::CouplingSettings& c) {
    return c.model == coupling::CoverRule::psm ? "partially saturated cells (a solid fraction per cell)"
                                               : "the cells whose centre a grain holds";
}

const char* describe_buoyancy(const coupling::CouplingSettings& c) {
    if (!c.buoyancy) return "off";
    return c.volume == coupling::BuoyancyVolume::sphere ? "on (the sphere's volume)"
                                                        : "on (the covered cells' volume)";
}

void accept_unused_coupling_keys(const Config& cfg) {
    cfg.accept_unused(
        {"coupling.substeps", "coupling.model", "coupling.buoyancy", "coupling.buoyancy_volume"});
}

}  // namespace sabo::cases
