// SPDX-License-Identifier: MIT
// The grain cells found on the lattice's device are the host finder's (coupling/grain_cells.h), by both
// rules, grains overlapping each other and the lattice's edges, and again after the grains move (the
// device releases the cells of the last call); the exchange made there gives the grains the CPU's forces.
#include "coupling/opencl/device_grain_cells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "coupling/grain_fluid_coupling.h"
#include "dem/particles.h"
#include "lbm/backends.h"
#include "lbm/opencl/device_view.h"

namespace sabo::coupling {
namespace {

void expect_same_cells(CoverRule rule) {
    using lbm::FluidLattice;
    FluidLattice<double> l({30, 20, 24, {false, false, false}}, lbm::Rheology{});
    for (int z = 0; z < 24; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 30; ++x) l.set_fluid(x, y, z, 1.0, {});
    l.prepare();
    lbm::opencl::OpenClLattice<double> lattice(l, lbm::test_device());
    const double dx = 0.01;
    const LatticeFrame frame{{0.1, -0.02, 0.0}, dx, 30, 20, 24, l.index(0, 1, 0), l.index(0, 0, 1)};
    opencl::DeviceGrainCells device(lattice.view(), l.cell_types().size(), rule);
    GrainCellFinder host;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> along(-0.02, 0.32), across(-0.04, 0.2), up(-0.02, 0.26),
        radius(0.012, 0.035);
    std::vector<Vec3> x(80);
    std::vector<double> r(80);
    for (int round = 0; round < 2; ++round) {
        for (std::size_t g = 0; g < x.size(); ++g) {
            x[g] = {along(random), across(random), up(random)};
            r[g] = radius(random);
        }
        host.find(x, r, frame, rule);
        device.find(x, r, frame);
        const std::vector<CoveredCell> found = device.read_cells(frame);
        const std::vector<CoveredCell>& expected = host.cells();
        ASSERT_GT(expected.size(), 2000u);
        ASSERT_EQ(found.size(), expected.size()) << "round " << round;
        std::size_t differ = 0;
        double worst = 0.0;
        for (std::size_t c = 0; c < found.size(); ++c) {
            differ += found[c].cell != expected[c].cell || found[c].grain != expected[c].grain ? 1 : 0;
            worst = std::max(worst, std::abs(found[c].fraction - expected[c].fraction));
            ASSERT_EQ(found[c].centre.x, expected[c].centre.x);
        }
        EXPECT_EQ(differ, 0u) << "round " << round;
        EXPECT_LT(worst, 1e-13);  // the fractions' 89 columns summed in another order
    }
}

TEST(DeviceGrainCells, TheCellCentreRuleFindsTheHostsCells) {
    expect_same_cells(CoverRule::cell_centre);
}

TEST(DeviceGrainCells, PartialSaturationFindsTheHostsCellsAndFractions) {
    expect_same_cells(CoverRule::psm);
}

// The exchange on the device (the grains' cells covered there, the lattice's collision of covered cells,
// each grain's sums) gives the grains what GrainFluidCoupling gives them on the CPU — drag, torque and
// buoyancy, by both rules — for grains moving and spinning in sloshing water, some across its surface;
// every other step with the sums requested right after the collision.
void expect_exchange_as_on_the_cpu(CoverRule rule) {
    const double dx = 0.01, dt = 2e-3, rho_f = 1000.0;
    const lbm::UnitConverter u(dx, dt, rho_f);
    const auto box = [&] {
        lbm::Rheology rh;
        rh.tau = 0.6;
        auto l = std::make_unique<lbm::FluidLattice<double>>(
            lbm::GridShape{40, 12, 36, {false, false, false}}, rh);
        for (int z = 0; z < 36; ++z)
            for (int y = 0; y < 12; ++y)
                for (int x = 0; x < 40; ++x) {
                    const double top = 8.0 + 12.0 * x / 39.0 + 0.5, lambda = std::clamp(top - z, 0.0, 1.0);
                    if (lambda >= 1.0 && top - (z + 1) > 0.0)
                        l->set_fluid(x, y, z, 1.0, {});
                    else if (lambda > 0.0 || z == 0)
                        l->set_interface(x, y, z, 1.0, {}, lambda);
                }
        l->set_acceleration({0.0, 0.0, u.acceleration(-9.81)});
        l->prepare();
        return l;
    };
    const auto cpu = box(), on_device = box();
    CouplingSettings cs;
    cs.model = rule;
    cs.gravity = {0.0, 0.0, -9.81};
    GrainFluidCoupling coupling(cs, u, {});
    dem::Particles p;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> along(0.04, 0.36), up(0.03, 0.18), radius(0.018, 0.03),
        speed(-0.3, 0.3);
    for (int g = 0; g < 12; ++g) {
        p.add_mobile({along(random), 0.06, up(random)}, radius(random), 2500.0,
                     {speed(random), speed(random), speed(random)});
        p.w.back() = {10.0 * speed(random), 10.0 * speed(random), 10.0 * speed(random)};
    }
    lbm::opencl::OpenClLattice<double> device(
        *on_device, lbm::test_device(), false,
        rule == CoverRule::psm ? lbm::SolidExchange::psm : lbm::SolidExchange::drag);
    opencl::DeviceGrainCells cells(device.view(), on_device->cell_types().size(), rule);
    const LatticeFrame frame{{}, dx, 40, 12, 36, on_device->index(0, 1, 0), on_device->index(0, 0, 1)};
    const std::vector<Vec3> x(p.x.begin(), p.x.end()), v(p.v.begin(), p.v.end()), w(p.w.begin(), p.w.end());
    const std::vector<double> r(p.r.begin(), p.r.end());
    double worst_force = 0.0, worst_torque = 0.0, worst_buoyancy = 0.0, largest = 0.0, largest_torque = 0.0;
    for (int step = 0; step < 30; ++step) {
        coupling.before_fluid_step(p, *cpu);
        cpu->step();
        coupling.find_forces(*cpu);
        cells.find(x, r, frame);
        cells.cover(v, w, dt);
        if (step % 2 == 0)
            device.step();
        else  // the sums read back right after the collision, ahead of the free surface's passes (on a GPU)
            device.step(1, [&] { cells.request_sums(); });
        const auto& sums = cells.sums();
        for (std::size_t g = 0; g < x.size(); ++g) {
            const double volume = 4.0 / 3.0 * std::numbers::pi * r[g] * r[g] * r[g];
            const Vec3 buoyancy =
                cs.gravity * rho_f *
                (-sums.buoyancy_weight[g] * volume / cells_covered_alone(x[g], r[g], frame, rule));
            const Vec3 force = sums.force[g] * u.force_si(1.0) + buoyancy;
            worst_force = std::max(worst_force, norm(force - coupling.forces()[g]));
            worst_torque =
                std::max(worst_torque, norm(sums.torque[g] * u.force_si(1.0) - coupling.torques()[g]));
            worst_buoyancy = std::max(worst_buoyancy, norm(buoyancy - coupling.buoyancies()[g]));
            largest = std::max(largest, norm(coupling.forces()[g]));
            largest_torque = std::max(largest_torque, norm(coupling.torques()[g]));
        }
    }
    EXPECT_GT(largest, 0.5);  // N: the grains' weight in water is ~1 N
    EXPECT_LT(worst_force, 1e-11 * largest);
    EXPECT_LT(worst_buoyancy, 1e-11 * largest);
    EXPECT_LT(worst_torque, 1e-11 * largest_torque);
}

TEST(DeviceGrainCells, TheCellCentreExchangeGivesTheGrainsTheCpusForces) {
    expect_exchange_as_on_the_cpu(CoverRule::cell_centre);
}

TEST(DeviceGrainCells, ThePartiallySaturatedExchangeGivesTheGrainsTheCpusForces) {
    expect_exchange_as_on_the_cpu(CoverRule::psm);
}

}  // namespace
}  // namespace sabo::coupling
