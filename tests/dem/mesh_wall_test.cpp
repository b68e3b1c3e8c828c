// SPDX-License-Identifier: MIT
// A part of a triangle mesh as a DEM wall (dem::Wall::mesh_part): it touches a sphere where and as deep as
// the box it meshes, once over an edge two of its triangles share, and a sphere rolls and stops on a
// meshed incline as on a plane (the analytic accelerations of CASES §C6).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "dem/mesh_contacts.h"
#include "dem/test_support.h"
#include "dem/walls.h"
#include "geometry/mesh_queries.h"
#include "geometry/triangle_mesh.h"

namespace sabo {
namespace {

// The box [lo, hi] as one closed part of 8 vertices and 12 outward triangles.
std::shared_ptr<geometry::TriangleMesh> box_mesh(const Vec3& lo, const Vec3& hi) {
    auto m = std::make_shared<geometry::TriangleMesh>();
    for (int i = 0; i < 8; ++i)
        m->vertices.push_back(
            {(i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z});
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        m->triangles.push_back({f[0], f[1], f[2]});
        m->triangles.push_back({f[0], f[2], f[3]});
    }
    m->part.assign(m->triangles.size(), 0);
    m->part_names = {"box"};
    return m;
}

// Two triangles of the unit square of lattice corners at `base` spanning the two axes after `axis`, facing
// +axis (`up`) or −axis (counter-clockwise seen from outside); corners numbered by at(corner).
template <class At>
void add_square(geometry::TriangleMesh& m, At& at, const std::array<int, 3>& base, int axis, bool up) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
    std::array<std::uint32_t, 4> q;
    for (int k = 0; k < 4; ++k) {
        auto c = base;
        c[static_cast<std::size_t>(u)] += du[k];
        c[static_cast<std::size_t>(v)] += dv[k];
        q[static_cast<std::size_t>(k)] = at(c);
    }
    if (!up) std::swap(q[1], q[3]);
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
}

// The box [lo, hi] as one closed part whose faces are split into quads of about `edge` (two triangles
// each), the corners shared: a fine mesh, as a CAD model exports a large flat face.
std::shared_ptr<geometry::TriangleMesh> fine_box_mesh(const Vec3& lo, const Vec3& hi, double edge) {
    auto m = std::make_shared<geometry::TriangleMesh>();
    const Vec3 size = hi - lo;
    const int n[3] = {static_cast<int>(std::ceil(size.x / edge)), static_cast<int>(std::ceil(size.y / edge)),
                      static_cast<int>(std::ceil(size.z / edge))};
    std::map<std::array<int, 3>, std::uint32_t> vertex;
    const auto at = [&](std::array<int, 3> c) {
        const auto [it, added] = vertex.try_emplace(c, static_cast<std::uint32_t>(m->vertices.size()));
        if (added)
            m->vertices.push_back(
                {lo.x + size.x * c[0] / n[0], lo.y + size.y * c[1] / n[1], lo.z + size.z * c[2] / n[2]});
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // (u, v, axis) right-handed: counter-clockwise in (u, v) faces +axis; the low side reversed
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (int a = 0; a < n[u]; ++a)
                for (int b = 0; b < n[v]; ++b) {
                    std::array<int, 3> base{};
                    base[static_cast<std::size_t>(axis)] = side * n[axis];
                    base[static_cast<std::size_t>(u)] = a;
                    base[static_cast<std::size_t>(v)] = b;
                    add_square(*m, at, base, axis, side == 1);
                }
        }
    m->part.assign(m->triangles.size(), 0);
    m->part_names = {"box"};
    return m;
}

// The union of unit cubes at `cells` (their lower corners, scaled by `edge`) as one closed part: every face
// between a filled and an empty cell as two triangles facing out, the corners shared. Concave corners and
// edges where the cells make them.
std::shared_ptr<geometry::TriangleMesh> voxel_mesh(const std::set<std::array<int, 3>>& cells, double edge) {
    auto m = std::make_shared<geometry::TriangleMesh>();
    std::map<std::array<int, 3>, std::uint32_t> vertex;
    const auto at = [&](std::array<int, 3> c) {
        const auto [it, added] = vertex.try_emplace(c, static_cast<std::uint32_t>(m->vertices.size()));
        if (added)
            m->vertices.push_back(
                Vec3{static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])} * edge);
        return it->second;
    };
    for (const auto& c : cells)
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                auto next = c;
                next[static_cast<std::size_t>(axis)] += side == 0 ? -1 : 1;
                if (cells.contains(next)) continue;
                auto base = c;
                base[static_cast<std::size_t>(axis)] += side;
                add_square(*m, at, base, axis, side == 1);
            }
    m->part.assign(m->triangles.size(), 0);
    m->part_names = {"cells"};
    return m;
}

