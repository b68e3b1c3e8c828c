// SPDX-License-Identifier: MIT
// Free surface by mass tracking (CASES C6, LBM): a sloshing box conserves mass to round-off while
// cells fill and empty, fluid never touches gas; a column at rest under gravity has the hydrostatic
// density profile and no spurious currents. On both backends (tests/lbm/backends.h); the OpenCL lattice
// agrees with the CPU one.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"
#include "lbm/backends.h"
#include "lbm/fluid_lattice.h"
#include "lbm/fluid_summary.h"
#include "lbm/inlet.h"

namespace sabo::lbm {
namespace {

// Fills a closed box up to the surface height h(x) (cell centres at integer z; a cell spans
// [z − ½, z + ½]): fluid below, one interface cell with the partial fill, gas above.
template <class Real, class Height>
void fill_to(FluidLattice<Real>& l, Height h) {
    const auto& s = l.shape();
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                const double top = h(x) + 0.5;  // fill counted from the cell's bottom face
                const double lambda = std::clamp(top - z, 0.0, 1.0);
                const bool below_full = z == 0 || std::clamp(top - (z - 1), 0.0, 1.0) >= 1.0;
                if (lambda >= 1.0 && std::clamp(top - (z + 1), 0.0, 1.0) > 0.0)
                    l.set_fluid(x, y, z, 1.0, {});
                else if (below_full && (lambda > 0.0 || z == 0))
                    l.set_interface(x, y, z, 1.0, {}, lambda);
            }
    l.prepare();
}

template <class Real>
bool fluid_touches_gas(const FluidLattice<Real>& l) {
    const auto& s = l.shape();
    for (int z = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x) {
                if (l.type(l.index(x, y, z)) != CellType::fluid) continue;
                for (int i = 1; i < Q; ++i) {
                    const int a = x + cx[i], b = y + cy[i], c = z + cz[i];
                    if (a < 0 || b < 0 || c < 0 || a >= s.nx || b >= s.ny || c >= s.nz) continue;
                    if (l.type(l.index(a, b, c)) == CellType::gas) return true;
                }
            }
    return false;
}

class LbmSurface : public testing::TestWithParam<Backend> {};
SABO_ON_BOTH_BACKENDS(LbmSurface);

TEST_P(LbmSurface, SloshingBoxConservesMassToRoundOff) {
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({32, 3, 20, {false, true, false}}, rh);
    fill_to(l, [](int x) { return 5.0 + 6.0 * x / 31.0; });  // a tilted surface: the water sloshes
    l.set_acceleration({0.0, 0.0, -2e-4});
    const double m0 = l.total_mass();
    std::size_t conversions = 0;
    double worst = 0.0;
    Stepper<double> stepper(l, GetParam());
    for (int k = 1; k <= 3000; ++k) {
        stepper.run(1);
        conversions += l.surface_stats().filled + l.surface_stats().emptied;
        if (k % 500 == 0) {
            worst = std::max(worst, std::abs(l.total_mass() - m0) / m0);
            ASSERT_FALSE(fluid_touches_gas(l)) << "step " << k;
        }
    }
    std::printf("sloshing box: %zu conversions, worst relative mass drift %.3e in 3000 steps\n", conversions,
                worst);
    EXPECT_GT(conversions, 50u);  // the surface moved across cells
    EXPECT_LT(worst, 3e-10);      // ≤ 1e-10 per 1000 steps
    EXPECT_GT(l.interface_count(), 0u);
}

// The fluid's mass in the cells x ≥ x0 as the observers read it: λρ (a fluid cell's ρ, an interface cell's
// m).
template <class Real>
double mass_from(const FluidLattice<Real>& l, int x0) {
    FluidFields f;
    l.snapshot(f);
    double m = 0.0;
    for (int z = 0; z < f.nz; ++z)
        for (int y = 0; y < f.ny; ++y)
            for (int x = x0; x < f.nx; ++x) {
                const std::size_t k = f.cell(x, y, z);
                if (f.wet(k)) m += f.fill[k] * f.density[k];
            }
    return m;
}

// What enters a region is counted: in the sloshing box, the region x ≥ 16 gains what the links from x = 15
// carried (from z ≥ 6 and below) and what the surface's spreads brought it, to the excess that conversions
// next to its face hand across it (a cell away; not counted) — on the device as on the CPU.
TEST_P(LbmSurface, TheMassEnteringARegionIsCounted) {
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({32, 3, 20, {false, true, false}}, rh);
    fill_to(l, [](int x) { return 11.0 - 6.0 * x / 31.0; });  // high on the left: the water flows right
    l.set_acceleration({0.0, 0.0, -2e-4});
    const auto& s = l.shape();
    std::vector<std::uint8_t> image(static_cast<std::size_t>(s.cells())),
        stored(FluidLattice<double>::stored_cells(s));
    for (int z = 0, c = 0; z < s.nz; ++z)
        for (int y = 0; y < s.ny; ++y)
            for (int x = 0; x < s.nx; ++x, ++c) {
                image[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(
                    (x >= 16 ? region_downstream : 0) | (z >= 6 ? region_above_crest : 0));
                stored[l.index(x, y, z)] = image[static_cast<std::size_t>(c)];
            }
    l.set_region(stored);
    EXPECT_EQ(l.crossings().size(), 5u * 3u * 20u - 2u * 3u);  // 5 links a cell (not through the bed or lid)
    const double behind0 = mass_from(l, 16);
    Stepper<double> stepper(l, GetParam());
    if (stepper.device) stepper.device->set_region(image);
    double worst = 0.0;
    for (int k = 1; k <= 12; ++k) {
        stepper.run(50);
        const auto& in = l.region_inflow();
        worst = std::max(worst, std::abs(mass_from(l, 16) - behind0 - (in[0] + in[1] + in[2])));
    }
    const auto& in = l.region_inflow();
    std::printf(
        "600 steps: %.6f entered over z = 6, %.6f below, %.6f by the spreads; largest difference "
        "from the region's gain %.3e\n",
        in[0], in[1], in[2], worst);
    EXPECT_GT(in[0], 10.0);  // the flow crossed above and below, and the spreads brought some
    EXPECT_GT(in[1], 10.0);
    EXPECT_GT(in[2], 0.5);
    EXPECT_LT(worst, 1e-11 * behind0);  // round-off (no excess was handed across the face in this flow)
}

TEST_P(LbmSurface, HydrostaticColumnAtRest) {
    Rheology rh;
    rh.tau = 1.0;  // acoustic waves of the start decay within a few thousand steps
    const double g = 1e-4, h = 15.3;
    FluidLattice<double> l({4, 4, 24, {true, true, false}}, rh);
    fill_to(l, [&](int) { return h; });
    l.set_acceleration({0.0, 0.0, -g});
    const double m0 = l.total_mass();
    Stepper<double>(l, GetParam()).run(6000);
    // density along the column: dρ/dz = −3 g ρ (p = ρ/3), ρ → ρ_A = 1 at the surface
    double u_max = 0.0, slope_err = 0.0;
    for (int z = 1; z < 14; ++z) {
        double r0 = 0.0, r1 = 0.0;
        Vec3 u0, u1;
        l.moments(l.index(1, 2, z), r0, u0);
        l.moments(l.index(1, 2, z + 1), r1, u1);
        u_max = std::max(u_max, norm(u0));
        slope_err = std::max(slope_err, std::abs((r1 - r0) / (-3.0 * g * 0.5 * (r0 + r1)) - 1.0));
    }
    double r_top = 0.0;
    Vec3 u_top;
    l.moments(l.index(1, 2, 14), r_top, u_top);  // the last fluid cell, ~0.8 below the surface
    std::printf("hydrostatic column: slope error %.2e, max |u| %.2e, rho below the surface %.6f\n", slope_err,
                u_max, r_top);
    EXPECT_LT(slope_err, 0.01);
    EXPECT_NEAR(r_top, 1.0 + 3.0 * g * (h - 14.0), 3.0 * g * 0.5);  // within half a cell of the surface
    EXPECT_LT(u_max, 1e-3 * std::sqrt(g * h));  // spurious currents: a thousandth of the gravity-wave speed
    EXPECT_NEAR(l.total_mass(), m0, 1e-10 * m0);
    // the column is uniform across x and y: no lateral currents anywhere, the surface cells included (the
    // cells at the ends of a row take a different code path and round differently; a reconstruction that
    // flipped on the round-off of the normal grew 6e-5 out of that)
    double lateral = 0.0;
    for (std::size_t k = 0; k < l.stored_cells(l.shape()); ++k) {
        if (l.type(k) != CellType::fluid && l.type(k) != CellType::interface) continue;
        double rho = 0.0;
        Vec3 u;
        l.moments(k, rho, u);
        lateral = std::max(lateral, std::hypot(u.x, u.y));
    }
    EXPECT_LT(lateral, 1e-12);
}

// A Bingham film down an incline (periodic along and across the slope, the bed a wall half a cell below the
// first cells, a free surface on top): the open channel's uniform flow of a wide channel. In steady uniform
// flow the shear stress at height s is the weight of what lies above. The lattice forces every wet cell as
// a full one — the interface cell too, whatever its fill (the free surface's mass is bookkeeping; its
// populations carry a whole cell's density) — so the film is driven as if D deep, D the count of its wet
// cells: half a cell more than its mass on average (docs/lbm.md, "The free surface's depth"); a Newtonian
// film of 20.5 cells by mass runs 4.6 % faster than one of that depth would, 0.1 % from one of D = 21. With
// that, τ(s) = ρ g sin θ (D − s). The lattice's law is η = ν_p + τ0/γ̇ capped at η_max = (τ_max − ½)/3, so
// the strain rate is (τ − τ0)/ν_p above τ_c = η_max τ0/(η_max − ν_p) and τ/η_max below it (the plug shears a
// little). Integrated from the bed: the exact profile of the lattice's law, against which the film's
// velocities are compared at every fluid cell's centre.
TEST_P(LbmSurface, BinghamFilmDownAnInclineHasTheLawsUniformProfile) {
    Rheology rh;
    rh.bingham = true;
    rh.nu_plastic = 0.02;  // τ = 0.56; ν_max = 0.433 = 22 ν_p
    const double theta = 35.0 * 3.141592653589793 / 180.0;
    const double depth = 20.5, yield_height = 14.0, u_plug = 0.02;  // (the film's nominal depth and yield)
    const double ax = u_plug * 2.0 * rh.nu_plastic / (yield_height * yield_height);
    rh.yield = ax * (depth - yield_height);
    FluidLattice<double> l({4, 4, 32, {true, true, false}}, rh);
    // (fill_to's height is the surface's above the first cell's centre)
    fill_to(l, [&](int) { return depth - 0.5; });
    l.set_acceleration({ax, 0.0, -ax / std::tan(theta)});
    const double m0 = l.total_mass();
    Stepper<double>(l, GetParam()).run(120000);  // ~6 viscous times D²/ν_p
    double d = 0.0, mass = 0.0;  // the film's wet cells, and its depth by its cells' fill fractions
    for (int z = 0; z < l.shape().nz; ++z) {
        const std::size_t k = l.index(1, 2, z);
        d += l.type(k) == CellType::fluid || l.type(k) == CellType::interface ? 1.0 : 0.0;
        mass += l.type(k) == CellType::fluid ? 1.0 : (l.type(k) == CellType::interface ? l.fill(k) : 0.0);
    }
    const double eta_max = (rh.tau_max - 0.5) / 3.0;
    const double tau_c = eta_max * rh.yield / (eta_max - rh.nu_plastic);
    const auto shear = [&](double s) {
        const double stress = ax * (d - s);
        return stress > tau_c ? (stress - rh.yield) / rh.nu_plastic : stress / eta_max;
    };
    // u(s) = ∫₀^s γ̇: Simpson's rule on fine steps
    const auto exact = [&](double s) {
        const int n = 2000;
        const double h = s / n;
        double sum = shear(0.0) + shear(s);
        for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * shear(i * h);
        return sum * h / 3.0;
    };
    double worst = 0.0, lateral = 0.0, top = 0.0;
    int cells = 0;
    for (int z = 0; z < l.shape().nz; ++z) {
        const std::size_t k = l.index(1, 2, z);
        if (l.type(k) != CellType::fluid) continue;
        double rho = 0.0;
        Vec3 u;
        l.moments(k, rho, u);
        worst = std::max(worst, std::abs(u.x - exact(z + 0.5)) / exact(d));
        lateral = std::max(lateral, std::hypot(u.y, u.z));
        top = u.x;
        ++cells;
    }
    std::printf(
        "Bingham film: %.0f wet cells (%.4f by mass), %d fluid cells, top speed %.5f (exact %.5f), "
        "worst %.2e of the surface speed\n",
        d, mass, cells, top, exact(cells - 0.5), worst);
    EXPECT_GE(cells, 18);
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(lateral, 1e-6 * exact(d));
    EXPECT_NEAR(l.total_mass(), m0, 1e-10 * m0);
}

// A half-full interface cell inside the fluid (no gas neighbour: what a closing gas pocket leaves)
// becomes a fluid cell at the next step, its missing mass taken from the free surface: the total is
// conserved and the cell does not run away (before this rule the gas-side reconstruction pushed such
// cells toward an atmosphere that was not there, by (ρ − ρ_A)/3 per step).
TEST_P(LbmSurface, InterfaceCellWithoutGasBecomesFluid) {
    Rheology rh;
    rh.tau = 0.8;
    FluidLattice<double> l({10, 10, 16, {true, true, false}}, rh);
    fill_to(l, [](int) { return 10.3; });
    l.set_interface(5, 5, 4, 1.0, {}, 0.5);
    l.prepare();
    const std::size_t trapped = l.index(5, 5, 4);
    ASSERT_EQ(l.type(trapped), CellType::interface);
    l.set_acceleration({0.0, 0.0, -1e-5});
    const double m0 = l.total_mass();
    Stepper<double> stepper(l, GetParam());
    stepper.run(1);
    EXPECT_EQ(l.type(trapped), CellType::fluid);
    stepper.run(200);
    EXPECT_NEAR(l.total_mass(), m0, 1e-12 * m0);
    double rho = 0.0;
    Vec3 u;
    l.moments(trapped, rho, u);
    EXPECT_LT(norm(u), 1e-3);
}

// With a pocket reach (FluidLattice::set_pocket_reach), the deficit of an enclosed cell that fills is taken
// in equal shares from the interface cells within that many steps of it through the fluid, not from the
// whole surface: against the same step with the whole surface, the 13 surface cells two steps above it
// (D3Q19: the links (0,0,1), (±1,0,1), (0,±1,1) twice) lose the deficit in equal parts, the other 87 of the
// surface layer keep the whole surface's share; the mass is kept. Without a cell in reach the whole surface
// gives it, as before. (CPU lattice: the OpenCL one refuses the key.)
TEST_P(LbmSurface, AnEnclosedCellsDeficitComesFromTheSurfaceWithinItsReach) {
    const auto step_once = [](int reach) {
        Rheology rh;
        rh.tau = 0.8;
        auto l = std::make_unique<FluidLattice<double>>(GridShape{10, 10, 16, {true, true, false}}, rh);
        fill_to(*l, [](int) { return 10.3; });    // the surface layer at z = 10 (λ = 0.8)
        l->set_interface(5, 5, 8, 1.0, {}, 0.5);  // two cells under it
        l->prepare();
        l->set_pocket_reach(reach);
        const double m0 = l->total_mass();
        Stepper<double>(*l, GetParam()).run(1);
        EXPECT_EQ(l->type(l->index(5, 5, 8)), CellType::fluid);
        EXPECT_EQ(l->surface_stats().pocket_cells, reach >= 2 ? 1u : 0u);
        EXPECT_NEAR(l->total_mass(), m0, 1e-13 * m0);
        return l;
    };
    const auto whole = step_once(0), near = step_once(2);
    int nearby = 0;
    double taken = 0.0, kept = 0.0, total = 0.0;
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) {
            const std::size_t k = near->index(x, y, 10);
            ASSERT_EQ(near->type(k), CellType::interface);
            const double d = near->fill(k) - whole->fill(k);  // (the same ρ in both)
            total += d;
            const int dx = std::abs(x - 5), dy = std::abs(y - 5);
            if (dx + dy <= 2 && !(dx == 2 && dy == 2)) {  // within two (0|±1, 0|±1, 1) links
                ++nearby;
                if (nearby == 1) taken = d;
                EXPECT_NEAR(d, taken, 1e-15);
                EXPECT_LT(d, -1e-3);
            } else {
                if (kept == 0.0) kept = d;
                EXPECT_NEAR(d, kept, 1e-15);
                EXPECT_GT(d, 1e-5);  // the whole surface's share, not taken from them here
            }
        }
    EXPECT_EQ(nearby, 13);
    EXPECT_NEAR(total, 0.0, 1e-13);
    // out of reach of the surface (one step), the whole surface gives it
    const auto short_reach = step_once(1);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) {
            const std::size_t k = short_reach->index(x, y, 10);
            EXPECT_EQ(short_reach->fill(k), whole->fill(k));
        }
    EXPECT_THROW(whole->set_pocket_reach(9), InputError);
}

