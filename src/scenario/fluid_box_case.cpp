// SPDX-License-Identifier: MIT
#include "scenario/fluid_box_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.h"
#include "scenario/channel_case.h"
#include "scenario/csv_table.h"
#include "scenario/overlap_grid.h"

namespace sabo::scenario {

namespace {

// The grains of the file, placed as mobile spheres of `density` (checked: inside the box, apart).
void read_grains(const std::filesystem::path& file, const FluidBoxCase& c, dem::Particles& p) {
    const CsvTable table = read_csv_table(file, "the grains' file (grains.file)", 1000000);
    const std::vector<std::string>& header = table.header;
    const std::vector<std::string> needed{"x_m", "y_m", "z_m", "radius_m"};
    const std::vector<std::string> velocity{"vx_m_s", "vy_m_s", "vz_m_s"};
    const bool moving =
        header.size() == 7 && std::equal(velocity.begin(), velocity.end(), header.begin() + 4);
    if (header.size() < 4 || !std::equal(needed.begin(), needed.end(), header.begin()) ||
        (header.size() != 4 && !moving))
        throw InputError(
            fmt::format("{}: line 1: the header must be 'x_m,y_m,z_m,radius_m' or "
                        "'x_m,y_m,z_m,radius_m,vx_m_s,vy_m_s,vz_m_s'",
                        file.string()));
    struct Row {
        std::size_t line;
        Vec3 x, v;
        double r;
    };
    std::vector<Row> rows;
    double r_max = 0.0;
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const std::vector<double>& v = table.rows[k];
        const std::size_t number = table.lines[k];
        const Vec3 x{v[0], v[1], v[2]};
        const double r = v[3];
        if (!(r > 0.0))
            throw InputError(
                fmt::format("{}: line {}: radius_m must be positive, got {}", file.string(), number, r));
        if (x.x - r < 0.0 || x.y - r < 0.0 || x.z - r < 0.0 || x.x + r > c.size.x || x.y + r > c.size.y ||
            x.z + r > c.size.z)
            throw InputError(
                fmt::format("{}: line {}: the grain ({}, {}, {}) m of radius {} m does not lie "
                            "inside the box [0, {}] x [0, {}] x [0, {}] m",
                            file.string(), number, x.x, x.y, x.z, r, c.size.x, c.size.y, c.size.z));
        rows.push_back({number, x, moving ? Vec3{v[4], v[5], v[6]} : Vec3{}, r});
        r_max = std::max(r_max, r);
    }
    // apart, in the file's order (touching is allowed)
    OverlapGrid kept({0.0, 0.0, 0.0}, c.size, 2.0 * r_max, false);
    for (const Row& g : rows) {
        if (const auto q = kept.overlap(g.x, g.r, p))
            throw InputError(fmt::format("{}: line {}: the grain overlaps the grain of line {}",
                                         file.string(), g.line, rows[*q].line));
        kept.add(static_cast<std::uint32_t>(p.n_mobile), g.x);
        p.add_mobile(g.x, g.r, c.density, g.v);
    }
    if (p.n_mobile == 0) throw InputError(fmt::format("{}: no grains", file.string()));
}

}  // namespace

FluidBoxCase read_fluid_box_case(const Config& cfg, double fluid_density, double fluid_viscosity) {
    FluidBoxCase c;
    c.name = cfg.text_or("case.name", "fluid_box");
    c.end_time = cfg.real("case.end_time_s", Range::positive());
    c.size = {cfg.real("box.length_m", Range::positive()), cfg.real("box.width_m", Range::positive()),
              cfg.real("box.height_m", Range::positive())};
    c.gravity = cfg.real_or("box.gravity_m_s2", 9.81, Range::non_negative());
    c.periodic = {cfg.boolean_or("box.periodic_x", false), cfg.boolean_or("box.periodic_y", false),
                  cfg.boolean_or("box.periodic_z", false)};
    c.drive = cfg.real_or("box.drive_x_m_s2", 0.0, Range::non_negative());
    c.held = cfg.boolean_or("grains.held", false);
    if (c.periodic[2] && c.gravity > 0.0)
        cfg.fail("box.periodic_z", "a box periodic along gravity (Z) needs box.gravity_m_s2 = 0");
    if (c.drive > 0.0 && !c.periodic[0])
        cfg.fail("box.drive_x_m_s2",
                 "a mean flow along X needs box.periodic_x = true (a closed box holds none)");
    if ((c.periodic[0] || c.periodic[1] || c.periodic[2]) && !c.held)
        cfg.fail(
            "grains.held",
            "grains in a periodic box must be held (grains.held = true): grains that cross a periodic face "
            "are not supported");
    c.density = cfg.real("grains.density_kg_m3", Range::positive());
    const std::filesystem::path named = cfg.text("grains.file");
    c.grains_file = beside_case(cfg.source(), named);
    c.grains_file = c.grains_file.lexically_normal();
    read_grains(c.grains_file, c, c.particles);
    const auto& r = c.particles.r;
    c.r_min = *std::min_element(r.begin(), r.end());
    c.r_max = *std::max_element(r.begin(), r.end());
    double sum = 0.0;
    for (const double ri : r) sum += ri;
    c.r_mean = sum / static_cast<double>(r.size());
    cfg.record("derived.grains", static_cast<std::int64_t>(c.particles.n_mobile));
    cfg.record("derived.grains_file", c.grains_file.string());
    c.walls.clear();  // the faces of the axes that are not periodic
    for (const dem::Wall& w : channel_walls({c.size.x, c.size.y, c.size.z, 0.0, c.gravity})) {
        const Vec3 n = w.normal;
        const int axis = n.x != 0.0 ? 0 : (n.y != 0.0 ? 1 : 2);
        if (!c.periodic[static_cast<std::size_t>(axis)]) c.walls.push_back(w);
    }
    // the fastest a grain gets: its start, or the least of its buoyant weight's fall through the box without
    // drag and Stokes' terminal velocity of the largest grain (the drag is never below Stokes')
    const double reduced = c.gravity * std::abs(c.density - fluid_density) / c.density;
    const double stokes =
        2.0 / 9.0 * std::abs(c.density - fluid_density) * c.gravity * c.r_max * c.r_max / fluid_viscosity;
    double fastest = std::min(std::sqrt(2.0 * reduced * c.size.z), stokes);
    for (const Vec3& v : c.particles.v) fastest = std::max(fastest, norm(v));
    if (c.held) {  // the driven flow past held grains: no faster than the drive against Stokes' drag on them
        double stokes_sum = 0.0;
        for (const double ri : r) stokes_sum += 6.0 * std::numbers::pi * fluid_viscosity * ri;
        fastest = fluid_density * c.drive * c.size.x * c.size.y * c.size.z / stokes_sum;
    }
    c.velocity_scale = cfg.real_or("box.velocity_scale_m_s", std::max(fastest, 1e-6), Range::positive());
    return c;
}

}  // namespace sabo::scenario