// Every triangle of a wall's part, the candidates a query hands mesh_touches.
std::span<const std::uint32_t> all_of(const dem::Wall& w) {
    return w.surface->triangles;
}

TEST(MeshWall, TouchesAsTheBoxItMeshes) {
    const Vec3 lo{0.2, -0.3, 0.0}, hi{0.5, 0.4, 0.8};
    const dem::Wall box =
        dem::Wall::box("b", (lo + hi) * 0.5, {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}, (hi - lo) * 0.5);
    const dem::Wall mesh = dem::Wall::mesh_part("m", box_mesh(lo, hi), 0);
    const dem::Wall fine = dem::Wall::mesh_part("f", fine_box_mesh(lo, hi, 0.05), 0);
    const double r = 0.05;
    int touching = 0;
    // centres around the box: off its faces, edges and corners, some too far (none exactly a radius from an
    // edge: the two ways of computing the distance may round such a tie to either side)
    for (double x : {0.16, 0.19, 0.3, 0.51, 0.535, 0.6})
        for (double y : {-0.34, -0.32, 0.0, 0.435, 0.46})
            for (double z : {-0.045, 0.4, 0.825, 0.9}) {
                const Vec3 c{x, y, z};
                if (c.x > lo.x && c.x < hi.x && c.y > lo.y && c.y < hi.y && c.z > lo.z && c.z < hi.z)
                    continue;
                dem::WallTouch a, b;
                const bool ta = dem::touches(box, c, r, a), tb = dem::touches(mesh, c, r, b);
                ASSERT_EQ(ta, tb) << "at " << x << " " << y << " " << z;
                EXPECT_NEAR(dem::clearance(box, {}, c, r),
                            dem::clearance(mesh, mesh.surface->triangles, c, r), 1e-12);
                // the contacts of a part: one, the box's, on the coarse mesh and on a finely meshed one
                for (const dem::Wall* m : {&mesh, &fine}) {
                    const dem::MeshTouches all = dem::mesh_touches(*m, all_of(*m), c, r);
                    ASSERT_EQ(all.count, ta ? 1U : 0U) << "at " << x << " " << y << " " << z;
                    if (!ta) continue;
                    EXPECT_NEAR(all.touch[0].delta, a.delta, 1e-12);
                    EXPECT_NEAR(norm(all.touch[0].n - a.n), 0.0, 1e-12);
                }
                if (!ta) continue;
                ++touching;
                EXPECT_NEAR(a.delta, b.delta, 1e-12);
                EXPECT_NEAR(norm(a.n - b.n), 0.0, 1e-12);
            }
    EXPECT_GT(touching, 20);
}

TEST(MeshWall, ASphereOverTheEdgeTwoTrianglesShareTouchesOnceStraightDown) {
    // the top face z = 1 is two triangles meeting along its diagonal; the centre above the diagonal
    const dem::Wall mesh = dem::Wall::mesh_part("m", box_mesh({0, 0, 0}, {1, 1, 1}), 0);
    dem::WallTouch t;
    ASSERT_TRUE(dem::touches(mesh, {0.3, 0.3, 1.04}, 0.05, t));
    EXPECT_NEAR(t.delta, 0.01, 1e-12);
    EXPECT_NEAR(norm(t.n - Vec3{0, 0, -1}), 0.0, 1e-12);
}

