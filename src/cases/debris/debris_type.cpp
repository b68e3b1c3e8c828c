// SPDX-License-Identifier: MIT
#include "cases/debris/debris_type.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include "analysis/flow_measures.h"
#include "cases/common/design_comparison.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/geometry_output.h"
#include "lbm/fluid_summary.h"
#include "scenario/debris_lattice.h"
#include "sim/run_control.h"
#include "sim/run_summary.h"

namespace sabo::cases {

namespace {

// The rank's lattice (the whole one undivided) with the fluid block and the barrier's cells; their count per
// element over all ranks.
template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> debris_lattice(const PreparedDebris& pc,
                                                        const parallel::Domain& domain,
                                                        std::vector<std::size_t>& barrier_cells,
                                                        double& seed) {
    const auto& s = pc.scene;
    const auto& units = pc.fluid.units;
    auto l = domain.make_lattice<Real>(pc.shape, pc.fluid.rheology);
    l->set_pocket_reach(pc.fluid.pocket_reach);
    scenario::fill_fluid_block(*l, s, units.dx(), domain.slab.first_global_x);
    scenario::mark_channel_mesh(*l, s, units.dx(), domain.slab.first_global_x);
    seed = scenario::seed_inlet(*l, s, units.dx(), domain.slab.first_global_x);
    barrier_cells = scenario::mark_barrier(*l, s, units.dx(), domain.slab.first_global_x);
    scenario::mark_outlets(*l, s, units.dx(), pc.shape.nx, domain.slab.first_global_x);
    if (s.barrier.mesh) l->keep_barrier_links();  // the fluid's force on each triangle (barrier_facets.vtp)
    for (std::size_t& n : barrier_cells) n = static_cast<std::size_t>(domain.sum(static_cast<double>(n)));
    l->prepare();
    l->set_acceleration({units.acceleration(s.gravity.x), 0.0, units.acceleration(s.gravity.z)});
    return l;
}

}  // namespace

parallel::Domain debris_domain(const PreparedDebris& pc, const MpiWorld* world) {
    const auto& s = pc.scene;
    parallel::Domain domain{.origin = {},
                            .dx = pc.fluid.units.dx(),
                            .box = {s.channel.length, s.channel.width, s.bounds.domain_height},
                            .halo = parallel::HaloSettings::with_free_surface(pc.fluid.pocket_reach)};
    if (s.fed_grains) domain.fed_radius_max = s.inflow->r_max();
    if (world == nullptr) return domain;
    if (pc.fluid_on())
        domain.divide(*world, pc.shape.nx);
    else
        domain.divide_grains(*world);  // the dry twin: grains alone, in slabs of their own
    return domain;
}

sim::Simulation debris_simulation(const PreparedDebris& pc, const parallel::Domain& domain,
                                  std::vector<std::size_t>& barrier_cells, double* inlet_seed) {
    const auto& s = pc.scene;
    const auto& units = pc.fluid.units;
    if (!pc.fluid_on())
        return sim::Simulation(dem::make_solver(s.particles, s.walls, s.gravity, *pc.dem), domain);
    const auto build = [&]<class Real>() {
        double seed = 0.0;
        auto lattice = debris_lattice<Real>(pc, domain, barrier_cells, seed);
        if (inlet_seed != nullptr) *inlet_seed = seed;
        if (!pc.grains()) {
            sim::Simulation fluid(std::move(lattice), units.dt(), domain);
            if (pc.fluid.on_opencl) fluid.run_fluid_on(pc.fluid.opencl_device);
            return fluid;
        }
        sim::Simulation coupled(
            dem::make_solver(s.particles, s.walls, s.gravity, *pc.dem), std::move(lattice),
            coupling::GrainFluidCoupling(pc.coupling, units, domain.origin), units.dt(), domain);
        if (pc.fluid.on_opencl) coupled.run_fluid_on(pc.fluid.opencl_device);
        return coupled;
    };
    sim::Simulation sim =
        pc.fluid.single_precision ? build.template operator()<float>() : build.template operator()<double>();
    // the fluid that passed the barrier (the observer's non-retained fraction), and over its crest or below
    // it (the links into the cells behind it from those above its height or not)
    if (s.barrier.present())
        sim.set_fluid_region([&](const Vec3& c) {
            return static_cast<std::uint8_t>((s.barrier.downstream(c) ? lbm::region_downstream : 0) |
                                             (c.z > s.barrier.height ? lbm::region_above_crest : 0));
        });
    return sim;
}

std::optional<sim::Simulation> DebrisType::build(const parallel::Domain& domain, sim::RunControl&, bool) {
    sim::Simulation sim = debris_simulation(pc_, domain, barrier_cells_, &inlet_seed_);
    blocked_cells_ = 0;
    for (const auto n : barrier_cells_) blocked_cells_ += n;
    return sim;
}

std::vector<sim::Observer*> DebrisType::observers(const sim::Simulation& sim) {
    const auto& s = pc_.scene;
    const auto& units = pc_.fluid.units;
    const double dx = units.dx();
    const parallel::Domain& domain = sim.domain();
    // (the snapshot the first series row reads too)
    const double m_start = sim.has_fluid() ? domain.sum(sim.fluid_fields().totals.mass) : 0.0;
    // the fluid: the block's cells less the grains' volume (the fluid in grain cells moves with them)
    double solid_volume = s.grains.solid_volume;
    fluid_volume_ = sim.has_fluid() ? m_start * dx * dx * dx - solid_volume : 0.0;
    if (s.inflow) {  // the whole surge's (W_tot and the forces over it)
        const auto& h = s.inflow->hydrograph;
        fluid_volume_ += h.fluid_volume(h.start(), h.end());
        if (s.fed_grains) solid_volume += h.solid_volume(h.start(), h.end());
    }
    const double sin_theta = std::sin(s.channel.slope_deg * std::numbers::pi / 180.0);
    const double weight = units.density() * s.channel.gravity * fluid_volume_ +
                          s.grains.density * s.channel.gravity * solid_volume;  // W_tot, N
    // W_tot sin θ, N (NaN on a level channel: the normalised columns are then empty)
    weight_along_ = sin_theta > 0.0 ? weight * sin_theta : std::numeric_limits<double>::quiet_NaN();
    if (pc_.grains())
        spdlog::info(
            "debris: {:.3f} m3 of fluid ({:.0f} kg) and {:.3f} m3 of grains ({:.0f} kg); W_tot sin(theta) = "
            "{:.4g} N",
            fluid_volume_, units.density() * fluid_volume_, solid_volume, s.grains.density * solid_volume,
            weight_along_);
    if (sim.has_fluid())
        spdlog::info(
            "fluid block {:.3f} m3 ({:.0f} kg), W sin(theta) = {:.4g} N; barrier: {} elements on {} lattice "
            "cells",
            m_start * dx * dx * dx, units.density() * m_start * dx * dx * dx, weight_along_,
            barrier_cells_.size(), blocked_cells_);
    debris_.emplace(pc_, weight_along_, domain);
    debris_->state().m0 = m_start;
    gauge_.emplace(pc_.gauge, debris_->forces(), pc_.output.out_dir,
                   sim.has_fluid() ? std::optional(units) : std::nullopt, domain);
    // the channel and the barrier around every view (once, when the run starts)
    if (domain.writes_outputs())
        io::write_geometry(pc_.output.out_dir / "geometry.vtp", s.walls, s.particles, domain.box,
                           s.barrier.mesh.get());
    std::vector<sim::Observer*> observers{&*debris_, &*gauge_};
    if (s.inflow) {  // first: the cells it fills are the state the others read
        inflow_.emplace(*s.inflow, units, scenario::inlet_bed_cells(s, dx, pc_.shape),
                        static_cast<int>(std::floor(s.channel.height / dx)), domain.sum(inlet_seed_),
                        -s.gravity.z, *debris_, pc_.output.out_dir, domain.writes_outputs());
        observers.insert(observers.begin(), &*inflow_);
    }
    if (s.fed_grains) {  // the grains join at the lattice steps' ends, the coupling finds them next step
        grain_inflow_.emplace(*s.inflow, units.dt(), pc_.output.out_dir, domain.writes_outputs(), true);
        debris_->feed_from(*grain_inflow_);
        observers.insert(observers.begin(), &*grain_inflow_);
    }
    if (sim.has_fluid()) observers.push_back(&fluid_frames_.emplace(pc_.output.out_dir, units));
    if (sim.has_grains()) observers.push_back(&grain_frames_.emplace(pc_.output.out_dir));
    return observers;
}

void DebrisType::finish(sim::Simulation& sim, const sim::RunEnd& end) {
    debris_->finish_forces(sim, end.time);
    if (sim.has_grains()) grains_.emplace(sim.grain_view());  // every grain (a collective call when divided)
}

void DebrisType::write_end_files(const sim::Simulation& sim, const sim::RunEnd&) {
    const auto& s = pc_.scene;
    const auto& forces = debris_->forces();
    io::write_force_maps(pc_.output.out_dir, s.barrier, forces);
    if (s.barrier.mesh)
        io::write_facet_maps(pc_.output.out_dir, *s.barrier.mesh, debris_->facet_maps(), pc_.grains(),
                             pc_.fluid_on());
    if (!sim.has_fluid()) return;
    // per element: where it is and the largest fluid force it received
    std::string csv = "element,pile,x_m,y_m,z_m,height_m,lattice_cells,max_fluid_force_N\n";
    for (std::size_t e = 0; e < s.barrier.elements.size(); ++e) {
        const auto& el = s.barrier.elements[e];
        csv +=
            fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.6g}\n", e, el.pile, el.centre.x, el.centre.y,
                        el.centre.z, el.height, barrier_cells_[e], forces.fluid_envelope()[e]);
    }
    io::write_text_atomically(pc_.output.out_dir / "barrier_fluid_elements.csv", csv);
}