// A drop (an interface cell with no fluid neighbour) flying above the pool empties at the next step, its
// mass given to the surface: kept, its populations would all come from the gas-side reconstruction with
// its own velocity, and gravity would accelerate it without bound (a coarse C5 run blew up in spray).
TEST_P(LbmSurface, DropWithoutFluidNeighbourEmptiesIntoTheSurface) {
    Rheology rh;
    rh.tau = 0.8;
    FluidLattice<double> l({10, 10, 16, {true, true, false}}, rh);
    fill_to(l, [](int) { return 6.3; });
    l.set_interface(5, 5, 12, 1.0, {0.05, 0.0, 0.0}, 0.6);
    l.prepare();
    const std::size_t drop = l.index(5, 5, 12);
    ASSERT_EQ(l.type(drop), CellType::interface);
    l.set_acceleration({0.0, 0.0, -1e-4});
    const double m0 = l.total_mass();
    Stepper<double> stepper(l, GetParam());
    stepper.run(1);
    EXPECT_EQ(l.type(drop), CellType::gas);
    EXPECT_GE(l.surface_stats().emptied, 1u);
    EXPECT_NEAR(l.total_mass(), m0, 1e-12 * m0);
    stepper.run(1000);
    EXPECT_NEAR(l.total_mass(), m0, 1e-12 * m0);
    EXPECT_LT(l.totals().max_speed, 0.02);
}

