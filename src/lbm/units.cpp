// SPDX-License-Identifier: MIT
#include "lbm/units.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sabo::lbm {

namespace {
// the storage's padding, where there is some
std::string stored_note(const LatticeRequest& req) {
    return req.stored_nodes > req.nodes
               ? fmt::format(" ({} stored: rows padded to cache lines)", req.stored_nodes)
               : std::string();
}
// A case's velocity scale is its estimate of an upper bound (the debris case's: a frictionless fall to the
// channel's end); a viscous flow may never come near it, and a user who knows so can say it
std::string velocity_key_hint(const LatticeRequest& req) {
    return req.velocity_key.empty() ? std::string()
                                    : fmt::format(
                                          ", or set {} to the fastest the flow runs if that is below "
                                          "the case's estimate",
                                          req.velocity_key);
}
}  // namespace

UnitConverter::UnitConverter(double dx_m, double dt_s, double density_kg_m3)
    : dx_(dx_m), dt_(dt_s), rho_(density_kg_m3) {
    const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    if (!positive(dx_) || !positive(dt_) || !positive(rho_))
        throw InputError(
            fmt::format("lattice units need Δx, Δt and ρ_f > 0 (got Δx = {} m, Δt = {} s, "
                        "ρ_f = {} kg/m3)",
                        dx_m, dt_s, density_kg_m3));
}

