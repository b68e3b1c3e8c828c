// SPDX-License-Identifier: MIT
// Validation of the grain–fluid coupling against the drag of a sphere in slow flow:
// - a fixed sphere in a periodic box (a simple cubic array) against the Stokes drag with the periodic
//   correction of Hasimoto (1959) as extended by Sangani & Acrivos (1982), at d/Δx = 8 and 16;
// - a sphere settling in a closed box reaching the Stokes terminal velocity with Schiller–Naumann's
//   Reynolds-number correction and Haberman & Sayre's wall correction.
// Resolutions, errors and their causes: docs/verification.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include "cases/fluid_box/fluid_box_type.h"
#include "coupling/coupling_support.h"

namespace sabo {
namespace {

constexpr double pi = std::numbers::pi;

// Drag coefficient K_sim / K_Hasimoto − 1 of a sphere of radius r_cells held at rest in a periodic box of
// n cells driven by a body force ρ a, at steady state; its centre `offset` cells off the box's centre along x
// (and 0.3 offset along y). The force on the sphere of the equivalent flow driven by a mean pressure gradient
// G = ρ a is G times the box's volume (Sangani & Acrivos): the body force on the whole box. The exchange
// carries all of it by the cell-centre rule (every cell is weighed); with partially saturated cells the
// solid share B of the covered cells is not weighed, and the exchange carries the body force on the rest,
// the mean gradient's push on that share being what the periodic body force does not make.
double fixed_sphere_drag_error(int n, double r_cells, double tau,
                               coupling::CoverRule rule = coupling::CoverRule::cell_centre,
                               double offset = 0.0) {
    const lbm::UnitConverter u(1.0, 1.0, 1.0);  // lattice units throughout
    auto l = test::full_lattice({n, n, n, {true, true, true}}, tau);
    const double a = 1e-6;  // slow: Re = U d / ν ≈ 0.03
    l->set_acceleration({a, 0, 0});
    dem::DemSolver held =
        test::one_grain({0.5 * n + offset, 0.5 * n + 0.3 * offset, 0.5 * n}, r_cells, 2.0, {}, {}, 1.0);
    coupling::CouplingSettings cs;
    cs.model = rule;
    coupling::GrainFluidCoupling c(cs, u, {});
    const double body = a * n * n * n;
    double drag = 0.0, weighed = body;
    for (int k = 0; k < 40000; ++k) {
        c.before_fluid_step(held.particles(), *l);  // held: never stepped
        l->step();
        c.after_fluid_step(*l, held);
        drag = c.last_exchange().drag.x;
        double solid = 0.0;  // Σ B: the share of the box not weighed
        if (rule == coupling::CoverRule::psm)
            for (const lbm::SolidCell& s : l->solid_cells()) solid += lbm::saturation_weight(s.fraction, tau);
        weighed = a * (n * n * n - solid);
        if (k > 200 && std::abs(drag / weighed - 1.0) < 1e-3) break;
    }
    EXPECT_NEAR(drag / weighed, 1.0, 1e-3) << "not at steady state";
    double flux = 0.0;
    (void)l->totals([&](std::size_t, double rho, const Vec3& v) { flux += rho * v.x; });
    const double mean_u = flux / (n * n * n), nu = (tau - 0.5) / 3.0;
    const double phi = 4.0 / 3.0 * pi * r_cells * r_cells * r_cells / (n * n * n);
    return body / (6.0 * pi * nu * r_cells * mean_u) / cases::periodic_array_correction(phi) - 1.0;
}

TEST(SphereDrag, FixedSphereInAPeriodicArrayConvergesToHasimoto) {
    // box 2.5 d (φ = 0.0335, correction 2.15); τ = 0.8
    const double coarse = fixed_sphere_drag_error(20, 4.0, 0.8);  // d/Δx = 8
    const double fine = fixed_sphere_drag_error(40, 8.0, 0.8);    // d/Δx = 16
    RecordProperty("drag_error_d_over_dx_8", std::to_string(coarse));
    RecordProperty("drag_error_d_over_dx_16", std::to_string(fine));
    EXPECT_LT(std::abs(coarse), 0.10);
    EXPECT_LT(std::abs(fine), 0.05);
    EXPECT_LT(std::abs(fine), 0.6 * std::abs(coarse)) << "the error must fall about as Δx (first order)";
}

// The same with partially saturated cells: −6.4 % at d/Δx = 8 and −1.4 % at 16 (τ = 0.8; first order), and
// the drag no longer depends on where the sphere lies on the grid (0.05 % for a shift of 0.37 cell against
// 1.6 % by the cell-centre rule, whose staircase changes as the sphere moves).
TEST(SphereDrag, PartiallySaturatedCellsConvergeToHasimotoWhereverTheSphereLies) {
    const auto psm = coupling::CoverRule::psm;
    const double coarse = fixed_sphere_drag_error(20, 4.0, 0.8, psm);
    const double shifted = fixed_sphere_drag_error(20, 4.0, 0.8, psm, 0.37);
    const double fine = fixed_sphere_drag_error(40, 8.0, 0.8, psm);
    const double centre_rule_shift =
        fixed_sphere_drag_error(20, 4.0, 0.8, coupling::CoverRule::cell_centre, 0.37) -
        fixed_sphere_drag_error(20, 4.0, 0.8);
    RecordProperty("psm_drag_error_d_over_dx_8", std::to_string(coarse));
    RecordProperty("psm_drag_error_d_over_dx_16", std::to_string(fine));
    EXPECT_LT(std::abs(coarse), 0.10);
    EXPECT_LT(std::abs(fine), 0.05);
    EXPECT_LT(std::abs(fine), 0.6 * std::abs(coarse)) << "the error must fall about as Δx (first order)";
    EXPECT_LT(std::abs(shifted - coarse), 0.002);
    EXPECT_GT(std::abs(centre_rule_shift), 0.005) << "the cell-centre rule's drag moves with the sphere";
}

// Haberman & Sayre (1958): drag of a sphere on the axis of a cylinder, λ = d / D, relative to Stokes'.
double wall_correction(double lambda) {
    const double l3 = lambda * lambda * lambda, l5 = l3 * lambda * lambda, l6 = l5 * lambda;
    return (1.0 - 0.75857 * l5) / (1.0 - 2.1050 * lambda + 2.0865 * l3 - 1.7068 * l5 + 0.72603 * l6);
}

TEST(SphereDrag, ASettlingSphereReachesItsTerminalVelocity) {
    // lattice units: a sphere of d = 8 cells, twice as dense as the fluid, in the middle of a closed box of
    // 6 d; Re at the terminal velocity ≈ 0.4
    const int n = 48;
    const double r = 4.0, tau = 0.8, nu = (tau - 0.5) / 3.0, rho_s = 2.0, g = 1.4e-4;
    const lbm::UnitConverter u(1.0, 1.0, 1.0);
    auto l = test::full_lattice({n, n, n, {false, false, false}}, tau);
    l->set_acceleration({0, 0, -g});
    coupling::CouplingSettings cs;
    cs.gravity = {0, 0, -g};
    cs.substeps = 1;
    sim::Simulation run =
        test::coupled_run(test::one_grain({0.5 * n, 0.5 * n, 0.8 * n}, r, rho_s, {}, {0, 0, -g}, 1.0),
                          std::move(l), cs, u);  // the coupled step of a run
    // the velocity history (settling_sphere_velocity.csv in GoogleTest's temporary folder, whatever folder
    // the tests run from): terminal by ~2500 steps, then ±1.5 % as the grain's cell count changes on its way
    // down
    std::ofstream history(::testing::TempDir() + "settling_sphere_velocity.csv");
    history << "step,velocity_z\n";
    double early = 0.0, late = 0.0;  // mean velocity over steps 2501–3000 and 3001–3500
    for (int k = 1; k <= 3500; ++k) {
        run.step();
        const double v = run.grains().particles().v[0].z;
        if (k % 10 == 0) history << k << ',' << v << '\n';
        if (k > 2500) (k > 3000 ? late : early) += v / 500.0;
    }
    EXPECT_NEAR(late / early, 1.0, 0.02) << "not at the terminal velocity yet";
    const double v = 0.5 * (early + late);
    // Stokes with the wall correction, then Schiller–Naumann's correction at the resulting Re (iterated)
    const double stokes = 2.0 / 9.0 * (rho_s - 1.0) * g * r * r / nu / wall_correction(2.0 * r / n);
    double predicted = stokes;
    for (int it = 0; it < 20; ++it) {
        const double re = predicted * 2.0 * r / nu;
        predicted = stokes / (1.0 + 0.15 * std::pow(re, 0.687));
    }
    const double error = -v / predicted - 1.0;
    RecordProperty("terminal_velocity_error", std::to_string(error));
    RecordProperty("terminal_reynolds", std::to_string(predicted * 2.0 * r / nu));
    std::printf("terminal velocity %.5g, predicted %.5g (Stokes %.5g), error %.3f\n", -v, predicted, stokes,
                error);
    EXPECT_LT(std::abs(error), 0.15);
}

}  // namespace
}  // namespace sabo