// Per stored cell: its type, fill fraction, density, u_x and u_z (0 where it is not wet).
std::vector<double> cell_states(const FluidLattice<double>& l) {
    std::vector<double> out;
    for (std::size_t k = 0; k < l.stored_cells(l.shape()); ++k) {
        double rho = 0.0;
        Vec3 u;
        if (l.type(k) == CellType::fluid || l.type(k) == CellType::interface) l.moments(k, rho, u);
        out.insert(out.end(), {static_cast<double>(l.type(k)), l.fill(k), rho, u.x, u.z});
    }
    return out;
}

// How many cells of two cell_states() differ in type, and the largest difference of their other fields.
std::pair<std::size_t, double> compare_states(const std::vector<double>& a, const std::vector<double>& b) {
    std::size_t types_differ = 0;
    double worst = 0.0;
    for (std::size_t k = 0; k < a.size(); k += 5) {
        types_differ += a[k] != b[k] ? 1 : 0;
        for (std::size_t c = 1; c < 5; ++c) worst = std::max(worst, std::abs(a[k + c] - b[k + c]));
    }
    return {types_differ, worst};
}

// The free surface's passes run in ascending cell order and the sweep's results do not depend on the
// team: 1 and 2 threads give the same bits (a lattice large enough for a team).
std::vector<double> sloshing_state(int threads, Backend backend = Backend::cpu, int steps = 301) {
    omp_set_num_threads(threads);
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({40, 12, 36, {false, false, false}}, rh);
    fill_to(l, [](int x) { return 8.0 + 12.0 * x / 39.0; });
    l.set_acceleration({0.0, 0.0, -2e-4});
    Stepper<double>(l, backend).run(steps);
    std::vector<double> out = cell_states(l);
    omp_set_num_threads(omp_get_num_procs());
    return out;
}

