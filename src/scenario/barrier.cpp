// SPDX-License-Identifier: MIT
#include "scenario/barrier.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/error.h"
#include "dem/grain_budget.h"

namespace sabo::scenario {

namespace {

constexpr double deg = std::numbers::pi / 180.0;
constexpr double eps = 1e-9;

// Y positions of the sphere columns of a pile [lo, hi]. The sphere surfaces are flush with the
// pile's outlet edges (centres one radius inside); columns are one radius apart; a side that
// touches a channel wall is filled up to the wall.
std::vector<double> sphere_columns(const Span& pile, double width, double r) {
    std::vector<double> ys;
    const bool wall_lo = pile.lo <= eps, wall_hi = pile.hi >= width - eps;
    if (wall_lo && wall_hi) {  // closed
        for (double y = 0.0; y <= width + eps; y += r) ys.push_back(y);
    } else if (wall_lo) {
        for (double y = pile.hi - r; y >= -eps; y -= r) ys.insert(ys.begin(), y);
    } else if (wall_hi) {
        for (double y = pile.lo + r; y <= width + eps; y += r) ys.push_back(y);
    } else {
        for (double y = pile.lo + r; y <= pile.hi - r + eps; y += r) ys.push_back(y);
        if (ys.empty() || ys.back() < pile.hi - r - eps) ys.push_back(pile.hi - r);
    }
    return ys;
}

SectionalLayout read_sectional_layout(const Config& cfg, double r_ref) {
    const std::string name = cfg.choice_or("barrier.configuration", "custom",
                                           {"A", "B", "C", "D", "E", "F", "G", "H", "I", "L", "custom"});
    if (name != "custom") {
        for (const auto& layout : sectional_configurations()) {
            if (layout.name == name) return layout;
        }
    }
    SectionalLayout layout;
    layout.name = "custom";
    layout.piles = static_cast<int>(cfg.integer("barrier.piles", 2, 100));
    layout.pile_width = r_ref * cfg.real("barrier.pile_width_over_r", Range::positive());
    layout.outlet_width = r_ref * cfg.real("barrier.outlet_width_over_r", Range::positive());
    return layout;
}

}  // namespace

const std::vector<SectionalLayout>& sectional_configurations() {
    static const std::vector<SectionalLayout> table = {
        {"A", 8, 0.10, 4 * 0.05}, {"B", 7, 0.10, 5 * 0.05},  {"C", 6, 0.10, 6 * 0.05},
        {"D", 5, 0.10, 8 * 0.05}, {"E", 4, 0.10, 11 * 0.05}, {"F", 4, 0.33, 5 * 0.05},
        {"G", 5, 0.22, 5 * 0.05}, {"H", 4, 0.30, 6 * 0.05},  {"I", 5, 0.18, 6 * 0.05},
        {"L", 3, 0.42, 8 * 0.05},
    };
    return table;
}

std::vector<Span> sectional_piles(const Config& cfg, const std::string& key, double channel_width,
                                  const SectionalLayout& layout) {
    const int n = layout.piles;
    const double b = 0.5 * (channel_width - (n - 2) * layout.pile_width - (n - 1) * layout.outlet_width);
    if (n < 2 || b <= 0.0) {
        cfg.fail(key, fmt::format("{} piles of width {:.3f} m with {} outlets of {:.3f} m do not fit in the "
                                  "{:.2f} m channel (boundary pile width b = {:.3f} m must be > 0)",
                                  n, layout.pile_width, n - 1, layout.outlet_width, channel_width, b));
    }
    std::vector<Span> piles;
    double y = 0.0;
    for (int k = 0; k < n; ++k) {
        const double w = (k == 0 || k == n - 1) ? b : layout.pile_width;
        piles.push_back({y, k == n - 1 ? channel_width : y + w});
        y += w + layout.outlet_width;
    }
    return piles;
}

BarrierInfo build_barrier(const Config& cfg, const ChannelShape& channel, double r_ref,
                          std::vector<dem::Wall>& walls, dem::Particles& particles) {
    const double width = channel.width;
    BarrierInfo b;
    b.type = cfg.enum_or("barrier.type", BarrierType::slit, barrier_type_names);
    // the keys of the other barrier types may stay in a case file that a sweep or --set switches
    cfg.accept_unused({"barrier.outlet_width_over_r", "barrier.outlet_width_m", "barrier.configuration",
                       "barrier.piles", "barrier.pile_width_over_r"});
    if (b.type == BarrierType::mesh)
        throw std::logic_error("build_barrier: a mesh barrier is built by mesh_barrier()");
    if (b.type == BarrierType::none) {
        // no barrier, but the plane X = face_x stays the reference for "downstream" (non-retained
        // fraction, kinetic energy downstream): the no-barrier run a barrier is compared with
        cfg.accept_unused({"barrier.orientation", "barrier.model", "barrier.sphere_radius_m",
                           "barrier.thickness_m", "barrier.height_m"});
        b.face_x = cfg.real_or("barrier.face_x_m", 8.0, Range::open_closed(0.0, channel.length));
        b.height = channel.height;
        return b;
    }
    b.orientation = cfg.enum_or("barrier.orientation", BarrierOrientation::OB, barrier_orientation_names);
    b.model = cfg.enum_or("barrier.model", BarrierModel::spheres, barrier_model_names);
    // a barrier of its own height: below the channel's walls, the flow can overtop it (the domain's top,
    // channel.height_m, is then the air's)
    const double height =
        cfg.real_or("barrier.height_m", channel.height, Range::open_closed(0.0, channel.height));
    b.height = height;
    const double r_el = cfg.real_or("barrier.sphere_radius_m", 0.05, Range::positive());
    b.thickness = b.model == BarrierModel::spheres
                      ? 2.0 * r_el
                      : cfg.real_or("barrier.thickness_m", 0.10, Range::positive());

    // piles and outlets across the channel
    if (b.type == BarrierType::closed) {
        b.piles = {{0.0, width}};
    } else if (b.type == BarrierType::slit) {
        if (cfg.has("barrier.outlet_width_m")) {
            b.outlet_width = cfg.real("barrier.outlet_width_m", Range::open_closed(0.0, width));
        } else {
            b.outlet_width =
                r_ref * cfg.real("barrier.outlet_width_over_r", Range::open_closed(0.0, width / r_ref));
        }
        const double y_lo = 0.5 * (width - b.outlet_width), y_hi = 0.5 * (width + b.outlet_width);
        b.piles = {{0.0, y_lo}, {y_hi, width}};
    } else {  // sectional
        const SectionalLayout layout = read_sectional_layout(cfg, r_ref);
        b.configuration = layout.name;
        b.outlet_width = layout.outlet_width;
        b.pile_width = layout.pile_width;
        b.piles = sectional_piles(cfg, "barrier.configuration", width, layout);
    }
    for (std::size_t k = 1; k < b.piles.size(); ++k) b.outlets.push_back({b.piles[k - 1].hi, b.piles[k].lo});
    if (b.model == BarrierModel::spheres) {
        for (const auto& s : b.outlets) {
            if (s.width() < 1e-6)
                cfg.fail("barrier.outlet_width_over_r",
                         "outlet narrower than 1 µm: use barrier.type = \"closed\"");
        }
    }

    // VB: the face is vertical in the world frame, i.e. the plane X = face_x − Z tan θ.
    const double tilt = b.orientation == BarrierOrientation::VB ? channel.slope_deg * deg : 0.0;
    b.face_x = cfg.real_or("barrier.face_x_m", 8.0, Range::open_closed(0.0, channel.length));
    b.face_normal = {std::cos(tilt), 0.0, std::sin(tilt)};
    b.up = {-std::sin(tilt), 0.0, std::cos(tilt)};
    b.tan_tilt = std::tan(tilt);
    b.face_height = height / std::cos(tilt);
    const Vec3 nrm = b.face_normal, up = b.up;

    if (b.model == BarrierModel::boxes) {
        b.first_wall = walls.size();
        for (std::size_t k = 0; k < b.piles.size(); ++k) {
            const Span& p = b.piles[k];
            const Vec3 centre = Vec3{b.face_x, 0.5 * (p.lo + p.hi), 0} + nrm * (0.5 * b.thickness) +
                                up * (0.5 * b.face_height);
            walls.push_back(dem::Wall::box(b.piles.size() == 1 ? "barrier" : fmt::format("pile_{}", k),
                                           centre, {nrm, Vec3{0, 1, 0}, up},
                                           {0.5 * b.thickness, 0.5 * p.width(), 0.5 * b.face_height}, true));
            b.elements.push_back({false, walls.size() - 1, centre, 0.5 * b.face_height, static_cast<int>(k)});
        }
        b.wall_count = walls.size() - b.first_wall;
        return b;
    }
    // Reference modelling: fixed spheres of radius r_el, centres one radius apart on a grid in the
    // plane r_el downstream of the face.
    dem::check_sphere_budget(
        cfg, "barrier.sphere_radius_m",
        (width / r_el + 2.0 * static_cast<double>(b.piles.size())) * (b.face_height / r_el + 1.0),
        "barrier spheres");
    for (std::size_t k = 0; k < b.piles.size(); ++k) {
        for (double y : sphere_columns(b.piles[k], width, r_el)) {
            for (double h = 0.0; h <= b.face_height + eps; h += r_el) {
                const Vec3 c = Vec3{b.face_x, y, 0} + nrm * r_el + up * h;
                b.elements.push_back({true, particles.n_fixed(), c, h, static_cast<int>(k)});
                particles.add_fixed(c, r_el);
            }
        }
    }
    b.sphere_count = particles.n_fixed();
    return b;
}

}  // namespace sabo::scenario