sim::SummaryHead DebrisType::summary_head(const sim::Simulation& sim) const {
    if (sim.has_fluid()) return {pc_.scene.name, "debris", "lattice_cells", pc_.shape.cells()};
    return {pc_.scene.name, "debris", "particles", pc_.scene.grains.count};
}

int DebrisType::summarise(io::JsonObject& js, const sim::Simulation& sim, const sim::RunEnd& end) {
    const auto& s = pc_.scene;
    const auto& units = pc_.fluid.units;
    const auto& forces = debris_->forces();
    const double solid_mass = debris_->solid_mass_kg(), solid_volume = debris_->solid_volume_m3();
    const double ws = weight_along_;
    const double peak_normal = forces.max_fluid_normal();
    js.number("solid_fraction", pc_.grains() ? s.solid_fraction : 0.0);
    if (pc_.grains()) {
        js.number("solid_fraction_actual",
                  s.fed_grains ? io::not_a_number : solid_volume / scenario::block_volume(s))
            .text("mode", pc_.mode())
            .text("grain_placement", s.placement)
            .integer("grains", static_cast<std::int64_t>(s.grains.count))
            .number("solid_volume_m3", solid_volume)
            .number("grain_radius_mean_m", s.grains.r_mean)
            .number("grain_density_kg_m3", s.grains.density)
            .integer("substeps", pc_.fluid_on() ? pc_.coupling.substeps : 0)
            .text("coupling_model",
                  pc_.fluid_on() ? std::string(coupling::name(pc_.coupling.model)) : std::string())
            .boolean("buoyancy", pc_.fluid_on() && pc_.coupling.buoyancy)
            .text("buoyancy_volume", pc_.fluid_on() && pc_.coupling.buoyancy
                                         ? std::string(coupling::name(pc_.coupling.volume))
                                         : std::string())
            .number("dem_dt_s", pc_.dem->dt)
            .number("force_normal_max_N", forces.max_normal())
            .number("force_normal_max_over_W_sin_theta", forces.max_normal() / ws)
            .number("time_of_force_normal_max_s", forces.time_of_max_normal())
            .number("solid_force_normal_max_N", forces.max_solid_normal())
            .number("solid_force_normal_max_over_W_sin_theta", forces.max_solid_normal() / ws)
            .number("time_of_solid_force_normal_max_s", forces.time_of_max_solid_normal())
            .number("force_normal_end_N", forces.normal())
            .number("solid_force_normal_end_N", forces.solid_normal())
            .number("solid_non_retained_fraction", debris_->solid_non_retained())
            .number("max_overlap_over_d", grains_->max_overlap_seen)
            .text("dry_twin_dir", pc_.dry_twin_dir);
        debris_->outflow().summarise(js, solid_mass);
    }
    if (sim.has_fluid()) js.text("rheology", pc_.fluid.rheology_name);
    js.number("fluid_volume_m3", fluid_volume_)
        .number(pc_.grains() ? "W_tot_sin_theta_N" : "W_sin_theta_N", ws)
        .number("channel_width_m", s.channel.width)
        .integer("barrier_elements", static_cast<std::int64_t>(s.barrier.elements.size()))
        .integer("barrier_cells", static_cast<std::int64_t>(blocked_cells_))
        .number("fluid_force_normal_max_N", peak_normal)
        .number("fluid_force_normal_max_over_W_sin_theta", peak_normal / ws)
        .number("time_of_fluid_force_normal_max_s", forces.time_of_max_fluid_normal())
        .number("fluid_force_normal_end_N", forces.fluid_normal())
        .number("fluid_non_retained_fraction",
                sim.has_fluid() ? debris_->state().non_retained : io::not_a_number)
        .number("fluid_over_crest_fraction",
                sim.has_fluid() ? debris_->fluid_behind_fraction(0) : io::not_a_number)
        .number("fluid_through_outlets_fraction",
                sim.has_fluid() ? debris_->fluid_behind_fraction(1) : io::not_a_number)
        .number("fluid_spread_behind_fraction",
                sim.has_fluid() ? debris_->fluid_behind_fraction(2) : io::not_a_number)
        .number("wall_height_m", s.channel.height)
        .number("barrier_height_m", s.barrier.height);
    io::add_barrier_face(js, s.barrier);
    summarise_bounds(js, s.bounds);
    js.number("fluid_height_max_m", sim.has_fluid() ? debris_->state().max_height : io::not_a_number)
        .boolean("fluid_reached_domain_top", sim.has_fluid() && debris_->state().top_reached);
    for (std::size_t o = 0; o < scenario::debris_outlet_names.size(); ++o)
        js.number(fmt::format("fluid_left_{}_fraction", scenario::debris_outlet_names[o]),
                  sim.has_fluid() ? debris_->state().left[o] : io::not_a_number);
    for (const auto& m : debris_->normal_means()) {
        const std::string window = fmt::format("{:.0f}ms", 1000.0 * m.window());
        js.number("force_normal_max_mean_" + window + "_N", m.max_mean())
            .number("force_normal_max_mean_" + window + "_over_W_sin_theta", m.max_mean() / ws)
            .number("time_of_force_normal_max_mean_" + window + "_s", m.time_of_max_mean());
    }
    gauge_->summarise(js);
    if (inflow_) inflow_->summarise(js);
    if (grain_inflow_) grain_inflow_->summarise(js);
    if (s.barrier.present()) {
        const dem::Particles none;
        const dem::Particles& p = grains_ ? grains_->particles : none;
        const analysis::UpstreamFlow deposit = analysis::upstream_flow(p, s.barrier, s.channel.width, 1.0);
        const bool at_rest = end.exit_code == 0 && end.ending == sim::RunEnding::complete_stop;
        add_design_comparison(
            js, pc_.output.out_dir,
            measured_run(gauge_->approach(), {forces.max_normal(), at_rest ? forces.normal() : std::nan("")},
                         deposit, p, s.grains.density, pc_.fluid_on() ? units.density() : 0.0, s.barrier,
                         s.channel.width, s.channel.slope_deg, norm(s.gravity),
                         debris_->outflow().retained(debris_->solid_non_retained(), solid_mass)));
    }
    return end.exit_code;
}