TEST(LbmFreeSurface, OneAndTwoThreadsGiveIdenticalBits) {
    const auto one = sloshing_state(1), two = sloshing_state(2);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
}

// A lattice built in another's memory (a divided run's face moves, FluidLattice's storage constructor)
// starts as a fresh one — nothing of the other's state shows through — sloshes as it does bit for bit, and
// takes the other's arrays where they are large enough.
TEST(LbmFreeSurface, ALatticeBuiltInAnothersMemorySloshesAsAFreshOne) {
    Rheology rh;
    rh.tau = 0.6;
    const auto slosh = [](FluidLattice<double>& l) {
        fill_to(l, [](int x) { return 8.0 + 12.0 * x / 39.0; });
        l.set_acceleration({0.0, 0.0, -2e-4});
        for (int k = 0; k < 151; ++k) l.step();
        std::vector<double> out;
        for (std::size_t k = 0; k < l.stored_cells(l.shape()); ++k) {
            double rho = 0.0;
            Vec3 u;
            if (l.type(k) == CellType::fluid || l.type(k) == CellType::interface) l.moments(k, rho, u);
            out.insert(out.end(), {static_cast<double>(l.type(k)), l.fill(k), l.tau(k), rho, u.x, u.z});
        }
        return out;
    };
    const GridShape shape{40, 12, 36, {false, false, false}};
    FluidLattice<double> used({44, 12, 36, {false, false, false}}, rh);  // larger: its arrays hold `shape`
    slosh(used);
    const double* memory = used.population_slots(0).data();
    FluidLattice<double> fresh(shape, rh), reused(shape, rh, std::move(used));
    EXPECT_EQ(reused.population_slots(0).data(), memory);
    const std::vector<double> a = slosh(fresh), b = slosh(reused);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

// A plane holding much of the free surface is swept in blocks of rows: its cells get what they get when the
// plane is one work item. Water sloshing in x and z, uniform across a periodic y: a lattice 64 cells wide
// (planes of ~1300 interface cells, split) against one 4 wide (not split, one thread) cell by cell, and the
// wide one on 1 and 3 threads bit for bit. (Not bitwise across widths: the excess mass of cells with no
// interface neighbour is spread over the whole surface, summed in another order.)
struct SlicedSloshing {
    std::vector<double> cells;     // per cell of the x-z slice at y = 0: type, fill, rho, u.x, u.z
    std::size_t widest_plane = 0;  // the most interface cells one z-plane held at the last step
};
SlicedSloshing sliced_sloshing(int ny, int threads, int y) {
    omp_set_num_threads(threads);
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({40, ny, 24, {false, true, false}}, rh);
    fill_to(l, [](int x) { return 8.0 + 1.5 * x / 39.0; });
    l.set_acceleration({0.0, 0.0, -2e-4});
    for (int k = 0; k < 120; ++k) l.step();
    SlicedSloshing out;
    const auto& s = l.shape();
    std::vector<std::size_t> per_plane(static_cast<std::size_t>(s.nz), 0);
    for (int z = 0; z < s.nz; ++z)
        for (int x = 0; x < s.nx; ++x) {
            for (int b = 0; b < s.ny; ++b)
                if (l.type(l.index(x, b, z)) == CellType::interface) ++per_plane[static_cast<std::size_t>(z)];
            const std::size_t k = l.index(x, y, z);
            double rho = 0.0;
            Vec3 u;
            if (l.type(k) == CellType::fluid || l.type(k) == CellType::interface) l.moments(k, rho, u);
            out.cells.insert(out.cells.end(), {static_cast<double>(l.type(k)), l.fill(k), rho, u.x, u.z});
        }
    out.widest_plane = *std::max_element(per_plane.begin(), per_plane.end());
    omp_set_num_threads(omp_get_num_procs());
    return out;
}

TEST(LbmFreeSurface, APlaneHoldingMuchOfTheSurfaceIsSweptInBlocksWithTheSameResults) {
    const SlicedSloshing narrow = sliced_sloshing(4, 1, 0);
    const SlicedSloshing wide = sliced_sloshing(64, 1, 37), wide3 = sliced_sloshing(64, 3, 37);
    ASSERT_LT(narrow.widest_plane, FluidLattice<double>::split_plane_interface_cells);
    ASSERT_GE(wide.widest_plane, FluidLattice<double>::split_plane_interface_cells);  // split
    ASSERT_EQ(wide.cells.size(), narrow.cells.size());
    double worst = 0.0;
    for (std::size_t a = 0; a < wide.cells.size(); ++a)
        worst = std::max(worst, std::abs(wide.cells[a] - narrow.cells[a]));
    std::printf("sloshing slice, 64 wide (split planes) against 4 wide: largest difference %.2e\n", worst);
    EXPECT_LT(worst, 1e-12);
    EXPECT_EQ(std::memcmp(wide.cells.data(), wide3.cells.data(), wide.cells.size() * sizeof(double)), 0);
}

// The OpenCL lattice's free surface against the CPU's: the same cells fill and empty, the same fields to
// round-off (float64: the two add the excess mass of converted cells in different orders), and the
// device's runs are identical bit for bit.
TEST(LbmOpenCl, SloshingAgreesWithTheCpuLattice) {
    const auto cpu = sloshing_state(2), device = sloshing_state(2, Backend::opencl);
    ASSERT_EQ(cpu.size(), device.size());
    const auto [types_differ, worst] = compare_states(cpu, device);
    std::printf("sloshing 301 steps, OpenCL vs CPU: %zu cell types differ, largest field difference %.3e\n",
                types_differ, worst);
    EXPECT_EQ(types_differ, 0u);
    EXPECT_LT(worst, 1e-11);
    const auto again = sloshing_state(2, Backend::opencl);
    EXPECT_EQ(std::memcmp(device.data(), again.data(), device.size() * sizeof(double)), 0);
}

// A closed pocket's deficit taken near it (FluidLattice::set_pocket_reach) on the device as on the CPU: a
// column falling with a bubble in it (the bubble closes, the splash closes more) and a periodic axis
// narrower than the search's box; the same cells fill and empty, the same pockets take their deficit near
// them, the same fields to round-off, and the device's runs are identical bit for bit.
std::vector<double> falling_bubble(Backend backend, std::size_t& pocket_cells) {
    Rheology rh;
    rh.tau = 0.6;
    FluidLattice<double> l({42, 5, 18, {false, true, false}}, rh);
    for (int z = 0; z < 18; ++z)
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 15; ++x) {
                const bool bubble = (x == 13 || x == 14) && y >= 1 && y <= 3 && z >= 4 && z <= 6;
                if (z < 13 + y / 2 && !bubble) l.set_fluid(x, y, z, 1.0, {});
            }
    l.set_acceleration({0.0, 0.0, -4e-4});
    l.set_pocket_reach(3);
    l.prepare();
    Stepper<double> stepper(l, backend);
    pocket_cells = 0;
    for (int s = 0; s < 300; ++s) {
        stepper.run(1);
        pocket_cells += l.surface_stats().pocket_cells;
    }
    return cell_states(l);
}

