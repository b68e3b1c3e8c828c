// SPDX-License-Identifier: MIT
// Grains divided into slabs along x, run on 1, 2 and 3 processes (`mpiexec -n N`; ctest grain_slabs_*): a
// block of polydisperse grains with rolling resistance slides down a steep channel, across the slab faces
// (which move to follow the grains), into a row of fixed spheres (a barrier) and the end wall. Each rank runs
// the undivided reference too and, every `compare_every` steps, compares its own grains and the contacts it
// evaluates with the reference's same grains and contacts (by global id): positions, velocities, the
// tangential springs and rolling torques of every live contact, the wall forces summed over the ranks, and
// the grain count.
//
// The divided run adds the same forces in another order (a contact across a face reaches its second grain
// as a reaction from the neighbour), so it follows the reference to round-off only as long as the flow
// does not amplify round-off. The yardstick is measured, not guessed: a second reference whose grains are
// moved by 1e-15 m (round-off of a position) runs alongside, and the divided run may differ from the
// reference by at most `allowed_ratio` times as much as that one does (plus 1e-12 of a radius). A contact
// history lost in a migration or a reaction sent to the wrong grain shows up at once: a spring of 1e-6 m
// against round-off of 1e-15.
// The run is divided after 1500 steps, with contacts (rolling torques, springs) live. Half way, every rank
// writes its state (solver and halo) to a checkpoint and reads it back into a second
// solver and halo, made like the first; from there on the two must step bit for bit alike.
// Usage: grain_slabs_ranks [STEPS [COMPARE_EVERY [GHOST_REACH]]] (a reach of one radius misses contacts: the
// test must then fail). Prints "grain slabs passed on N ranks" on rank 0, or exits with 1
// naming the first difference.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/mpi_world.h"
#include "dem/dem_solver.h"
#include "io/checkpoint.h"
#include "parallel/grain_halo.h"

namespace {

using sabo::Vec3;
using namespace sabo::dem;

constexpr double length = 0.5, width = 0.08, r_min = 0.004, r_max = 0.006, skin = 0.002;
constexpr double allowed_ratio = 1e3;
constexpr int undivided_steps = 1500;  // steps before the grains are divided (some 30 contacts by then)

ContactLaw<LinearNormal> law(double mu_r) {
    ContactLaw<LinearNormal> l;
    l.normal.kn = 2e3;
    l.normal.alpha_n = damping_ratio_from_restitution(0.5);
    l.tangential = {1.0, 0.5, 0.45, FrictionMemory::hysteresis};
    l.rolling.mu_r = mu_r;
    return l;
}

// The same grains on every rank: a lattice block at the top of the channel with small random offsets and
// velocities (a fixed linear congruential sequence), then the barrier's fixed spheres.
DemSolver make_grains(double nudge) {
    Particles p;
    std::uint64_t seed = 12345;
    const auto uniform = [&] {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(seed >> 11) * 0x1.0p-53;
    };
    const double pitch = 2.2 * r_max;
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 18; ++i) {
                const Vec3 x{0.012 + pitch * i + 0.001 * uniform(), 0.012 + pitch * j + 0.001 * uniform(),
                             0.008 + pitch * k + 0.001 * uniform()};
                const Vec3 v{0.5 + 0.2 * uniform(), 0.1 * (uniform() - 0.5), 0.1 * (uniform() - 0.5)};
                p.add_mobile(x + Vec3{nudge, nudge, nudge}, r_min + (r_max - r_min) * uniform(), 2650.0, v);
            }
    for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k) p.add_fixed({0.33, 0.01 + 0.02 * j, 0.01 + 0.02 * k}, 0.008);
    std::vector<Wall> walls{
        Wall::plane("floor", {0, 0, 0}, {0, 0, 1}), Wall::plane("left", {0, 0, 0}, {0, 1, 0}),
        Wall::plane("right", {0, width, 0}, {0, -1, 0}), Wall::plane("start", {0, 0, 0}, {1, 0, 0}),
        Wall::plane("end", {length, 0, 0}, {-1, 0, 0}, true)};
    const ContactLaw<LinearNormal> grain = law(0.1), wall = law(0.05);
    DemSolver solver(std::move(p), std::move(walls), ContactLawSet<LinearNormal>{grain, wall, wall},
                     {4.0, 0.0, -9.0}, 2e-5, skin);
    solver.set_skin_max(2.0 * skin);
    return solver;
}

