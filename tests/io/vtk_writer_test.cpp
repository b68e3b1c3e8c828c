// SPDX-License-Identifier: MIT
#include "io/vtk_writer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

namespace sabo::io {

TEST(VtkWriter, AppendedOffsetsPointAtTheRightBlocks) {
    const auto dir = std::filesystem::temp_directory_path() / "sabo_vtk_test";
    std::filesystem::create_directories(dir);
    const std::vector<Vec3> x{{1, 2, 3}, {4, 5, 6}};
    const std::vector<double> r{0.1, 0.2};
    PolyDataWriter w(x);
    w.scalar("radius_m", r);
    w.vector("velocity_m_s", x);
    w.write(dir / "p.vtp");
    EXPECT_FALSE(std::filesystem::exists(dir / "p.vtp.tmp"));
    std::ifstream in(dir / "p.vtp", std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string s = ss.str();
    const auto start = s.find('_', s.find("<AppendedData")) + 1;
    // the radius array: find its offset attribute and read the block there
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        s, m, std::regex(R"re(Name="radius_m" NumberOfComponents="1" format="appended" offset="(\d+)")re")));
    const auto off = std::stoull(m[1]);
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, s.data() + start + off, 8);
    ASSERT_EQ(bytes, 16u);
    double values[2];
    std::memcpy(values, s.data() + start + off + 8, 16);
    EXPECT_EQ(values[0], 0.1);
    EXPECT_EQ(values[1], 0.2);
    PvdSeries pvd(dir / "s.pvd");
    pvd.add(0.5, "p.vtp");
    std::ifstream pin(dir / "s.pvd");
    std::stringstream ps;
    ps << pin.rdbuf();
    EXPECT_NE(ps.str().find(R"(timestep="0.5" part="0" file="p.vtp")"), std::string::npos);
}

}  // namespace sabo::io