TEST(LbmOpenCl, APocketsDeficitTakenNearItAgreesWithTheCpuLattice) {
    std::size_t on_cpu = 0, on_device = 0, again_cells = 0;
    const auto cpu = falling_bubble(Backend::cpu, on_cpu),
               device = falling_bubble(Backend::opencl, on_device);
    ASSERT_EQ(cpu.size(), device.size());
    const auto [types_differ, worst] = compare_states(cpu, device);
    std::printf(
        "falling bubble 300 steps, pocket reach 3, OpenCL vs CPU: %zu / %zu pocket cells spread near "
        "them, %zu cell types differ, largest field difference %.3e\n",
        on_device, on_cpu, types_differ, worst);
    EXPECT_GT(on_cpu, 10u);
    EXPECT_EQ(on_device, on_cpu);
    EXPECT_EQ(types_differ, 0u);
    EXPECT_LT(worst, 1e-11);
    const auto again = falling_bubble(Backend::opencl, again_cells);
    EXPECT_EQ(std::memcmp(device.data(), again.data(), device.size() * sizeof(double)), 0);
}

// An inflow boundary's held cells (lbm/inlet.h) on the device as on the CPU: a box filling through its first
// plane (the held layers 0–5 at u = 0.05, the top one filled to ρ), 400 steps; the mass each step added and
// the fields at the end agree to round-off.
TEST(LbmOpenCl, TheInletHoldsItsCellsAsOnTheCpu) {
    const auto run = [](Backend backend, std::vector<double>& added) {
        Rheology rh;
        rh.tau = 0.6;
        auto l = std::make_unique<FluidLattice<double>>(GridShape{30, 6, 20, {false, false, false}}, rh);
        fill_to(*l, [](int) { return 1.0; });
        l->set_acceleration({0.0, 0.0, -2e-4});
        std::vector<InletCell> cells;
        for (int z = 0; z < 6; ++z)
            for (int y = 0; y < 6; ++y) cells.push_back({0, y, z, z == 5, 1.0 + 6e-4 * (5.5 - z)});
        Stepper<double> stepper(*l, backend);
        for (int k = 0; k < 400; ++k) {
            if (stepper.device) {
                stepper.device->step(1);
                added.push_back(stepper.device->hold_inlet(cells, {0.05, 0.0, 0.0}));
            } else {
                l->step();
                added.push_back(hold_inlet(*l, std::span<const InletCell>(cells), Vec3{0.05, 0.0, 0.0}));
            }
        }
        if (stepper.device) stepper.device->pull();
        return l;
    };
    std::vector<double> on_cpu, on_device;
    const auto cpu = run(Backend::cpu, on_cpu), device = run(Backend::opencl, on_device);
    double worst_added = 0.0, worst_field = 0.0, total = 0.0;
    std::size_t first = 0;
    for (std::size_t k = 0; k < on_cpu.size(); ++k) {
        total += on_cpu[k];
        const double d = std::abs(on_cpu[k] - on_device[k]);
        if (d > 1e-12 && first == 0) first = k + 1;
        worst_added = std::max(worst_added, d);
    }
    std::size_t types_differ = 0;
    for (std::size_t k = 0; k < cpu->stored_cells(cpu->shape()); ++k) {
        types_differ += cpu->type(k) != device->type(k) ? 1 : 0;
        worst_field = std::max(worst_field, std::abs(cpu->fill(k) - device->fill(k)));
    }
    std::printf(
        "inlet 400 steps: %.4f added; largest difference per step %.3e (first above 1e-12 at step %zu), "
        "%zu cell types differ, largest fill difference %.3e\n",
        total, worst_added, first, types_differ, worst_field);
    EXPECT_GT(total, 5.0);  // the box filled through its inlet
    EXPECT_LT(worst_added, 1e-10);
    EXPECT_EQ(types_differ, 0u);
    EXPECT_LT(worst_field, 1e-10);
}

