// SPDX-License-Identifier: MIT
#include "cases/dam_break/dam_break_type.h"

#include <spdlog/spdlog.h>

#include <memory>

#include "io/json_writer.h"
#include "sim/run_control.h"
#include "sim/run_summary.h"

namespace sabo::cases {

namespace {

// The rank's lattice (the whole one undivided) with the column.
template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> column_lattice(const PreparedDamBreak& pc,
                                                        const parallel::Domain& domain) {
    const auto& units = pc.fluid.units;
    auto l = domain.make_lattice<Real>(pc.shape, pc.fluid.rheology);
    l->set_pocket_reach(pc.fluid.pocket_reach);
    for (int z = 0; z < pc.height_cells; ++z)
        for (int y = 0; y < pc.shape.ny; ++y)
            for (int x = 0; x < l->shape().nx; ++x)
                if (domain.global_x(x) < pc.column_cells) l->set_fluid(x, y, z, 1.0, {});
    l->prepare();  // the column's faces toward the gas become interface cells
    l->set_acceleration({0.0, 0.0, -units.acceleration(pc.scene.gravity)});
    return l;
}

}  // namespace

parallel::Domain DamBreakType::domain(const MpiWorld* world) const {
    const auto& units = pc_.fluid.units;
    parallel::Domain whole{.origin = {},
                           .dx = units.dx(),
                           .box = {pc_.scene.tank_length, pc_.shape.ny * units.dx(), pc_.scene.tank_height},
                           .halo = parallel::HaloSettings::with_free_surface(pc_.fluid.pocket_reach)};
    if (world != nullptr) whole.divide(*world, pc_.shape.nx);
    return whole;
}

std::optional<sim::Simulation> DamBreakType::build(const parallel::Domain& domain, sim::RunControl&, bool) {
    const double dt = pc_.fluid.units.dt();
    std::optional<sim::Simulation> sim;
    if (pc_.fluid.single_precision)
        sim.emplace(column_lattice<float>(pc_, domain), dt, domain);
    else
        sim.emplace(column_lattice<double>(pc_, domain), dt, domain);
    if (pc_.fluid.on_opencl) sim->run_fluid_on(pc_.fluid.opencl_device);
    return sim;
}

std::vector<sim::Observer*> DamBreakType::observers(const sim::Simulation& sim) {
    const parallel::Domain& domain = sim.domain();
    const double m0 = domain.sum(sim.fluid_fields().totals.mass);  // (the snapshot the first row reads too)
    front_.emplace(pc_, m0, domain);
    frames_.emplace(pc_.output.out_dir, pc_.fluid.units);
    return {&*front_, &*frames_};
}

sim::SummaryHead DamBreakType::summary_head(const sim::Simulation&) const {
    return {pc_.scene.name, "dam_break", "lattice_cells", pc_.shape.cells()};
}

int DamBreakType::summarise(io::JsonObject& js, const sim::Simulation&, const sim::RunEnd& end) {
    versus_ = analysis::compare_with_martin_moyce(front_->times(), front_->fronts());
    std::vector<io::JsonObject> points;
    for (const auto& p : versus_.points) {
        io::JsonObject o;
        o.number("T", p.t_scaled)
            .number("front_over_a_experiment", p.experiment)
            .number("front_over_a_sabo", p.simulation);
        points.push_back(o);
    }
    const double dx = pc_.fluid.units.dx();
    js.number("column_width_m", pc_.column_cells * dx)
        .number("column_height_m", pc_.height_cells * dx)
        .number("front_final_over_a", final_front())
        .number("front_rms_relative_error_vs_martin_moyce",
                versus_.points.empty() ? io::not_a_number : versus_.rms_relative_error)
        .objects("front_vs_martin_moyce", points);
    return end.exit_code;
}

void DamBreakType::summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const {
    sim::add_lattice_summary(js, pc_.fluid, front_->worst_drift(), totals.wall_s, totals.work);
}

void DamBreakType::log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                           const sim::RunTotals& totals) const {
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {}; front {:.3f} a; RMS deviation from Martin & Moyce {:.1f} % "
        "over {} points; max relative mass drift {:.2e}",
        sim::run_status(end.exit_code), end.time, sim.steps(), sim::format_duration(totals.wall_s),
        final_front(), 100.0 * versus_.rms_relative_error, versus_.points.size(), front_->worst_drift());
}

double DamBreakType::final_front() const {
    return front_->fronts().empty() ? 0.0 : front_->fronts().back();
}

}  // namespace sabo::cases
