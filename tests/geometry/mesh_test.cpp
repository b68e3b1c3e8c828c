// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/mesh_queries.h"
#include "geometry/stl_reader.h"
#include "geometry/triangle_mesh.h"

namespace sabo::geometry {
namespace {

using Triangle = std::array<Vec3, 3>;

// The 12 outward triangles of the box [lo, hi].
std::vector<Triangle> box_triangles(const Vec3& lo, const Vec3& hi) {
    const auto p = [&](int i) {
        return Vec3{(i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z};
    };
    // each face's corners counter-clockwise seen from outside
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    std::vector<Triangle> out;
    for (const auto& f : faces) {
        out.push_back({p(f[0]), p(f[1]), p(f[2])});
        out.push_back({p(f[0]), p(f[2]), p(f[3])});
    }
    return out;
}

std::string ascii_solid(const std::string& name, const std::vector<Triangle>& tris) {
    std::string s = "solid " + name + "\n";
    for (const Triangle& t : tris) {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for (const Vec3& v : t)
            s += "      vertex " + std::to_string(v.x) + " " + std::to_string(v.y) + " " +
                 std::to_string(v.z) + "\n";
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid " + name + "\n";
}

std::filesystem::path temp_file(const std::string& name, const std::string& content) {
    const auto path = std::filesystem::temp_directory_path() / ("sabo_mesh_test_" + name);
    std::ofstream(path, std::ios::binary) << content;
    return path;
}

std::string binary_stl(const std::vector<Triangle>& tris) {
    std::string s(80, ' ');
    s.replace(0, 5, "solid");  // (a binary header may start so: the size tells)
    const auto count = static_cast<std::uint32_t>(tris.size());
    s.append(reinterpret_cast<const char*>(&count), 4);
    for (const Triangle& t : tris) {
        const std::array<float, 12> v{0,
                                      0,
                                      0,
                                      float(t[0].x),
                                      float(t[0].y),
                                      float(t[0].z),
                                      float(t[1].x),
                                      float(t[1].y),
                                      float(t[1].z),
                                      float(t[2].x),
                                      float(t[2].y),
                                      float(t[2].z)};
        s.append(reinterpret_cast<const char*>(v.data()), sizeof(v));
        s.append(2, '\0');
    }
    return s;
}

TEST(StlReader, AnAsciiCubeIsOneClosedPartOfEightVerticesAndItsVolume) {
    const auto file = temp_file("cube.stl", ascii_solid("pile", box_triangles({1, 2, 3}, {3, 3, 4})));
    const TriangleMesh m = read_stl(file);
    ASSERT_EQ(m.parts(), 1U);
    EXPECT_EQ(m.part_names[0], "pile");
    EXPECT_EQ(m.vertices.size(), 8U);
    EXPECT_EQ(m.triangles.size(), 12U);
    EXPECT_NO_THROW(check_closed(m, "cube.stl"));
    EXPECT_NEAR(m.volume(0), 2.0, 1e-12);
    const Vec3 c = m.centroid(0);
    EXPECT_NEAR(c.x, 2.0, 1e-12);
    EXPECT_NEAR(c.y, 2.5, 1e-12);
    EXPECT_NEAR(c.z, 3.5, 1e-12);
}

TEST(StlReader, ABinaryFileWhoseHeaderSaysSolidIsReadAsBinary) {
    const auto file = temp_file("cube_binary.stl", binary_stl(box_triangles({0, 0, 0}, {1, 2, 0.5})));
    const TriangleMesh m = read_stl(file);
    ASSERT_EQ(m.parts(), 1U);
    EXPECT_EQ(m.part_names[0], "sabo_mesh_test_cube_binary");
    EXPECT_EQ(m.vertices.size(), 8U);
    EXPECT_NEAR(m.volume(0), 1.0, 1e-6);
    EXPECT_NO_THROW(check_closed(m, "cube_binary.stl"));
}

TEST(StlReader, EachSolidIsAPart) {
    const auto file =
        temp_file("two.stl", ascii_solid("left pile", box_triangles({0, 0, 0}, {1, 1, 1})) +
                                 ascii_solid("right pile", box_triangles({0, 2, 0}, {1, 3, 2})));
    const TriangleMesh m = read_stl(file);
    ASSERT_EQ(m.parts(), 2U);
    EXPECT_EQ(m.part_names[1], "right pile");
    EXPECT_NEAR(m.volume(0), 1.0, 1e-12);
    EXPECT_NEAR(m.volume(1), 2.0, 1e-12);
    EXPECT_NEAR(m.bounds(1).lo.y, 2.0, 1e-12);
}

TEST(StlReader, BadFilesAreRefusedWithTheirPlace) {
    const auto expect_error = [](const std::string& content, const std::string& what) {
        try {
            (void)read_stl(temp_file("bad.stl", content));
            ADD_FAILURE() << "accepted: " << content;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    expect_error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n",
                 ":4: a vertex needs three finite numbers");
    expect_error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
                 "a facet with 2 vertices");
    expect_error("solid a\n", "no 'endsolid'");
    expect_error("hello\n", "unexpected 'hello'");
    expect_error(std::string(84, 'x') + "abc", "not an STL file");
    EXPECT_THROW((void)read_stl("/nonexistent/barrier.stl"), InputError);
}

TEST(TriangleMesh, OpenInwardAndDegenerateSurfacesAreRefused) {
    const auto mesh_of = [](std::vector<Triangle> tris) {
        return read_stl(temp_file("check.stl", ascii_solid("p", tris)));
    };
    const auto message = [](const TriangleMesh& m) {
        try {
            check_closed(m, "barrier.stl");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    auto open = box_triangles({0, 0, 0}, {1, 1, 1});
    open.pop_back();
    EXPECT_NE(message(mesh_of(open)).find("is not closed"), std::string::npos);
    auto inward = box_triangles({0, 0, 0}, {1, 1, 1});
    for (Triangle& t : inward) std::swap(t[1], t[2]);
    EXPECT_NE(message(mesh_of(inward)).find("faces inward"), std::string::npos);
    auto flat = box_triangles({0, 0, 0}, {1, 1, 1});
    flat.push_back({Vec3{0, 0, 0}, Vec3{0.5, 0, 0}, Vec3{1, 0, 0}});
    EXPECT_NE(message(mesh_of(flat)).find("degenerate"), std::string::npos);
    EXPECT_EQ(message(mesh_of(box_triangles({0, 0, 0}, {1, 1, 1}))), "");
}

TEST(TriangleMesh, MillimetresToMetresAndARotation) {
    const TriangleMesh m =
        read_stl(temp_file("mm.stl", ascii_solid("p", box_triangles({0, 0, 0}, {1000, 500, 200}))));
    const TriangleMesh metres = transformed(m, 1e-3, {0, 0, 90}, {5, 0, 0});
    EXPECT_NEAR(metres.volume(0), 0.1, 1e-12);
    const Bounds b = metres.bounds();  // x, y of the box turned a quarter about z, moved 5 m along x
    EXPECT_NEAR(b.lo.x, 4.5, 1e-12);
    EXPECT_NEAR(b.hi.x, 5.0, 1e-12);
    EXPECT_NEAR(b.hi.y, 1.0, 1e-12);
    EXPECT_NO_THROW(check_closed(metres, "mm.stl"));
}

TEST(MeshQueries, TheCellsInsideABoxAreThoseWhoseCentresItHolds) {
    const Vec3 lo{0.33, 0.27, 0.07}, hi{1.71, 0.93, 0.66};
    const TriangleMesh m = read_stl(temp_file("box.stl", ascii_solid("b", box_triangles(lo, hi))));
    const CellGrid grid{{0, 0, 0}, 0.1, 20, 12, 9};
    std::vector<std::array<int, 3>> found, expected;
    for_cells_inside(m, 0, grid, [&](int i, int j, int k) { found.push_back({i, j, k}); });
    for (int k = 0; k < grid.nz; ++k)
        for (int j = 0; j < grid.ny; ++j)
            for (int i = 0; i < grid.nx; ++i) {
                const Vec3 c{(i + 0.5) * 0.1, (j + 0.5) * 0.1, (k + 0.5) * 0.1};
                if (c.x > lo.x && c.x < hi.x && c.y > lo.y && c.y < hi.y && c.z > lo.z && c.z < hi.z)
                    expected.push_back({i, j, k});
            }
    EXPECT_EQ(found, expected);
    EXPECT_EQ(found.size(), 14U * 6U * 6U);
}

TEST(MeshQueries, ARotatedBoxSharesEdgesWithCellRowsAndStillCountsOnce) {
    // a cube turned 45° about z, its corners and edges on the rows of cell centres
    TriangleMesh m =
        read_stl(temp_file("cube45.stl", ascii_solid("c", box_triangles({-1, -1, -1}, {1, 1, 1}))));
    m = transformed(m, 1.0, {0, 0, 45}, {2.05, 2.05, 1.05});
    const CellGrid grid{{0, 0, 0}, 0.1, 41, 41, 21};
    std::vector<char> found(41 * 41 * 21, 0);
    for_cells_inside(
        m, 0, grid, [&](int i, int j, int k) { found[static_cast<std::size_t>((k * 41 + j) * 41 + i)] = 1; });
    // every centre clearly inside (|x| + |y| < √2, |z| < 1 by more than 1e-9) or clearly outside agrees;
    // those on the surface (the top and bottom faces run through centres) may go either way
    int wrong = 0, clearly_inside = 0;
    for (int k = 0; k < 21; ++k)
        for (int j = 0; j < 41; ++j)
            for (int i = 0; i < 41; ++i) {
                const double x = (i + 0.5) * 0.1 - 2.05, y = (j + 0.5) * 0.1 - 2.05,
                             z = (k + 0.5) * 0.1 - 1.05;
                const double depth = std::min(std::sqrt(2.0) - std::abs(x) - std::abs(y), 1.0 - std::abs(z));
                const bool in = found[static_cast<std::size_t>((k * 41 + j) * 41 + i)] != 0;
                if (depth > 1e-9) ++clearly_inside;
                if ((depth > 1e-9 && !in) || (depth < -1e-9 && in)) ++wrong;
            }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(clearly_inside, 7000);
    EXPECT_TRUE(contains(m, 0, {2.05, 2.05, 1.05}));
    EXPECT_TRUE(contains(m, 0, {2.05 + 1.4, 2.05, 1.05}));
    EXPECT_FALSE(contains(m, 0, {2.05 + 1.0, 2.05 + 1.0, 1.05}));
}

TEST(MeshQueries, TheHighestCrossingOfAVerticalLineIsThePartsTopThere) {
    // a bed step (z to 0.2) and a taller wall on half of it, as two solids
    const auto path =
        temp_file("crossing.stl", ascii_solid("bed_step", box_triangles({0, 0, 0}, {1, 1, 0.2})) +
                                      ascii_solid("wall", box_triangles({0, 0.5, 0}, {1, 1, 1})));
    const TriangleMesh mesh = read_stl(path);
    EXPECT_NEAR(highest_crossing(mesh, 0, 0.3, 0.25), 0.2, 1e-12);
    EXPECT_NEAR(highest_crossing(mesh, 0, 0.5, 0.5), 0.2, 1e-12);  // on the top face's diagonal
    EXPECT_NEAR(highest_crossing(mesh, 0, 1.0, 1.0), 0.2, 1e-12);  // on its corner
    EXPECT_NEAR(highest_crossing(mesh, 1, 0.3, 0.75), 1.0, 1e-12);
    EXPECT_TRUE(std::isnan(highest_crossing(mesh, 1, 0.3, 0.25)));  // beside the wall
    EXPECT_TRUE(std::isnan(highest_crossing(mesh, 0, 1.5, 0.25)));  // past the step
    std::filesystem::remove(path);
}

TEST(MeshQueries, ClosestPointsOnAVertexAnEdgeAndTheFace) {
    const TriangleMesh m =
        read_stl(temp_file("cube1.stl", ascii_solid("c", box_triangles({0, 0, 0}, {1, 1, 1}))));
    EXPECT_NEAR(distance(m, 0, {0.5, 0.5, 3.0}), 2.0, 1e-12);             // above the top face
    EXPECT_NEAR(distance(m, 0, {2.0, 0.5, 2.0}), std::sqrt(2.0), 1e-12);  // beside an edge
    EXPECT_NEAR(distance(m, 0, {2.0, 2.0, 2.0}), std::sqrt(3.0), 1e-12);  // beyond a corner
    EXPECT_NEAR(distance(m, 0, {0.5, 0.5, 0.4}), 0.4, 1e-12);             // inside: to the bottom
}

}  // namespace
}  // namespace sabo::geometry