struct Gap {
    double x = 0.0, v = 0.0, xi = 0.0, roll = 0.0;
    [[nodiscard]] double largest() const { return std::max({x, v, xi, roll}); }
};

// How far `run`'s own grains and contacts lie from the same ones of `reference` (by global id); -1 in .x
// if a contact of `run` is missing from the reference or the other way round.
Gap gap(const DemSolver& run, const DemSolver& reference, std::size_t& contacts_seen) {
    Gap g;
    const auto& p = run.particles();
    const auto& q = reference.particles();
    std::vector<std::size_t> where(reference.ids().size());
    for (std::size_t i = 0; i < q.n_mobile; ++i) where[reference.ids()[i]] = i;
    for (std::size_t i = 0; i < run.own_count(); ++i) {
        const std::size_t k = where[run.ids()[i]];
        g.x = std::max(g.x, norm(p.x[i] - q.x[k]));
        g.v = std::max(g.v, norm(p.v[i] - q.v[k]));
    }
    std::vector<ContactRecord> mine, all;
    run.contact_records(mine);
    reference.contact_records(all);
    std::sort(all.begin(), all.end(), before);
    contacts_seen = mine.size();
    for (const ContactRecord& c : mine) {
        const auto it = std::lower_bound(all.begin(), all.end(), c, before);
        if (it == all.end() || it->a != c.a || it->b != c.b) {
            std::fprintf(stderr, "contact %u-%u is not in the reference\n", c.a, c.b);
            g.x = -1.0;
            return g;
        }
        g.xi = std::max(g.xi, norm(c.history.xi - it->history.xi));
        g.roll = std::max(g.roll, norm(c.rolling - it->rolling));
    }
    return g;
}