// A closed box whose water surface is tilted (it sloshes under gravity): the device tests' state.
std::unique_ptr<FluidLattice<double>> tilted_box() {
    Rheology rh;
    rh.tau = 0.6;
    auto l = std::make_unique<FluidLattice<double>>(GridShape{40, 12, 36, {false, false, false}}, rh);
    fill_to(*l, [](int x) { return 8.0 + 12.0 * x / 39.0; });
    l->set_acceleration({0.0, 0.0, -2e-4});
    return l;
}

// A slab's ghost planes cross through the host (parallel/device_halo.h): planes packed on one device and
// unpacked on another carry their whole state there — populations, τ, cell types, λ, masses and the
// interface cells' surface state — after an odd step (the populations in the neighbours' slots) as after an
// even one.
TEST(LbmOpenCl, PlanesPackedOnOneDeviceAndUnpackedOnAnotherCarryTheirWholeState) {
    for (const std::uint64_t steps : {151, 152}) {
        const auto a = tilted_box(), b = tilted_box();
        b->set_acceleration({1e-5, 0.0, -2.5e-4});  // (another flow: b's planes differ before)
        opencl::OpenClLattice<double> from(*a, test_device()), into(*b, test_device());
        from.step(steps);
        into.step(steps);
        const int x0 = 12, planes = 4;
        std::vector<std::byte> message(from.packed_bytes(planes));
        from.pack_planes(x0, planes, message);
        from.wait();
        into.unpack_planes(x0, planes, message);
        from.pull();
        into.pull();
        std::size_t differ = 0, cells = 0;
        const auto fa = a->populations(), fb = b->populations();
        for (int z = 0; z < 36; ++z)
            for (int y = 0; y < 12; ++y)
                for (int x = x0; x < x0 + planes; ++x, ++cells) {
                    const std::size_t k = a->index(x, y, z);
                    differ += a->cell_types()[k] != b->cell_types()[k] || a->fill(k) != b->fill(k) ||
                                      a->masses()[k] != b->masses()[k] || a->tau(k) != b->tau(k)
                                  ? 1
                                  : 0;
                    for (int i = 0; i < Q; ++i) {
                        const std::size_t at = static_cast<std::size_t>(i) * a->slot_stride() + k;
                        differ += fa[at] != fb[at] ? 1 : 0;
                    }
                }
        std::vector<double> surface_a, surface_b;
        a->pack_surface(x0, planes, surface_a);
        b->pack_surface(x0, planes, surface_b);
        EXPECT_EQ(differ, 0u) << steps << " steps, " << cells << " cells";
        EXPECT_FALSE(surface_a.empty()) << "the planes must hold interface cells";
        EXPECT_EQ(surface_a, surface_b) << steps << " steps";
    }
}