LatticeNumbers check_lattice(const LatticeRequest& req) {
    const UnitConverter units(req.dx_m, req.dt_s, req.density_kg_m3);
    const std::string at = req.where.empty() ? std::string("fluid set-up") : req.where;
    LatticeNumbers n;
    n.nu_lb = units.kinematic_viscosity(req.viscosity_Pa_s / req.density_kg_m3);
    n.tau = 0.5 + 3.0 * n.nu_lb;
    n.u_lb = units.velocity(req.velocity_scale_m_s);
    n.mach = n.u_lb * std::sqrt(3.0);
    n.yield_lb = units.stress(req.yield_stress_Pa);
    n.memory_bytes = std::max(req.nodes, req.stored_nodes) * req.bytes_per_node;
    if (!(req.tau_min > 0.5 && req.tau_min <= req.tau_max))
        throw InputError(
            fmt::format("{}: tau_min = {} and tau_max = {} must satisfy 0.5 < tau_min <= tau_max", at,
                        req.tau_min, req.tau_max));
    if (!(n.tau > 0.5) || n.tau > req.tau_max)
        throw InputError(fmt::format(
            "{}: the relaxation time tau = 0.5 + 3 nu dt/dx^2 = {:.4f} (nu = {:.4g} m2/s, dt = {:.4g} s, "
            "dx = {:.4g} m) must lie in (0.5, tau_max = {}]: change dt or dx",
            at, n.tau, req.viscosity_Pa_s / req.density_kg_m3, req.dt_s, req.dx_m, req.tau_max));
    if (n.tau < req.tau_min)
        n.warnings.push_back(
            fmt::format("tau = {:.4f} is below tau_min = {}: cells are clamped to tau_min, the "
                        "fluid is more viscous than asked ({:.4g} Pa s instead of {:.4g})",
                        n.tau, req.tau_min,
                        req.density_kg_m3 * (req.tau_min - 0.5) / 3.0 * req.dx_m * req.dx_m / req.dt_s,
                        req.viscosity_Pa_s));
    if (n.mach >= 1.0)
        throw InputError(
            fmt::format("{}: lattice Mach number u_LB sqrt(3) = {:.3f} for the velocity scale "
                        "{:.3g} m/s must be below 1 (aim < 0.3): reduce dt{}",
                        at, n.mach, req.velocity_scale_m_s, velocity_key_hint(req)));
    if (n.mach >= 0.3)
        n.warnings.push_back(
            fmt::format("lattice Mach number {:.3f} >= 0.3 for the velocity scale {:.3g} m/s: "
                        "compressibility errors grow; reduce dt{}",
                        n.mach, req.velocity_scale_m_s, velocity_key_hint(req)));
    n.hydrostatic_variation =
        3.0 * req.gravity_m_s2 * req.depth_m * req.dt_s * req.dt_s / (req.dx_m * req.dx_m);
    if (n.hydrostatic_variation > max_hydrostatic_variation)
        throw InputError(fmt::format(
            "{}: under gravity the fluid's density would vary by {:.0f} % over its {:.3g} m depth "
            "(3 g H dt^2/dx^2 = {:.3g}; at most {}): the lattice fluid is only weakly compressible and its "
            "pressure would come from compression, not from depth; reduce dt to below {:.3g} s",
            at, 100.0 * n.hydrostatic_variation, req.depth_m, n.hydrostatic_variation,
            max_hydrostatic_variation,
            req.dt_s * std::sqrt(max_hydrostatic_variation / n.hydrostatic_variation)));
    if (n.hydrostatic_variation > warn_hydrostatic_variation)
        n.warnings.push_back(
            fmt::format("under gravity the fluid's density varies by {:.1f} % over its depth (3 g "
                        "H dt^2/dx^2): "
                        "pressures are that much compressible; reduce dt to below {:.3g} s for under 1 %",
                        100.0 * n.hydrostatic_variation,
                        req.dt_s * std::sqrt(warn_hydrostatic_variation / n.hydrostatic_variation)));
    if (req.grain_d_mean_m > 0.0 && req.dx_m > 0.25 * req.grain_d_mean_m)
        throw InputError(
            fmt::format("{}: dx = {:.4g} m must be at most d_mean/4 = {:.4g} m (grains must span "
                        "at least 4 cells)",
                        at, req.dx_m, 0.25 * req.grain_d_mean_m));
    if (req.grain_d_min_m > 0.0 && req.dx_m > 0.1 * req.grain_d_min_m)
        n.warnings.push_back(fmt::format("dx = {:.4g} m is coarser than the recommended d_min/10 = {:.4g} m",
                                         req.dx_m, 0.1 * req.grain_d_min_m));
    if (req.memory_limit_bytes > 0 && n.memory_bytes > req.memory_limit_bytes)
        throw InputError(fmt::format(
            "{}: {} lattice nodes{} x {} bytes = {:.1f} MiB exceed the memory available "
            "({:.1f} MiB): coarsen dx or shrink the domain, or divide the run among machines (mpirun "
            "across N machines, one rank each: docs/distributed.md)",
            at, req.nodes, stored_note(req), req.bytes_per_node, n.memory_bytes / 1048576.0,
            req.memory_limit_bytes / 1048576.0));
    return n;
}

std::vector<std::string> describe(const LatticeRequest& req, const LatticeNumbers& n) {
    std::vector<std::string> lines;
    lines.push_back(fmt::format(
        "lattice: dx = {:.4g} m, dt = {:.4g} s, {} nodes{}, {} bytes per node, {:.1f} MiB", req.dx_m,
        req.dt_s, req.nodes, stored_note(req), req.bytes_per_node, n.memory_bytes / 1048576.0));
    lines.push_back(
        fmt::format("fluid: nu_LB = {:.5f}, tau = {:.4f} (clamp [{}, {}]), u_LB = {:.4f}, Mach = {:.3f}; "
                    "hydrostatic density variation over the depth {:.2g}",
                    n.nu_lb, n.tau, req.tau_min, req.tau_max, n.u_lb, n.mach, n.hydrostatic_variation));
    if (req.yield_stress_Pa > 0.0)
        lines.push_back(fmt::format("Bingham: yield stress {} Pa = {:.4g} in lattice units (stress/rho_f)",
                                    req.yield_stress_Pa, n.yield_lb));
    return lines;
}

}  // namespace sabo::lbm