int fail(const sabo::MpiWorld& world, const std::string& what) {
    std::fprintf(stderr, "[rank %d] %s\n", world.rank(), what.c_str());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    sabo::MpiWorld world(argc, argv);
    const int steps = argc > 1 ? std::atoi(argv[1]) : 6000,
              compare_every = argc > 2 ? std::atoi(argv[2]) : 250;
    const double reach = argc > 3 ? std::atof(argv[3]) : 0.0;
    DemSolver reference = make_grains(0.0), nudged = make_grains(1e-15), run = make_grains(0.0);
    std::vector<double> faces;
    for (int r = 1; r < world.size(); ++r) faces.push_back(0.05 + 0.3 * r / world.size());
    sabo::parallel::GrainHalo halo(world, run, faces);
    double worst_ratio = 0.0;
    DemSolver resumed = make_grains(0.0);
    sabo::parallel::GrainHalo resumed_halo(world, resumed, faces);
    bool resumed_yet = false;
    for (int s = 1; s <= steps; ++s) {
        reference.step();
        nudged.step();
        if (s <= undivided_steps) {  // the grains collide first: the division takes live contacts over
            run.step();
            if (s == undivided_steps) halo.divide(reach);
        } else {
            halo.step();
        }
        if (s == steps / 2) {
            const std::string file = fmt::format("grain_slabs.rank{}.bin", world.rank());
            sabo::io::CheckpointOut out(file);
            out(run, halo);
            out.commit();
            sabo::io::CheckpointIn in(file);
            in(resumed, resumed_halo);
            in.expect_end();
            resumed.restored();
            std::filesystem::remove(file);
            resumed_yet = true;
        } else if (resumed_yet) {
            resumed_halo.step();
            const auto& p = run.particles();
            const auto& q = resumed.particles();
            const auto same_bits = [](const std::vector<Vec3>& u, const std::vector<Vec3>& w) {
                return u.size() == w.size() && std::memcmp(u.data(), w.data(), u.size() * sizeof(Vec3)) == 0;
            };
            const bool same = run.own_count() == resumed.own_count() && same_bits(p.x, q.x) &&
                              same_bits(p.v, q.v) && same_bits(p.w, q.w);
            if (world.sum(same ? 0 : 1) > 0)
                return fail(world, fmt::format("step {}: the run read back from its checkpoint differs", s));
        }
        if (s <= undivided_steps || (s % compare_every != 0 && s != steps)) continue;
        std::size_t seen = 0, seen_by_nudged = 0;
        const Gap g = gap(run, reference, seen);
        const Gap noise = gap(nudged, reference, seen_by_nudged);
        if (world.sum(g.x < 0.0 ? 1 : 0) > 0)
            return fail(world, fmt::format("step {}: the contacts differ from the reference's", s));
        std::vector<double> worst{g.x, g.v, g.xi, g.roll, noise.x, noise.v, noise.xi, noise.roll};
        world.max_reals(worst);
        const std::int64_t own = world.sum(static_cast<std::int64_t>(run.own_count()));
        const std::int64_t contacts = world.sum(static_cast<std::int64_t>(seen));
        std::vector<ContactRecord> all;
        reference.contact_records(all);
        if (own != static_cast<std::int64_t>(reference.mobile_count()))
            return fail(world, fmt::format("step {}: {} grains among the ranks, {} in the run", s, own,
                                           reference.mobile_count()));
        if (contacts != static_cast<std::int64_t>(all.size()))
            return fail(world, fmt::format("step {}: {} live contacts among the ranks, {} in the reference",
                                           s, contacts, all.size()));
        std::vector<double> wall_force;
        for (const Vec3& f : run.wall_forces()) wall_force.insert(wall_force.end(), {f.x, f.y, f.z});
        world.sum_reals(wall_force);
        double wall_gap = 0.0, wall_noise = 0.0;
        for (std::size_t w = 0; w < reference.wall_forces().size(); ++w) {
            const Vec3 f{wall_force[3 * w], wall_force[3 * w + 1], wall_force[3 * w + 2]};
            wall_gap = std::max(wall_gap, norm(f - reference.wall_forces()[w]));
            wall_noise = std::max(wall_noise, norm(nudged.wall_forces()[w] - reference.wall_forces()[w]));
        }
        const double floor = 1e-12 * r_min;
        const char* names[] = {"position", "velocity", "tangential spring", "rolling torque"};
        for (int k = 0; k < 4; ++k) {
            const double allowed = allowed_ratio * worst[k + 4] + floor;
            worst_ratio = std::max(worst_ratio, worst[k] / (worst[k + 4] + floor));
            if (worst[k] > allowed)
                return fail(world, fmt::format("step {}: {} differs by {:.3g} from the reference (round-off "
                                               "of a position grows to {:.3g}, allowed {:.3g})",
                                               s, names[k], worst[k], worst[k + 4], allowed));
        }
        if (wall_gap > allowed_ratio * wall_noise + 1e-9)
            return fail(world,
                        fmt::format("step {}: wall forces differ by {:.3g} N (round-off grows to {:.3g})", s,
                                    wall_gap, wall_noise));
        if (world.rank() == 0)
            std::printf(
                "step %5d: %lld contacts; divided vs undivided: x %.2e, v %.2e, xi %.2e, roll %.2e; "
                "round-off: x %.2e, v %.2e, xi %.2e, roll %.2e\n",
                s, static_cast<long long>(contacts), worst[0], worst[1], worst[2], worst[3], worst[4],
                worst[5], worst[6], worst[7]);
    }
    const std::int64_t arrivals = world.sum(static_cast<std::int64_t>(halo.arrivals()));
    if (world.size() > 1 && (arrivals < 50 || halo.face_moves() == 0))
        return fail(world, fmt::format("only {} grains changed rank and the faces moved {} times: the test "
                                       "moved too little",
                                       arrivals, halo.face_moves()));
    if (world.rank() == 0)
        std::printf(
            "grain slabs passed on %d ranks: %lld grains changed rank in %zu re-partitions, the faces "
            "moved %zu times; largest difference %.3g times the round-off's; resumed bit for bit\n",
            world.size(), static_cast<long long>(arrivals), halo.repartitions(), halo.face_moves(),
            worst_ratio);
    return 0;
}