// What observers read of a device's fluid (OpenClLattice::snapshot: the fields computed there, a few bytes a
// cell copied back) is what the host lattice's snapshot gives once the whole state is copied back.
TEST(LbmOpenCl, TheDevicesSnapshotIsTheHostLatticesAfterAPull) {
    const auto lattice = tilted_box();
    FluidLattice<double>& l = *lattice;
    opencl::OpenClLattice<double> device(l, test_device());
    device.step(301);
    FluidFields on_device, on_host;
    device.snapshot(on_device);
    device.pull();
    l.snapshot(on_host);
    ASSERT_EQ(on_device.cells(), on_host.cells());
    EXPECT_EQ(on_device.type, on_host.type);
    EXPECT_EQ(on_device.fill, on_host.fill);
    EXPECT_EQ(on_device.tau, on_host.tau);
    double worst = 0.0;
    for (std::size_t c = 0; c < on_host.cells(); ++c) {
        worst = std::max(worst, std::abs(on_device.density[c] - on_host.density[c]));
        worst = std::max(worst, norm(on_device.velocity[c] - on_host.velocity[c]));
    }
    EXPECT_LT(worst, 1e-14);  // the same state; ρ and u summed in another order
    EXPECT_NEAR(on_device.totals.mass, on_host.totals.mass, 1e-13 * on_host.totals.mass);
    EXPECT_NEAR(on_device.totals.max_speed, on_host.totals.max_speed, 1e-14);
    EXPECT_EQ(on_device.interface_cells, on_host.interface_cells);
    EXPECT_EQ(on_device.clamps.at_max, on_host.clamps.at_max);
    EXPECT_EQ(on_device.drained, on_host.drained);
}

