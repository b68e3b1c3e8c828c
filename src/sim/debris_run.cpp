// SPDX-License-Identifier: MIT
#include "sim/debris_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "analysis/barrier_forces.h"
#include "analysis/flow_measures.h"
#include "core/error.h"
#include "core/memory.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/json_writer.h"
#include "io/report_script.h"
#include "io/run_output.h"
#include "scenario/debris_lattice.h"
#include "sim/debris_observer.h"
#include "sim/design_inputs.h"
#include "sim/frame_observers.h"
#include "sim/gauge_observer.h"
#include "sim/run_checkpoint.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/run_summary.h"
#include "sim/simulation.h"

namespace sabo::sim {

namespace {

// The grains' derived keys, refused beyond the memory (`sabo check`: the count without placing them).
void record_grains(const Config& cfg, const scenario::DebrisCase& s) {
    const auto& g = s.grains;
    check_memory(cfg, s.particles.n_fixed() + g.count);
    cfg.record("derived.grains", static_cast<std::int64_t>(g.count));
    cfg.record("derived.solid_volume_m3", g.solid_volume);
    cfg.record("derived.solid_fraction", g.solid_volume / scenario::block_volume(s));
}

}  // namespace

PreparedDebris prepare_debris(const RunRequest& req, const Config& cfg) {
    PreparedDebris pc;
    // every key is read and checked with the grains counted first; a run places them once all passed (a
    // bad key is not said after minutes of placement)
    pc.scene = scenario::build_debris_case(cfg, false);
    const auto& s = pc.scene;
    pc.fluid = lbm::read_fluid_settings(cfg);
    const double dx = pc.fluid.units.dx();
    const auto cells = [&](double length) { return static_cast<int>(std::lround(length / dx)); };
    pc.shape = {
        cells(s.channel.length), cells(s.channel.width), cells(s.channel.height), {false, false, false}};
    if (s.barrier.present() && s.barrier.outlet_width > 0.0 && s.barrier.outlet_width < 2.0 * dx)
        cfg.fail("lattice.dx_m", fmt::format("the barrier's outlets ({} m) must span at least 2 cells",
                                             s.barrier.outlet_width));
    const auto& g = s.grains;
    lbm::check_fluid_settings(
        cfg, pc.fluid,
        {s.velocity_scale, pc.shape, pc.grains() ? 2.0 * g.r_mean : 0.0, pc.grains() ? 2.0 * g.r_min : 0.0},
        available_memory_bytes());
    // the contact model is read (and checked) with the fluid alone too: it is the case's
    pc.dem = dem::read_dem_settings(cfg, {g.r_min, g.r_max, g.density, s.velocity_scale});
    if (pc.grains()) record_grains(cfg, s);
    if (pc.grains() && pc.fluid_on()) {
        // DEM sub-steps: Δt_DEM = Δt_LBM / n_sub no longer than the contact's step t_c / n
        auto& d = *pc.dem;
        const double dt = pc.fluid.units.dt();
        const auto fewest = static_cast<std::int64_t>(std::ceil(dt / d.dt - 1e-9));
        if (fewest > max_substeps)
            cfg.fail(
                "lattice.dt_s",
                fmt::format("one lattice step ({} s) would take {} DEM steps of at most {:.4g} s (t_c / {}): "
                            "more than {}; reduce lattice.dt_s",
                            dt, fewest, d.dt, d.steps_per_contact, max_substeps));
        const std::int64_t n_sub = cfg.integer_or("coupling.substeps", fewest, fewest, max_substeps);
        pc.coupling.substeps = static_cast<int>(n_sub);
        pc.coupling.buoyancy = cfg.boolean_or("coupling.buoyancy", true);
        pc.coupling.gravity = s.gravity;
        if (g.density <= pc.fluid.units.density())
            pc.fluid.numbers.warnings.push_back(
                fmt::format("the grains ({} kg/m3) are no denser than the fluid ({} kg/m3): {}", g.density,
                            pc.fluid.units.density(),
                            pc.coupling.buoyancy ? "they float"
                                                 : "without buoyancy (coupling.buoyancy = false) they sink"));
        d.dt = dt / static_cast<double>(n_sub);
        d.steps_per_contact = d.contact_time / d.dt;
        cfg.record("derived.substeps", n_sub);
        cfg.record("derived.dem_dt_s", d.dt);
    } else {
        cfg.accept_unused({"coupling.substeps", "coupling.buoyancy"});
    }
    pc.output = read_output_settings(cfg, req, s.name, s.end_time / 30.0, s.end_time / 1000.0);
    pc.gauge = read_gauge_settings(cfg, s.barrier.face_x, s.channel.width,
                                   pc.grains() ? 2.0 * s.grains.r_mean : 2.0 * pc.fluid.units.dx());
    if (pc.grains())
        pc.dry_twin_dir = cfg.text_or("output.dry_twin_dir", "");
    else
        cfg.accept_unused({"output.dry_twin_dir"});
    cfg.finish();
    if (pc.grains() && req.place_grains) {
        pc.scene = scenario::build_debris_case(cfg, true);
        record_grains(cfg, pc.scene);
    }
    return pc;
}

void print_derived(const PreparedDebris& pc) {
    const auto& s = pc.scene;
    const std::string what =
        pc.mode() == "fluid" ? "fluid only" : (pc.mode() == "dry" ? "grains, dry" : "grains in fluid");
    spdlog::info(
        "case '{}': debris ({}) in a {:.2f} x {:.2f} x {:.2f} m channel at {} deg; block X [{:.2f}, "
        "{:.2f}] x Z [0, {:.2f}] m; barrier {} {} {} at X = {:.2f} m ({} elements)",
        s.name, what, s.channel.length, s.channel.width, s.channel.height, s.channel.slope_deg, s.block_lo.x,
        s.block_hi.x, s.block_hi.z, s.barrier.type, s.barrier.orientation, s.barrier.model, s.barrier.face_x,
        s.barrier.elements.size());
    if (pc.grains()) {
        const auto& g = s.grains;
        const auto& d = *pc.dem;
        spdlog::info(
            "grains: {} ({}), V_s = {:.4f} m3 = {:.4f} of the block (asked {:.3f}), r in [{:.4f}, {:.4f}] m, "
            "rho = {} kg/m3",
            g.count, s.placement, g.solid_volume, g.solid_volume / scenario::block_volume(s),
            s.solid_fraction, g.r_min, g.r_max, g.density);
        spdlog::info("grain placement: {}", g.lattice_rule);
        spdlog::info("{}; t_c = {:.4e} s", dem::describe_contact(d), d.contact_time);
        if (pc.fluid_on())
            spdlog::info(
                "coupling: {} DEM sub-steps of {:.4e} s per lattice step (t_c / {:.1f}); d / dx = {:.1f}; "
                "buoyancy {}",
                pc.coupling.substeps, d.dt, d.steps_per_contact, 2.0 * g.r_mean / pc.fluid.units.dx(),
                pc.coupling.buoyancy ? "on" : "off");
        else
            spdlog::info("dry: DEM step {:.4e} s (t_c / {:.1f}), no fluid", d.dt, d.steps_per_contact);
    }
    if (pc.fluid_on()) {
        for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
        spdlog::info("velocity scale {:.3f} m/s; {} steps to t = {} s", s.velocity_scale,
                     static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time);
    }
}

namespace {

// The rank's lattice (the whole one undivided) with the fluid block and the barrier's cells; their count per
// element over all ranks.
template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> debris_lattice(const PreparedDebris& pc, const Domain& domain,
                                                        std::vector<std::size_t>& barrier_cells) {
    const auto& s = pc.scene;
    const auto& u = pc.fluid.units;
    auto l = domain.make_lattice<Real>(pc.shape, pc.fluid.rheology);
    scenario::fill_fluid_block(*l, s, u.dx(), domain.slab.first_global_x);
    barrier_cells = scenario::mark_barrier(*l, s, u.dx(), domain.slab.first_global_x);
    for (std::size_t& n : barrier_cells) n = static_cast<std::size_t>(domain.sum(static_cast<double>(n)));
    l->prepare();
    l->set_acceleration({u.acceleration(s.gravity.x), 0.0, u.acceleration(s.gravity.z)});
    return l;
}

}  // namespace

Simulation debris_simulation(const PreparedDebris& pc, std::vector<std::size_t>& barrier_cells,
                             const MpiWorld* world) {
    const auto& s = pc.scene;
    const auto& u = pc.fluid.units;
    Domain domain{.origin = {}, .dx = u.dx(), .box = {s.channel.length, s.channel.width, s.channel.height}};
    if (!pc.fluid_on()) {  // the dry twin: grains alone, in slabs of their own
        if (world != nullptr) domain.divide_grains(*world);
        return Simulation(dem::make_solver(s.particles, s.walls, s.gravity, *pc.dem), domain);
    }
    if (world != nullptr) domain.divide(*world, pc.shape.nx);
    const auto build = [&]<class Real>() {
        auto lattice = debris_lattice<Real>(pc, domain, barrier_cells);
        if (!pc.grains()) return Simulation(std::move(lattice), u.dt(), domain);
        return Simulation(dem::make_solver(s.particles, s.walls, s.gravity, *pc.dem), std::move(lattice),
                          coupling::GrainFluidCoupling(pc.coupling, u, domain.origin), u.dt(), domain);
    };
    return pc.fluid.single_precision ? build.template operator()<float>()
                                     : build.template operator()<double>();
}

int run_debris(const RunRequest& req, const Config& cfg) {
    PreparedDebris pc = prepare_debris(req, cfg);
    const auto& out = pc.output;
    const auto& s = pc.scene;
    const auto& fs = pc.fluid;
    const auto& u = fs.units;
    const double dx = u.dx();
    std::vector<std::size_t> barrier_cells;
    Simulation sim = debris_simulation(pc, barrier_cells, req.world);
    const Domain& domain = sim.domain();
    open_run_folder(out.out_dir, req.case_file, cfg, req.resume, domain);
    print_derived(pc);
    std::size_t blocked = 0;
    for (const auto n : barrier_cells) blocked += n;
    const double m_start =
        sim.has_fluid() ? domain.sum(sim.with_fluid([](const auto& l) { return l.total_mass(); })) : 0.0;
    // the fluid: the block's cells less the grains' volume (the fluid in grain cells moves with them)
    const double solid_volume = s.grains.solid_volume;
    const double fluid_volume = sim.has_fluid() ? m_start * dx * dx * dx - solid_volume : 0.0;
    const double sin_theta = std::sin(s.channel.slope_deg * std::numbers::pi / 180.0);
    const double weight = u.density() * s.channel.gravity * fluid_volume +
                          s.grains.density * s.channel.gravity * solid_volume;  // W_tot, N
    // W_tot sin θ, N (NaN on a level channel: the normalised columns are then empty)
    const double weight_along =
        sin_theta > 0.0 ? weight * sin_theta : std::numeric_limits<double>::quiet_NaN();
    if (pc.grains())
        spdlog::info(
            "debris: {:.3f} m3 of fluid ({:.0f} kg) and {:.3f} m3 of grains ({:.0f} kg); W_tot sin(theta) = "
            "{:.4g} N",
            fluid_volume, u.density() * fluid_volume, solid_volume, s.grains.density * solid_volume,
            weight_along);
    if (sim.has_fluid())
        spdlog::info(
            "fluid block {:.3f} m3 ({:.0f} kg), W sin(theta) = {:.4g} N; barrier: {} elements on {} lattice "
            "cells",
            m_start * dx * dx * dx, u.density() * m_start * dx * dx * dx, weight_along, barrier_cells.size(),
            blocked);

    RunControl control(out.progress_interval, 0);
    control.set_ends_at_end_time();
    const std::size_t ne = s.barrier.elements.size();
    DebrisObserver debris(pc, weight_along, domain);
    debris.state().m0 = m_start;
    std::optional<FluidFrames> fluid_frames;
    std::optional<ParticleFrames> grain_frames;
    GaugeObserver gauge(pc.gauge, debris.forces(), out.out_dir,
                        sim.has_fluid() ? std::optional(u) : std::nullopt, domain);
    std::vector<Observer*> observers{&debris, &gauge};
    if (sim.has_fluid()) observers.push_back(&fluid_frames.emplace(out.out_dir, u));
    if (sim.has_grains()) observers.push_back(&grain_frames.emplace(out.out_dir));
    RunCheckpoint checkpoint(out.out_dir, cfg, domain);
    if (req.resume) checkpoint.load(sim, observers);
    Schedule at = make_schedule(sim.dt(), s.end_time, out.series_interval, out.frame_interval);
    at.progress_every = sim.has_fluid() ? 16 : 64;
    checkpoint.schedule(at, out, sim, observers, control, req.resume);
    const RunEnd end = run(sim, at, observers, control);
    const int exit_code = end.exit_code;
    const double t_end = end.time;
    auto& forces = debris.forces();
    forces.finish(t_end);
    const double wall = checkpoint.wall_before() + control.elapsed_s();
    const double own_work = checkpoint.work_before() + end.work;
    const double work = domain.sum(own_work);
    const DivisionSummary division = summarise_division(sim, own_work, control.elapsed_s());
    std::optional<GrainView> grains;  // every grain of the run (a collective call when divided)
    if (sim.has_grains()) grains.emplace(sim.grain_view());
    if (!domain.writes_outputs()) return exit_code;  // the first rank writes the run's files
    io::write_force_maps(out.out_dir, s.barrier, forces);
    if (sim.has_fluid()) {
        // per element: where it is and the largest fluid force it received
        std::string csv = "element,pile,x_m,y_m,z_m,height_m,lattice_cells,max_fluid_force_N\n";
        for (std::size_t e = 0; e < ne; ++e) {
            const auto& el = s.barrier.elements[e];
            csv += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.6g}\n", e, el.pile, el.centre.x,
                               el.centre.y, el.centre.z, el.height, barrier_cells[e],
                               forces.fluid_envelope()[e]);
        }
        io::write_text_atomically(out.out_dir / "barrier_fluid_elements.csv", csv);
    }
    const double peak_normal = forces.max_fluid_normal();
    io::JsonObject js =
        summary_header(s.name, "debris", end, sim, sim.has_fluid() ? "lattice_cells" : "particles",
                       sim.has_fluid() ? pc.shape.cells() : s.grains.count);
    js.number("solid_fraction", pc.grains() ? s.solid_fraction : 0.0);
    if (pc.grains()) {
        const double ws = weight_along;
        js.number("solid_fraction_actual", solid_volume / scenario::block_volume(s))
            .text("mode", pc.mode())
            .text("grain_placement", s.placement)
            .integer("grains", static_cast<std::int64_t>(s.grains.count))
            .number("solid_volume_m3", solid_volume)
            .number("grain_radius_mean_m", s.grains.r_mean)
            .number("grain_density_kg_m3", s.grains.density)
            .integer("substeps", pc.fluid_on() ? pc.coupling.substeps : 0)
            .boolean("buoyancy", pc.fluid_on() && pc.coupling.buoyancy)
            .number("dem_dt_s", pc.dem->dt)
            .number("force_normal_max_N", forces.max_normal())
            .number("force_normal_max_over_W_sin_theta", forces.max_normal() / ws)
            .number("time_of_force_normal_max_s", forces.time_of_max_normal())
            .number("solid_force_normal_max_N", forces.max_solid_normal())
            .number("solid_force_normal_max_over_W_sin_theta", forces.max_solid_normal() / ws)
            .number("time_of_solid_force_normal_max_s", forces.time_of_max_solid_normal())
            .number("force_normal_end_N", forces.normal())
            .number("solid_force_normal_end_N", forces.solid_normal())
            .number("solid_non_retained_fraction", debris.solid_non_retained())
            .number("max_overlap_over_d", grains->max_overlap_seen)
            .text("dry_twin_dir", pc.dry_twin_dir);
    }
    if (sim.has_fluid()) js.text("rheology", fs.rheology_name);
    js.number("fluid_volume_m3", fluid_volume)
        .number(pc.grains() ? "W_tot_sin_theta_N" : "W_sin_theta_N", weight_along)
        .number("channel_width_m", s.channel.width)
        .number("barrier_face_x_m", s.barrier.face_x)
        .integer("barrier_elements", static_cast<std::int64_t>(ne))
        .integer("barrier_cells", static_cast<std::int64_t>(blocked))
        .number("fluid_force_normal_max_N", peak_normal)
        .number("fluid_force_normal_max_over_W_sin_theta", peak_normal / weight_along)
        .number("time_of_fluid_force_normal_max_s", forces.time_of_max_fluid_normal())
        .number("fluid_force_normal_end_N", forces.fluid_normal())
        .number("fluid_non_retained_fraction",
                sim.has_fluid() ? debris.state().non_retained : io::not_a_number);
    gauge.summarise(js);
    if (s.barrier.present()) {
        const dem::Particles none;
        const dem::Particles& p = grains ? grains->particles : none;
        const analysis::UpstreamFlow deposit = analysis::upstream_flow(p, s.barrier, s.channel.width, 1.0);
        add_design_comparison(js, out.out_dir,
                              measured_run(gauge.approach(), {forces.max_normal(), forces.normal()}, deposit,
                                           p, s.grains.density, pc.fluid_on() ? u.density() : 0.0, s.barrier,
                                           s.channel.width, s.channel.slope_deg, norm(s.gravity),
                                           pc.grains() ? 1.0 - debris.solid_non_retained() : 0.0));
    }
    add_division_summary(js, division);
    if (sim.has_fluid()) {
        add_lattice_summary(js, fs, debris.state().worst_drift, wall, work);
    } else {
        js.number("wall_time_s", wall).number("particle_steps_per_s", work / wall);
    }
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    if (pc.grains() && sim.has_fluid()) {
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; barrier normal force: peak {:.4g} N = {:.3f} W_tot sin(theta) "
            "at t = {:.3f} s (solid peak {:.3f}, fluid peak {:.3f}); non-retained: solid {:.3f}, fluid "
            "{:.3f}",
            run_status(exit_code), t_end, sim.steps(), format_duration(wall), forces.max_normal(),
            forces.max_normal() / weight_along, forces.time_of_max_normal(),
            forces.max_solid_normal() / weight_along, peak_normal / weight_along, debris.solid_non_retained(),
            debris.state().non_retained);
    } else if (pc.grains()) {  // the dry twin
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; barrier normal force: peak {:.4g} N = {:.3f} W_s sin(theta) "
            "at t = {:.3f} s; solid non-retained {:.3f}",
            run_status(exit_code), t_end, sim.steps(), format_duration(wall), forces.max_normal(),
            forces.max_normal() / weight_along, forces.time_of_max_normal(), debris.solid_non_retained());
    } else {
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; fluid force on the barrier: peak normal {:.4g} N = {:.3f} "
            "W sin(theta) at t = {:.3f} s; fluid non-retained {:.3f}; max relative mass drift {:.2e}",
            run_status(exit_code), t_end, sim.steps(), format_duration(wall), peak_normal,
            peak_normal / weight_along, forces.time_of_max_fluid_normal(), debris.state().non_retained,
            debris.state().worst_drift);
    }
    if (out.report) io::run_report_script(out.out_dir, "debris_report.py");
    checkpoint.tell_how_to_resume(exit_code);
    return exit_code;
}

}  // namespace sabo::sim