void DebrisType::summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const {
    if (pc_.fluid_on())
        sim::add_lattice_summary(js, pc_.fluid, debris_->state().worst_drift, totals.wall_s, totals.work);
    else
        js.number("wall_time_s", totals.wall_s).number("particle_steps_per_s", totals.work / totals.wall_s);
}

void DebrisType::log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                         const sim::RunTotals& totals) const {
    const auto& forces = debris_->forces();
    const double w = weight_along_;
    const std::string status = sim::run_status(end.exit_code);
    const std::string wall = sim::format_duration(totals.wall_s);
    if (pc_.grains() && sim.has_fluid()) {
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; barrier normal force: peak {:.4g} N = {:.3f} W_tot sin(theta) "
            "at t = {:.3f} s (solid peak {:.3f}, fluid peak {:.3f}); non-retained: solid {:.3f}, fluid "
            "{:.3f}",
            status, end.time, sim.steps(), wall, forces.max_normal(), forces.max_normal() / w,
            forces.time_of_max_normal(), forces.max_solid_normal() / w, forces.max_fluid_normal() / w,
            debris_->solid_non_retained(), debris_->state().non_retained);
    } else if (pc_.grains()) {  // the dry twin
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; barrier normal force: peak {:.4g} N = {:.3f} W_s sin(theta) "
            "at t = {:.3f} s; solid non-retained {:.3f}",
            status, end.time, sim.steps(), wall, forces.max_normal(), forces.max_normal() / w,
            forces.time_of_max_normal(), debris_->solid_non_retained());
    } else {
        spdlog::info(
            "{}: t = {:.4f} s, {} steps in {}; fluid force on the barrier: peak normal {:.4g} N = {:.3f} "
            "W sin(theta) at t = {:.3f} s; fluid non-retained {:.3f}; max relative mass drift {:.2e}",
            status, end.time, sim.steps(), wall, forces.max_fluid_normal(), forces.max_fluid_normal() / w,
            forces.time_of_max_fluid_normal(), debris_->state().non_retained, debris_->state().worst_drift);
    }
    // the channel case's rule, dry or in fluid
    if (pc_.grains())
        sim::warn_large_overlap(grains_->max_overlap_seen, "stiffer contacts or smaller impact speeds");
    // the fluid the surface's conversions placed behind the barrier is not flow (docs/lbm.md, "What the
    // spread moves"): said when it is a tenth of what passed and more than a trace
    const double spread = sim.has_fluid() ? debris_->fluid_behind_fraction(2) : 0.0;
    const double passed = sim.has_fluid() ? debris_->state().non_retained : 0.0;
    if (spread > 0.01 && spread > 0.1 * passed)
        spdlog::warn(
            "{:.3f} of the fluid ({:.0f} % of the {:.3f} that passed) was placed behind the barrier by "
            "the free surface's conversions, not by flow (fluid_spread_behind_fraction): {}a finer "
            "lattice.dx_m lowers it (about in proportion)",
            spread, 100.0 * spread / passed, passed,
            pc_.fluid.pocket_reach == 0 ? "lattice.pocket_reach_cells = 3 takes the closed pockets' volume "
                                          "near them instead (docs/lbm.md, \"What the spread moves\"); "
                                        : "");
}

}  // namespace sabo::cases
