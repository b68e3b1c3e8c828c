// SPDX-License-Identifier: MIT
#include "cases/debris/debris_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "cases/common/coupling_keys.h"
#include "core/error.h"
#include "core/memory.h"
#include "scenario/mesh_barrier.h"
#include "sim/run_summary.h"

namespace sabo::cases {

namespace {

// The grains' derived keys, refused beyond the memory (`sabo check`: the count without placing them).
void record_grains(const Config& cfg, const scenario::DebrisCase& s) {
    const auto& g = s.grains;
    sim::check_memory(cfg, s.particles.n_fixed() + g.count);
    cfg.record("derived.grains", static_cast<std::int64_t>(g.count));
    cfg.record("derived.solid_volume_m3", g.solid_volume);
    if (g.count > 0) cfg.record("derived.solid_fraction", g.solid_volume / scenario::block_volume(s));
}

}  // namespace

PreparedDebris prepare_debris(const sim::RunRequest& req, const Config& cfg) {
    PreparedDebris pc;
    // every key is read and checked with the grains counted first; a run places them once all passed (a
    // bad key is not said after minutes of placement)
    pc.scene = scenario::build_debris_case(cfg, false);
    const auto& s = pc.scene;
    pc.fluid = lbm::read_fluid_settings(cfg);
    const double dx = pc.fluid.units.dx();
    if (s.inflow && 2.0 * dx > s.channel.height)
        cfg.fail("lattice.dx_m", "the inflow needs at least two cells under the walls' height");
    if (pc.fluid_on()) pc.mesh_cells = scenario::mesh_cells_on_lattice(cfg, s.barrier, dx);
    const auto cells = [&](double length) { return static_cast<int>(std::lround(length / dx)); };
    pc.shape = {cells(s.channel.length),
                cells(s.channel.width),
                cells(s.bounds.domain_height),
                {false, false, false}};
    if (s.barrier.present() && s.barrier.outlet_width > 0.0 && s.barrier.outlet_width < 2.0 * dx)
        cfg.fail("lattice.dx_m", fmt::format("the barrier's outlets ({} m) must span at least 2 cells",
                                             s.barrier.outlet_width));
    const auto& g = s.grains;
    lbm::check_fluid_settings(
        cfg, pc.fluid,
        {s.velocity_scale, s.channel.gravity, std::max(s.block_hi.z, s.barrier.height), pc.shape,
         pc.grains() ? 2.0 * g.r_mean : 0.0, pc.grains() ? 2.0 * g.r_min : 0.0, "debris.velocity_scale_m_s"},
        memory_of_all_machines_bytes());
    // the contact model is read (and checked) with the fluid alone too: it is the case's
    pc.dem = dem::read_dem_settings(cfg, {g.r_min, g.r_max, g.density, s.velocity_scale});
    if (pc.grains()) record_grains(cfg, s);
    if (pc.grains() && pc.fluid_on())
        pc.coupling = read_coupling_settings(cfg, pc.fluid, *pc.dem, s.gravity, g.density);
    else
        accept_unused_coupling_keys(cfg);
    pc.output = sim::read_output_settings(cfg, req, s.name, s.end_time / 30.0, s.end_time / 1000.0);
    pc.gauge = read_gauge_settings(cfg, s.barrier.face_x, s.channel.width,
                                   pc.grains() ? 2.0 * s.grains.r_mean : 2.0 * pc.fluid.units.dx(),
                                   s.channel_mesh.get());
    if (pc.grains())
        pc.dry_twin_dir = cfg.text_or("output.dry_twin_dir", "");
    else
        cfg.accept_unused({"output.dry_twin_dir"});
    cfg.finish();
    if (pc.grains() && req.place_grains) {
        pc.scene = scenario::build_debris_case(cfg, true);
        record_grains(cfg, pc.scene);
    }
    cfg.record("derived.mode", pc.mode());  // the kind of run whose speed sim/run_rates keeps
    return pc;
}

namespace {

// Where the channel is open, and what leaves it there.
std::string describe_bounds(const scenario::DebrisCase& s) {
    const bool end = s.bounds.end == scenario::ChannelEnd::open;
    if (s.bounds.top == scenario::ChannelTop::open)
        return fmt::format(
            "open above them to {:.2f} m (fluid leaves at X >= {:.2f} m, the top and over the walls; grains "
            "over the walls{})",
            s.bounds.domain_height, s.outflow_x, end ? " and past the open end" : "");
    return end ? fmt::format(
                     "a lid on them, the end open (fluid leaves at X >= {:.2f} m, grains past the end)",
                     s.outflow_x)
               : std::string("a lid on them");
}

}  // namespace

void print_derived(const PreparedDebris& pc) {
    const auto& s = pc.scene;
    const std::string what =
        pc.mode() == "fluid" ? "fluid only" : (pc.mode() == "dry" ? "grains, dry" : "grains in fluid");
    spdlog::info(
        "case '{}': debris ({}) in a {:.2f} x {:.2f} m channel at {} deg, walls {:.2f} m high, {}; block X "
        "[{:.2f}, {:.2f}] x Z [{:.2f}, {:.2f}] m; barrier {} at X = {:.2f} m, {:.2f} m high ({} elements)",
        s.name, what, s.channel.length, s.channel.width, s.channel.slope_deg, s.channel.height,
        describe_bounds(s), s.block_lo.x, s.block_hi.x, s.block_lo.z, s.block_hi.z,
        s.barrier.mesh ? std::string("from a mesh")
                       : fmt::format("{} {} {}", scenario::name(s.barrier.type),
                                     scenario::name(s.barrier.orientation), scenario::name(s.barrier.model)),
        s.barrier.face_x, s.barrier.height, s.barrier.elements.size());
    if (s.channel_mesh) spdlog::info("{}", scenario::describe_channel_mesh(*s.channel_mesh));
    if (s.barrier.mesh) spdlog::info("{}", scenario::describe_mesh(s.barrier, pc.mesh_cells));
    if (const std::string w =
            scenario::open_top_mesh_warning(s.bounds, s.channel_mesh.get(), s.channel.height);
        !w.empty())
        spdlog::warn("{}", w);
    for (const std::string& w :
         scenario::fine_mesh_warnings(s.barrier.mesh.get(), s.channel_mesh.get(),
                                      s.grains.count > 0 || s.fed_grains ? s.grains.r_min : 0.0))
        spdlog::warn("{}", w);
    if (const auto& in = s.inflow) {
        const auto& h = in->hydrograph;
        spdlog::info(
            "inflow: {} rows over t [{:.3g}, {:.3g}] s, fluid volume {:.4g} m3, Q up to {:.4g} m3/s, "
            "through the first plane from the bed up to Q / (u W) at u = {:.3g} m/s (at most {:.3f} m)",
            h.rows(), h.start(), h.end(), h.fluid_volume(h.start(), h.end()), h.largest_discharge(),
            in->velocity, h.largest_discharge() / (in->velocity * s.channel.width));
        if (s.fed_grains)
            spdlog::info(
                "inflow grains: {:.4g} m3 (solid fraction up to {:.3g}), r {:.4f} m ± {:.0f} %, rho = {} "
                "kg/m3, placed in X [{:.3f}, {:.3f}] m at u{}",
                h.solid_volume(h.start(), h.end()), h.largest_solid_fraction(), s.grains.r_mean,
                100.0 * in->spread, in->density, in->x0, in->x0 + in->length, scenario::inflow_bed_note(*in));
    }
    if (pc.grains() && !s.fed_grains) {
        const auto& g = s.grains;
        spdlog::info(
            "grains: {} ({}), V_s = {:.4f} m3 = {:.4f} of the block (asked {:.3f}), r in [{:.4f}, {:.4f}] m, "
            "rho = {} kg/m3",
            g.count, s.placement, g.solid_volume, g.solid_volume / scenario::block_volume(s),
            s.solid_fraction, g.r_min, g.r_max, g.density);
        spdlog::info("grain placement: {}", g.lattice_rule);
    }
    if (pc.grains()) {
        const auto& g = s.grains;
        const auto& d = *pc.dem;
        spdlog::info("{}; t_c = {:.4e} s", dem::describe_contact(d), d.contact_time);
        sim::log_expected_overlap(s.velocity_scale, d.expected_max_overlap_ratio, "d_min");
        if (pc.fluid_on())
            spdlog::info(
                "coupling: {}; {} DEM sub-steps of {:.4e} s per lattice step (t_c / {:.1f}); d / dx = "
                "{:.1f}; "
                "buoyancy {}",
                describe_model(pc.coupling), pc.coupling.substeps, d.dt, d.steps_per_contact,
                2.0 * g.r_mean / pc.fluid.units.dx(), describe_buoyancy(pc.coupling));
        else
            spdlog::info("dry: DEM step {:.4e} s (t_c / {:.1f}), no fluid", d.dt, d.steps_per_contact);
    }
    if (pc.fluid_on()) {
        for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
        for (const auto& w : lbm::warnings(pc.fluid)) spdlog::warn("{}", w);
        spdlog::info("velocity scale {:.3f} m/s; {} steps to t = {} s", s.velocity_scale,
                     static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time);
    }
}

}  // namespace sabo::cases
