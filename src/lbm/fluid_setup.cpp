// SPDX-License-Identifier: MIT
#include "lbm/fluid_setup.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"
#include "lbm/fluid_lattice.h"

namespace sabo::lbm {

FluidSettings read_fluid_settings(const Config& cfg) {
    FluidSettings fs;
    const double rho = cfg.real("fluid.density_kg_m3", Range::positive());
    fs.rheology_name = cfg.choice_or("fluid.rheology", "newtonian", {"newtonian", "bingham"});
    const bool bingham = fs.rheology_name == "bingham";
    // η, or the plastic viscosity η0 of a Bingham fluid; a Newtonian case may carry the yield stress it
    // would have as Bingham (switched with --set fluid.rheology=bingham)
    fs.viscosity = cfg.real("fluid.viscosity_Pa_s", Range::positive());
    if (bingham)
        fs.yield_stress = cfg.real("fluid.yield_stress_Pa", Range::positive());
    else
        cfg.accept_unused({"fluid.yield_stress_Pa"});
    // round-off keeps the free surface's mass to ~1e-13; a drift a million times larger is a leak
    fs.max_mass_drift = cfg.real_or("lattice.max_mass_drift", 1e-6, Range::open_closed(0.0, 1.0));
    const double dx = cfg.real("lattice.dx_m", Range::positive());
    const double dt = cfg.real("lattice.dt_s", Range::positive());
    fs.single_precision = cfg.choice_or("lattice.storage", "float64", {"float64", "float32"}) == "float32";
    fs.on_opencl = cfg.choice_or("lattice.device", "cpu", {"cpu", "opencl"}) == "opencl";
    fs.pocket_reach = static_cast<int>(cfg.integer_or("lattice.pocket_reach_cells", fs.pocket_reach, 0,
                                                      FluidLattice<double>::max_pocket_reach));
    const std::string device = cfg.text_or("lattice.opencl_device", "");
    if (fs.on_opencl)
        fs.opencl_device = opencl::choose_device(device, cfg.source() + ": lattice.opencl_device");
    fs.units = UnitConverter(dx, dt, rho);
    Rheology& rh = fs.rheology;
    rh.tau_min = cfg.real_or("lattice.tau_min", 0.501, Range::open_closed(0.5, 100.0));
    rh.tau_max = cfg.real_or("lattice.tau_max", 1.8, Range::open_closed(0.5, 1000.0));
    if (rh.tau_max < rh.tau_min)
        cfg.fail("lattice.tau_max", fmt::format("must be at least lattice.tau_min = {}", rh.tau_min));
    rh.bingham = bingham;
    rh.smagorinsky = cfg.real_or("lattice.smagorinsky_constant", 0.0, Range::closed(0.0, 0.5));
    rh.nu_plastic = fs.units.kinematic_viscosity(fs.viscosity / rho);
    rh.yield = fs.units.stress(fs.yield_stress);
    // Newtonian τ, clamped like the Bingham cells (a warning says so)
    rh.tau = std::clamp(0.5 + 3.0 * rh.nu_plastic, rh.tau_min, rh.tau_max);
    return fs;
}

void check_fluid_settings(const Config& cfg, FluidSettings& fs, const FluidScale& scale,
                          double memory_available_bytes) {
    LatticeRequest& r = fs.request;
    r.dx_m = fs.units.dx();
    r.dt_s = fs.units.dt();
    r.density_kg_m3 = fs.units.density();
    r.viscosity_Pa_s = fs.viscosity;
    r.yield_stress_Pa = fs.yield_stress;
    r.velocity_scale_m_s = scale.velocity_m_s;
    r.velocity_key = scale.velocity_key;
    r.gravity_m_s2 = scale.gravity_m_s2;
    r.depth_m = scale.depth_m > 0.0 ? scale.depth_m : scale.shape.nz * r.dx_m;
    r.tau_min = fs.rheology.tau_min;
    r.tau_max = fs.rheology.tau_max;
    r.nodes = scale.shape.cells();
    r.stored_nodes = fs.single_precision ? FluidLattice<float>::stored_cells(scale.shape)
                                         : FluidLattice<double>::stored_cells(scale.shape);
    // the lattice, and the snapshot of its fields that observers and frames read (lbm/fluid_fields.h)
    r.bytes_per_node = (fs.single_precision ? FluidLattice<float>::bytes_per_cell()
                                            : FluidLattice<double>::bytes_per_cell()) +
                       FluidFields::bytes_per_cell;
    r.memory_limit_bytes = static_cast<std::size_t>(0.8 * memory_available_bytes);
    r.grain_d_mean_m = scale.grain_d_mean_m;
    r.grain_d_min_m = scale.grain_d_min_m;
    r.where = cfg.source() + " ([lattice] dx_m, dt_s; [fluid])";
    fs.numbers = check_lattice(r);
    cfg.record("derived.lattice_nodes", static_cast<std::int64_t>(r.nodes));
    cfg.record("derived.tau", fs.numbers.tau);
    cfg.record("derived.nu_lattice", fs.numbers.nu_lb);
    cfg.record("derived.u_lattice", fs.numbers.u_lb);
    cfg.record("derived.mach", fs.numbers.mach);
    cfg.record("derived.hydrostatic_density_variation", fs.numbers.hydrostatic_variation);
    cfg.record("derived.lattice_memory_MiB", static_cast<double>(fs.numbers.memory_bytes) / 1048576.0);
    if (fs.on_opencl) {
        const opencl::DeviceInfo& d = fs.opencl_device;
        if (!fs.single_precision && !d.fp64)
            cfg.fail("lattice.storage",
                     fmt::format("\"float64\" needs cl_khr_fp64, which the OpenCL device {} lacks: "
                                 "store \"float32\" or choose another lattice.opencl_device",
                                 d.name));
        const std::uint64_t populations =
            static_cast<std::uint64_t>(Q) * r.stored_nodes * (fs.single_precision ? 4 : 8);
        fs.opencl_bytes =
            opencl::lattice_bytes(r.stored_nodes, fs.single_precision, true, scale.grain_d_mean_m > 0.0);
        if (const std::string why = opencl::misfit(fs.opencl_bytes, populations, d); !why.empty())
            cfg.fail(
                "lattice.dx_m",
                why + ": coarsen dx_m, store float32 (lattice.storage) or run on the CPU (lattice.device)");
        cfg.record("derived.opencl_device", d.name);
        cfg.record("derived.opencl_memory_MiB", static_cast<double>(fs.opencl_bytes) / 1048576.0);
    }
}

std::vector<std::string> describe(const FluidSettings& fs) {
    auto lines = describe(fs.request, fs.numbers);
    lines.push_back(fmt::format(
        "storage {} ({} bytes per cell, the snapshot of its fields included); rheology {}",
        fs.single_precision ? "float32" : "float64", fs.request.bytes_per_node, fs.rheology_name));
    if (fs.rheology.smagorinsky > 0.0)
        lines.push_back(
            fmt::format("Smagorinsky eddy viscosity on, C = {} (an option beyond plain BGK: docs/lbm.md)",
                        fs.rheology.smagorinsky));
    lines.push_back(
        fs.pocket_reach > 0
            ? fmt::format("a closed gas pocket's volume taken from the surface within {} cells of "
                          "it (lattice.pocket_reach_cells)",
                          fs.pocket_reach)
            : std::string("a closed gas pocket's volume taken from the whole surface "
                          "(lattice.pocket_reach_cells = 0)"));
    if (fs.on_opencl)
        lines.push_back(fmt::format("lattice on the OpenCL device {} ({}): {:.1f} MiB of its {:.1f} GiB",
                                    fs.opencl_device.name, fs.opencl_device.platform,
                                    static_cast<double>(fs.opencl_bytes) / 1048576.0,
                                    static_cast<double>(fs.opencl_device.global_memory) / 1073741824.0));
    return lines;
}

const std::vector<std::string>& warnings(const FluidSettings& fs) {
    return fs.numbers.warnings;
}

void check_fluid_stable(double time, double mass_drift, double lattice_speed, double max_mass_drift) {
    if (!std::isfinite(mass_drift) || !(lattice_speed <= 0.5))
        throw RunError(
            fmt::format("t = {:.4g} s: the fluid became unstable (lattice speed {:.3g}): reduce dt", time,
                        lattice_speed));
    if (std::abs(mass_drift) > max_mass_drift)
        throw RunError(
            fmt::format("t = {:.4g} s: the fluid's mass drifted by {:.3g} (relative; limit {:.3g}, "
                        "lattice.max_mass_drift): the free surface lost or made mass",
                        time, mass_drift, max_mass_drift));
}

}  // namespace sabo::lbm