// Concave parts: an L of three unit cells (a floor and a wall in one solid, 0.5 m cells) pushes a sphere
// in its inner corner from both faces; a cube with one cell cut from its corner pushes from three faces;
// over the L's convex ridge and over its faces the sphere is touched once.
TEST(MeshWall, ASphereInAConcaveCornerIsTouchedByEachFace) {
    const dem::Wall el = dem::Wall::mesh_part("L", voxel_mesh({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, 0.5), 0);
    const double r = 0.1;
    // the inner edge is x = 0.5, z = 0.5 (y from 0 to 0.5): the floor 0.07 below the centre, the wall 0.08
    dem::MeshTouches t = dem::mesh_touches(el, all_of(el), {0.58, 0.25, 0.57}, r);
    ASSERT_EQ(t.count, 2U);
    EXPECT_NEAR(t.touch[0].delta, 0.03, 1e-12);
    EXPECT_NEAR(norm(t.touch[0].n - Vec3{0, 0, -1}), 0.0, 1e-12);
    EXPECT_NEAR(t.touch[1].delta, 0.02, 1e-12);
    EXPECT_NEAR(norm(t.touch[1].n - Vec3{-1, 0, 0}), 0.0, 1e-12);
    // over the inner edge's end, where the L's side face meets it: still the two faces, the side's edges
    // not counted
    t = dem::mesh_touches(el, all_of(el), {0.58, 0.001, 0.57}, r);
    EXPECT_EQ(t.count, 2U);
    // over the convex ridge x = 1, z = 0.5: one contact, at the ridge
    t = dem::mesh_touches(el, all_of(el), {1.03, 0.25, 0.54}, r);
    ASSERT_EQ(t.count, 1U);
    EXPECT_NEAR(t.touch[0].delta, r - 0.05, 1e-12);
    // over the floor, away from the wall: one
    t = dem::mesh_touches(el, all_of(el), {0.8, 0.25, 0.56}, r);
    ASSERT_EQ(t.count, 1U);
    EXPECT_NEAR(t.touch[0].delta, 0.04, 1e-12);

    std::set<std::array<int, 3>> cube;
    for (int k = 0; k < 8; ++k)
        if (k != 7) cube.insert({k & 1, (k >> 1) & 1, (k >> 2) & 1});
    const dem::Wall cut = dem::Wall::mesh_part("cut", voxel_mesh(cube, 0.5), 0);
    t = dem::mesh_touches(cut, all_of(cut), {0.55, 0.56, 0.57}, r);
    ASSERT_EQ(t.count, 3U);
    EXPECT_NEAR(t.touch[0].delta, 0.05, 1e-12);
    EXPECT_NEAR(t.touch[1].delta, 0.04, 1e-12);
    EXPECT_NEAR(t.touch[2].delta, 0.03, 1e-12);
}

// Two piles on a sill, one solid (a U of 0.5 m cells): cut at half its height it stands where the piles do,
// lower down across the whole sill (where a barrier of such a part has its outlets).
TEST(MeshWall, APartStandsAcrossTheChannelWhereItsCutIs) {
    std::set<std::array<int, 3>> u;
    for (int y = 0; y < 5; ++y) u.insert({0, y, 0});
    for (int z = 1; z < 3; ++z) {
        u.insert({0, 0, z});
        u.insert({0, 4, z});
    }
    const auto m = voxel_mesh(u, 0.5);
    const auto piles = geometry::spans_across(*m, 0, 0.75);
    ASSERT_EQ(piles.size(), 2U);
    EXPECT_DOUBLE_EQ(piles[0].first, 0.0);
    EXPECT_DOUBLE_EQ(piles[0].second, 0.5);
    EXPECT_DOUBLE_EQ(piles[1].first, 2.0);
    EXPECT_DOUBLE_EQ(piles[1].second, 2.5);
    const auto sill = geometry::spans_across(*m, 0, 0.25);
    ASSERT_EQ(sill.size(), 1U);
    EXPECT_DOUBLE_EQ(sill[0].first, 0.0);
    EXPECT_DOUBLE_EQ(sill[0].second, 2.5);
    EXPECT_TRUE(geometry::spans_across(*m, 0, 1.6).empty());
}

// The slots: a contact keeps the slot whose normal it continues, whichever is nearer this step; a lone
// contact keeps a lone slot however its normal turned; a new one starts afresh in a free slot.
TEST(MeshWall, ContactsKeepTheirSlotsByTheirNormals) {
    dem::MeshTouches now;
    now.count = 2;
    now.touch[0] = {{-1, 0, 0}, 0.02};  // the wall, nearer now
    now.touch[1] = {{0, 0, -1}, 0.01};  // the floor
    const std::array<Vec3, dem::mesh_slots> last{Vec3{0, 0, -1}, Vec3{}, Vec3{-1, 0, 0}, Vec3{}};
    const std::array<std::uint8_t, dem::mesh_slots> touching{1, 0, 1, 0};
    dem::SlotChoice c = dem::assign_slots(now, last, touching);
    EXPECT_EQ(c.slot[0], 2U);
    EXPECT_EQ(c.slot[1], 0U);
    EXPECT_FALSE(c.fresh[0] || c.fresh[1]);
    // a third contact, along y: fresh, in the first free slot
    now.count = 3;
    now.touch[2] = {{0, -1, 0}, 0.005};
    c = dem::assign_slots(now, last, touching);
    EXPECT_EQ(c.slot[2], 1U);
    EXPECT_TRUE(c.fresh[2]);
    // a lone contact continues a lone slot though its normal turned 90° (over an edge)
    now.count = 1;
    c = dem::assign_slots(now, last, std::array<std::uint8_t, dem::mesh_slots>{0, 0, 0, 1});
    EXPECT_EQ(c.slot[0], 3U);
    EXPECT_FALSE(c.fresh[0]);
    // two contacts, one slot 90° off each: both start afresh, in the free slots
    now.count = 2;
    now.touch[0] = {{0, 1, 0}, 0.02};
    now.touch[1] = {{1, 0, 0}, 0.01};
    c = dem::assign_slots(now, last, touching);
    EXPECT_EQ(c.slot[0], 1U);
    EXPECT_EQ(c.slot[1], 3U);
    EXPECT_TRUE(c.fresh[0] && c.fresh[1]);
}

constexpr double g = 9.81, r = 0.05, rho = 2500.0, kn = 1e6;

// A sphere rolling on the bed z = 0 of an incline tilted by θ: the bed a plane, or the top face of a meshed
// slab 10 m long.
enum class Bed { plane, mesh, fine_mesh };
dem::DemSolver rolling_sphere(double theta, double mu_r, double v0, Bed bed) {
    dem::Particles p;
    const double m = test::mass_of(r, rho), delta0 = m * g * std::cos(theta) / kn;
    p.add_mobile({0.5, 0.5, r - delta0}, r, rho, {v0, 0, 0});
    p.w[0] = {0, v0 / r, 0};
    const Vec3 lo{-1, -1, -0.5}, hi{9, 2, 0};
    std::vector<dem::Wall> walls{bed == Bed::plane ? dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1})
                                 : bed == Bed::mesh
                                     ? dem::Wall::mesh_part("bed", box_mesh(lo, hi), 0)
                                     : dem::Wall::mesh_part("bed", fine_box_mesh(lo, hi, 0.04), 0)};
    const auto law = test::linear_law({.kn = kn, .restitution = 0.2, .mu_s = 1.0, .mu_r = mu_r});
    return dem::DemSolver(p, walls, test::same_everywhere(law),
                          {g * std::sin(theta), 0, -g * std::cos(theta)}, law.normal.contact_time(m) / 40.0,
                          0.1 * r);
}