// A series row's sums made on the device (OpenClLattice::summary) are those the CPU sums from the same
// state's snapshot (lbm::summarize), the region's included; a section's planes are those planes of the
// whole snapshot.
TEST(LbmOpenCl, TheDevicesSummaryAndSectionsAreTheHostsOfTheSameState) {
    const auto lattice = tilted_box();
    FluidLattice<double>& l = *lattice;
    opencl::OpenClLattice<double> device(l, test_device());
    const auto behind = [](int x, int, int z) -> std::uint8_t { return x >= 25 && z < 20 ? 1 : 0; };
    std::vector<std::uint8_t> region(40 * 12 * 36);
    for (int z = 0, c = 0; z < 36; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 40; ++x, ++c) region[static_cast<std::size_t>(c)] = behind(x, y, z);
    device.set_region(region);
    device.step(301);
    const FluidSummary made = device.summary();
    FluidFields whole;
    device.snapshot(whole);
    const FluidSummary summed = summarize(whole, behind);
    EXPECT_GT(summed.region_mass, 0.0);
    EXPECT_LT(summed.region_mass, 0.5 * summed.free_mass);
    EXPECT_NEAR(made.totals.mass, summed.totals.mass, 1e-13 * summed.totals.mass);  // (other order)
    EXPECT_NEAR(made.free_mass, summed.free_mass, 1e-13 * summed.free_mass);
    EXPECT_NEAR(made.region_mass, summed.region_mass, 1e-13 * summed.free_mass);
    EXPECT_EQ(made.totals.max_speed, summed.totals.max_speed);
    EXPECT_EQ(made.interface_cells, summed.interface_cells);
    EXPECT_EQ(made.front_x, summed.front_x);
    EXPECT_EQ(made.top_z, summed.top_z);
    EXPECT_EQ(made.nz, 36);
    FluidFields section;
    device.snapshot(section, 17, 23);
    ASSERT_EQ(section.nx, 6);
    EXPECT_EQ(section.first_x, 17);
    for (int z = 0; z < 36; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 6; ++x) {
                const std::size_t a = section.cell(x, y, z), b = whole.cell(17 + x, y, z);
                ASSERT_EQ(section.type[a], whole.type[b]);
                ASSERT_EQ(section.fill[a], whole.fill[b]);
                ASSERT_EQ(section.density[a], whole.density[b]);
                ASSERT_EQ(section.velocity[a].x, whole.velocity[b].x);
            }
}

// Cells covered by a moving solid (the coupling's grains) exchange momentum on the device as on the CPU, by
// the drag and by the partially saturated collision: a ball of cells moving through a periodic box of fluid
// and through the tilted box's sloshing water and its surface (interface cells weighted by λ, their recorded
// velocity with the drag's force; gas cells exchange nothing), the cells set anew every step as the
// coupling does.
std::unique_ptr<FluidLattice<double>> full_box() {
    Rheology rh;
    rh.tau = 0.6;
    auto l = std::make_unique<FluidLattice<double>>(GridShape{40, 12, 36, {true, true, true}}, rh);
    for (int z = 0; z < 36; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 40; ++x) l->set_fluid(x, y, z, 1.0, {});
    l->set_acceleration({1e-5, 0.0, -2e-5});
    l->prepare();
    return l;
}

void expect_solids_as_on_the_cpu(SolidExchange exchange, bool surface = true) {
    const auto cpu = surface ? tilted_box() : full_box(), on_device = surface ? tilted_box() : full_box();
    opencl::OpenClLattice<double> device(*on_device, test_device(), false, exchange);
    std::vector<SolidCell> ball;
    for (int z = 0; z < 36; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 40; ++x) {
                const double d = std::hypot(x - 20.0, y - 6.0, z - 14.0);
                if (d < 5.5)
                    ball.push_back({cpu->index(x, y, z), {0.02, -0.005, 0.01}, std::min(1.0, 5.5 - d)});
            }
    std::sort(ball.begin(), ball.end(),
              [](const SolidCell& a, const SolidCell& b) { return a.cell < b.cell; });
    double worst_force = 0.0, largest = 0.0;
    for (int step = 0; step < 60; ++step) {
        cpu->set_solid_cells(ball, exchange);
        device.set_solid_cells(ball);
        cpu->step();
        device.step();
        const std::vector<Vec3> on_gpu = device.solid_cell_forces();
        const std::vector<Vec3>& expected = cpu->solid_cell_forces();
        ASSERT_EQ(on_gpu.size(), expected.size());
        for (std::size_t g = 0; g < expected.size(); ++g) {
            worst_force = std::max(worst_force, norm(on_gpu[g] - expected[g]));
            largest = std::max(largest, norm(expected[g]));
        }
    }
    EXPECT_GT(largest, 1e-4);
    EXPECT_LT(worst_force, 1e-12 * largest);
    device.pull();
    const auto a = cpu->populations(), b = on_device->populations();
    double worst = 0.0;
    for (std::size_t c = 0; c < a.size(); ++c) worst = std::max(worst, std::abs(a[c] - b[c]));
    EXPECT_LT(worst, 1e-13);
}

TEST(LbmOpenCl, CellsCoveredBySolidsDragAsOnTheCpu) {
    expect_solids_as_on_the_cpu(SolidExchange::drag, false);
    expect_solids_as_on_the_cpu(SolidExchange::drag);
}

TEST(LbmOpenCl, CellsCoveredBySolidsPartiallySaturatedAsOnTheCpu) {
    expect_solids_as_on_the_cpu(SolidExchange::psm);
}

}  // namespace
}  // namespace sabo::lbm
