// SPDX-License-Identifier: MIT
#include "cases/fluid_box/fluid_box_type.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "core/error.h"
#include "sim/run_summary.h"

namespace sabo::cases {

SettlingPrediction settling_prediction(double radius, double grain_density, double fluid_density,
                                       double viscosity, double gravity) {
    SettlingPrediction p;
    const double d = 2.0 * radius;
    p.stokes = (grain_density - fluid_density) * gravity * d * d / (18.0 * viscosity);
    double v = p.stokes;
    for (int it = 0; it < 200; ++it) {  // v = v_Stokes / (1 + 0.15 Re^0.687): a contraction
        const double re = std::abs(v) * d * fluid_density / viscosity;
        v = p.stokes / (1.0 + 0.15 * std::pow(re, 0.687));
    }
    p.schiller_naumann = v;
    p.reynolds = std::abs(v) * d * fluid_density / viscosity;
    return p;
}

double periodic_array_correction(double phi) {
    const double c = std::cbrt(phi);
    return 1.0 / (1.0 - 1.7601 * c + phi - 1.5593 * phi * phi + 3.9799 * std::pow(phi, 7.0 / 3.0) -
                  3.0734 * std::pow(phi, 8.0 / 3.0));
}

parallel::Domain FluidBoxType::domain(const MpiWorld* world) const {
    if (world != nullptr && world->size() > 1)
        throw InputError("case.type = \"fluid_box\" runs in one process (use threads, not MPI ranks)");
    return {.origin = {}, .dx = pc_.fluid.units.dx(), .box = pc_.scene.size};
}

std::optional<sim::Simulation> FluidBoxType::build(const parallel::Domain& domain, sim::RunControl&, bool) {
    const auto& s = pc_.scene;
    const auto& units = pc_.fluid.units;
    const auto make = [&]<class Real>() {
        auto l = domain.make_lattice<Real>(pc_.shape, pc_.fluid.rheology);
        l->set_pocket_reach(pc_.fluid.pocket_reach);
        // at rest under gravity from the start: the hydrostatic density dρ/dz = −3 g ρ (lattice units, c_s² =
        // 1/3), 1 at mid-height; a uniform start would collapse and ring as a standing sound wave of period
        // 2H / c_s (0.07 s in the shipped case), which the grains feel as an oscillating drag
        const double g = units.acceleration(s.gravity), middle = 0.5 * pc_.shape.nz;
        for (int z = 0; z < pc_.shape.nz; ++z)
            for (int y = 0; y < pc_.shape.ny; ++y)
                for (int x = 0; x < pc_.shape.nx; ++x)
                    l->set_fluid(x, y, z, std::exp(-3.0 * g * (z + 0.5 - middle)), {});
        l->prepare();
        l->set_acceleration({0.0, 0.0, -units.acceleration(s.gravity)});
        sim::Simulation sim(dem::make_solver(s.particles, s.walls, {0.0, 0.0, -s.gravity}, pc_.dem),
                            std::move(l), coupling::GrainFluidCoupling(pc_.coupling, units, domain.origin),
                            units.dt(), domain);
        // the drive is a force on the fluid alone (a mean pressure gradient ρ_f a along X), not gravity: it
        // joins the lattice's body force after the set-up's one-gravity check, and the grains' buoyancy
        // stays gravity's (a periodic box has no mean pressure gradient of its own)
        if (s.drive > 0.0)
            sim.with_fluid([&](auto& lattice) {
                lattice.set_acceleration({units.acceleration(s.drive), 0.0, -units.acceleration(s.gravity)});
            });
        if (pc_.fluid.on_opencl) sim.run_fluid_on(pc_.fluid.opencl_device);
        return sim;
    };
    return pc_.fluid.single_precision ? make.template operator()<float>()
                                      : make.template operator()<double>();
}

std::vector<sim::Observer*> FluidBoxType::observers(const sim::Simulation& sim) {
    measures_.emplace(pc_, sim.fluid_fields().totals.mass);
    fluid_frames_.emplace(pc_.output.out_dir, pc_.fluid.units);
    grain_frames_.emplace(pc_.output.out_dir);
    return {&*measures_, &*fluid_frames_, &*grain_frames_};
}

sim::SummaryHead FluidBoxType::summary_head(const sim::Simulation&) const {
    return {pc_.scene.name, "fluid_box", "lattice_cells", pc_.shape.cells()};
}

int FluidBoxType::summarise(io::JsonObject& js, const sim::Simulation& sim, const sim::RunEnd& end) {
    const auto& s = pc_.scene;
    const dem::Particles& p = sim.grains().particles();
    const double rho_f = pc_.fluid.units.density();
    std::vector<io::JsonObject> grains;
    for (std::size_t i = 0; i < p.n_mobile && i < 100; ++i) {
        const Vec3 v = measures_->late_velocity(i);
        const SettlingPrediction pred =
            settling_prediction(p.r[i], s.density, rho_f, pc_.fluid.viscosity, s.gravity);
        io::JsonObject o;
        o.integer("grain", static_cast<std::int64_t>(i))
            .number("radius_m", p.r[i])
            .number("x_m", p.x[i].x)
            .number("y_m", p.x[i].y)
            .number("z_m", p.x[i].z)
            .number("vz_end_m_s", p.v[i].z)
            .number("settling_velocity_m_s", -v.z)
            .number("lateral_velocity_m_s", std::hypot(v.x, v.y))
            .number("reynolds", std::abs(v.z) * 2.0 * p.r[i] * rho_f / pc_.fluid.viscosity)
            .number("stokes_velocity_m_s", pred.stokes)
            .number("schiller_naumann_velocity_m_s", pred.schiller_naumann);
        const Vec3 force = measures_->late_force(i);
        o.number("force_x_N", force.x).number("force_y_N", force.y).number("force_z_N", force.z);
        grains.push_back(o);
    }
    const double flow = measures_->late_flow();
    const std::string periodic =
        std::string(s.periodic[0] ? "x" : "") + (s.periodic[1] ? "y" : "") + (s.periodic[2] ? "z" : "");
    js.text("periodic", periodic.empty() ? "none" : periodic)
        .number("drive_x_m_s2", s.drive)
        .boolean("grains_held", s.held)
        .number("fluid_mean_velocity_x_m_s", flow);
    if (s.held && s.drive > 0.0 && p.n_mobile == 1 && flow > 0.0 && s.periodic[0] && s.periodic[1] &&
        s.periodic[2]) {
        // one held sphere in a box periodic every way is a simple cubic array: its drag is that of the
        // equivalent flow driven by the mean pressure gradient ρ_f a, the body force on the whole box
        // (docs/coupling.md), against Stokes' drag at the mean velocity times the array's correction
        const double box = s.size.x * s.size.y * s.size.z, r = p.r[0];
        const double phi = 4.0 / 3.0 * std::numbers::pi * r * r * r / box;
        const double drag = rho_f * s.drive * box,
                     stokes = 6.0 * std::numbers::pi * pc_.fluid.viscosity * r * flow;
        io::JsonObject a;
        a.number("solid_fraction", phi)
            .number("drag_N", drag)
            .number("exchange_force_x_N", measures_->late_force(0).x)
            .number("stokes_drag_N", stokes)
            .number("array_correction", periodic_array_correction(phi))
            .number("drag_over_prediction", drag / (stokes * periodic_array_correction(phi)))
            .number("reynolds", flow * 2.0 * r * rho_f / pc_.fluid.viscosity);
        js.object("periodic_array", a);
    }
    js.number("box_length_m", s.size.x)
        .number("box_width_m", s.size.y)
        .number("box_height_m", s.size.z)
        .integer("grains", static_cast<std::int64_t>(p.n_mobile))
        .number("grain_density_kg_m3", s.density)
        .number("fluid_density_kg_m3", rho_f)
        .number("viscosity_Pa_s", pc_.fluid.viscosity)
        .number("gravity_m_s2", s.gravity)
        .number("d_over_dx_min", 2.0 * s.r_min / pc_.fluid.units.dx())
        .integer("substeps", pc_.coupling.substeps)
        .text("coupling_model", std::string(coupling::name(pc_.coupling.model)))
        .boolean("buoyancy", pc_.coupling.buoyancy)
        .text("buoyancy_volume", std::string(coupling::name(pc_.coupling.volume)))
        .number("averaged_from_s", pc_.average_from)
        .integer("averaged_samples", static_cast<std::int64_t>(measures_->averaged_samples()))
        .objects("grain_settling", grains);
    return end.exit_code;
}

void FluidBoxType::summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const {
    sim::add_lattice_summary(js, pc_.fluid, measures_->worst_drift(), totals.wall_s, totals.work);
}

void FluidBoxType::log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                           const sim::RunTotals& totals) const {
    const dem::Particles& p = sim.grains().particles();
    const std::string head = fmt::format("{}: t = {:.4f} s, {} steps in {}", sim::run_status(end.exit_code),
                                         end.time, sim.steps(), sim::format_duration(totals.wall_s));
    if (pc_.scene.held) {
        const Vec3 f = measures_->late_force(0);
        spdlog::info(
            "{}; the grains held; over the last fifth the fluid's mean velocity along X {:.5g} m/s, the "
            "force on "
            "grain 0 ({:.5g}, {:.5g}, {:.5g}) N; max relative mass drift {:.2e}",
            head, measures_->late_flow(), f.x, f.y, f.z, measures_->worst_drift());
        return;
    }
    const Vec3 v = measures_->late_velocity(0);
    const SettlingPrediction pred = settling_prediction(p.r[0], pc_.scene.density, pc_.fluid.units.density(),
                                                        pc_.fluid.viscosity, pc_.scene.gravity);
    spdlog::info(
        "{}; grain 0 settles at {:.5g} m/s over the last fifth (unbounded fluid: Stokes {:.5g}, "
        "Schiller-Naumann {:.5g} m/s at Re {:.3g}); max relative mass drift {:.2e}",
        head, -v.z, pred.stokes, pred.schiller_naumann, pred.reynolds, measures_->worst_drift());
}

}  // namespace sabo::cases