TEST(MeshWall, ASphereRollsOnAMeshedInclineAsOnAPlane) {
    const double theta = std::atan(0.3), mu_r = 0.1;
    auto plane = rolling_sphere(theta, mu_r, 0.0, Bed::plane),
         mesh = rolling_sphere(theta, mu_r, 0.0, Bed::mesh);
    while (mesh.time() < 0.2) {
        plane.step();
        mesh.step();
    }
    const double v1 = mesh.particles().v[0].x, t1 = mesh.time();
    while (mesh.time() < 1.2) {
        plane.step();
        mesh.step();
    }
    const double a = (mesh.particles().v[0].x - v1) / (mesh.time() - t1);
    const double expected = 5.0 / 7.0 * g * (std::sin(theta) - mu_r * std::cos(theta));
    EXPECT_NEAR(a, expected, 0.01 * expected);
    EXPECT_NEAR(mesh.particles().x[0].x, plane.particles().x[0].x, 1e-9);
    EXPECT_NEAR(mesh.particles().x[0].z, plane.particles().x[0].z, 1e-12);
}

// The bed's top face in 19 000 triangles of 4 cm (the sphere's radius 5 cm): the neighbour list hands the
// contact the few triangles within the grain's reach, and the sphere rolls over their shared edges and
// corners as on the plane.
TEST(MeshWall, ASphereRollsOnAFinelyMeshedInclineAsOnAPlane) {
    const double theta = std::atan(0.3), mu_r = 0.1;
    auto plane = rolling_sphere(theta, mu_r, 0.0, Bed::plane),
         mesh = rolling_sphere(theta, mu_r, 0.0, Bed::fine_mesh);
    ASSERT_GT(mesh.walls()[0].surface->triangles.size(), 18000U);
    while (mesh.time() < 1.2) {
        plane.step();
        mesh.step();
    }
    EXPECT_GT(mesh.particles().x[0].x, 1.4);  // rolled 0.9 m: over the edges of some twenty quads
    EXPECT_NEAR(mesh.particles().x[0].x, plane.particles().x[0].x, 1e-9);
    EXPECT_NEAR(mesh.particles().x[0].z, plane.particles().x[0].z, 1e-12);
}

// The bins of a fine mesh find every triangle within a reach of a point (against all the part's triangles),
// in ascending order, each once.
TEST(MeshWall, TheBinsFindEveryTriangleWithinReach) {
    const auto m = fine_box_mesh({0.1, -0.2, 0.0}, {1.3, 0.5, 0.4}, 0.07);
    std::vector<std::uint32_t> all(m->triangles.size());
    for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<std::uint32_t>(t);
    const geometry::TriangleBins bins(*m, all);
    std::vector<std::uint32_t> found;
    int checked = 0;
    for (double x = -0.1; x < 1.5; x += 0.137)
        for (double y = -0.35; y < 0.65; y += 0.111)
            for (double z = -0.1; z < 0.55; z += 0.093)
                for (const double reach : {0.02, 0.09, 0.3}) {
                    const Vec3 p{x, y, z};
                    bins.near(p, reach, found);
                    ASSERT_TRUE(std::is_sorted(found.begin(), found.end()));
                    ASSERT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
                    for (std::uint32_t t = 0; t < all.size(); ++t)
                        if (norm(geometry::closest_point(*m, t, p) - p) < reach) {
                            ASSERT_TRUE(std::binary_search(found.begin(), found.end(), t))
                                << "triangle " << t << " within " << reach << " of (" << x << ", " << y
                                << ", " << z << ")";
                            ++checked;
                        }
                }
    EXPECT_GT(checked, 10000);
    EXPECT_GT(bins.bins(), 100U);
}

TEST(MeshWall, ASphereStopsOnAMeshedInclineWhereRollingResistanceWins) {
    const double theta = std::atan(0.05), mu_r = 0.1, v0 = 1.0;
    auto s = rolling_sphere(theta, mu_r, v0, Bed::mesh);
    const double t_stop = v0 / (5.0 / 7.0 * g * (mu_r * std::cos(theta) - std::sin(theta)));
    double stopped_at = -1.0;
    while (s.time() < 1.5 * t_stop) {
        s.step();
        if (stopped_at < 0.0 && s.particles().v[0].x <= 1e-4) stopped_at = s.time();
    }
    EXPECT_NEAR(stopped_at, t_stop, 0.01 * t_stop);
}

// A sphere dropped into the inner corner of a meshed L (one solid) under gravity pointing into the corner
// comes to rest held by both faces: their forces add up to its weight and neither face lets it sink. Without
// friction each face carries the weight's component along its normal (their overlaps tell); with friction
// the split depends on how it came to rest (statically indeterminate), and both faces carry load.
dem::DemSolver sphere_in_a_corner(double mu) {
    dem::Particles p;
    p.add_mobile({0.5 + 1.2 * r, 0.25, 0.5 + 1.5 * r}, r, rho);
    std::vector<dem::Wall> walls{
        dem::Wall::mesh_part("L", voxel_mesh({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, 0.5), 0)};
    const auto law = test::linear_law({.kn = kn, .restitution = 0.2, .mu_s = mu, .mu_r = mu / 5.0});
    return dem::DemSolver(p, walls, test::same_everywhere(law), {-0.6 * g, 0, -0.8 * g},
                          law.normal.contact_time(test::mass_of(r, rho)) / 40.0, 0.1 * r);
}

TEST(MeshWall, ASphereRestsInAConcaveCornerHeldByBothFaces) {
    const double m = test::mass_of(r, rho);
    const Vec3 weight = Vec3{-0.6 * g, 0, -0.8 * g} * m;
    for (const double mu : {0.0, 0.5}) {
        auto s = sphere_in_a_corner(mu);
        while (s.time() < 1.0) s.step();
        EXPECT_LT(norm(s.particles().v[0]), 1e-6) << "mu " << mu;
        EXPECT_NEAR(norm(s.wall_forces()[0] - weight), 0.0, 1e-6 * m * g) << "mu " << mu;
        const double floor_overlap = 0.5 + r - s.particles().x[0].z,
                     wall_overlap = 0.5 + r - s.particles().x[0].x;
        if (mu == 0.0) {
            EXPECT_NEAR(floor_overlap, 0.8 * m * g / kn, 1e-12);
            EXPECT_NEAR(wall_overlap, 0.6 * m * g / kn, 1e-12);
        } else {
            EXPECT_GT(floor_overlap, 0.1 * m * g / kn);
            EXPECT_GT(wall_overlap, 0.1 * m * g / kn);
        }
    }
}

}  // namespace
}  // namespace sabo
