// SPDX-License-Identifier: MIT
#include "cases/channel/channel_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "dem/grain_budget.h"
#include "scenario/mesh_barrier.h"
#include "sim/run_summary.h"

namespace sabo::cases {

PreparedCase prepare_channel(const sim::RunRequest& req, const Config& cfg) {
    PreparedCase pc;
    pc.scene = scenario::build_channel_case(cfg, req.place_grains);
    const auto& rel = pc.scene.release;
    if (pc.scene.barrier.present() && rel.hi.x > pc.scene.barrier.face_x - 0.01) {
        cfg.fail("release.front_x_m",
                 fmt::format("the released block (front at X = {:.3f} m) reaches the barrier face "
                             "(X = {:.3f} m)",
                             rel.hi.x, pc.scene.barrier.face_x));
    }
    double r_min = rel.r_min, r_max = rel.r_max;
    if (const auto& in = pc.scene.inflow) {  // the contacts and the lists for the inflow's grains too
        r_min = rel.count > 0 ? std::min(r_min, in->r_min()) : in->r_min();
        r_max = rel.count > 0 ? std::max(r_max, in->r_max()) : in->r_max();
    }
    pc.dem = dem::read_dem_settings(cfg, {r_min, r_max, rel.density, pc.scene.velocity_scale});
    const double end = pc.scene.end_time;
    pc.output = sim::read_output_settings(cfg, req, pc.scene.name, end / 50.0, std::min(0.01, end / 100.0));
    AnalysisSettings& an = pc.analysis;
    an.arching_depth = rel.r_mean * cfg.real_or("analysis.arching_depth_over_r", 4.0, Range::positive());
    an.arching_intervals = static_cast<int>(cfg.integer_or("analysis.arching_intervals", 10, 1, 1000));
    an.arching_threshold = cfg.real_or("analysis.arching_threshold_J", 1e-5, Range::positive());
    an.upstream_reach = cfg.real_or("analysis.upstream_reach_m", 1.0, Range::positive());
    an.gauge = read_gauge_settings(cfg, pc.scene.barrier.face_x, pc.scene.width, 2.0 * rel.r_mean,
                                   pc.scene.channel_mesh.get());
    an.stop_enabled = cfg.boolean_or("stop.enabled", true);
    // with an inflow: the grains it brings count, and no stop before it ends
    double grains = static_cast<double>(rel.count);
    if (const auto& in = pc.scene.inflow) {
        grains += in->hydrograph.solid_volume(in->hydrograph.start(), in->hydrograph.end()) /
                  dem::sphere_volume(in->radius);
        an.stop_not_before = in->hydrograph.end();
    }
    an.stop_threshold = grains * cfg.real_or("stop.kinetic_energy_per_grain_J", 1e-6, Range::positive());
    an.stop_hold = cfg.real_or("stop.hold_s", 1.0, Range::positive());
    if (pc.output.series_interval < pc.dem.dt) {
        cfg.fail("output.series_interval_s",
                 fmt::format("must be at least the time step {:.4g} s", pc.dem.dt));
    }
    cfg.record("derived.particles", static_cast<std::int64_t>(rel.count));
    cfg.record("derived.solid_volume_m3", rel.solid_volume);
    cfg.record("derived.barrier_spheres", static_cast<std::int64_t>(pc.scene.barrier.sphere_count));
    cfg.record("derived.velocity_scale_m_s", pc.scene.velocity_scale);
    cfg.finish();

    sim::check_memory(cfg, pc.scene.particles.n_fixed() + rel.count);
    return pc;
}

void print_derived(const PreparedCase& pc) {
    const auto& s = pc.scene;
    const auto& d = pc.dem;
    const bool open_top = s.bounds.top == scenario::ChannelTop::open;
    spdlog::info("case '{}': channel {:.2f} x {:.2f} x {:.2f} m, slope {:.1f} deg; {}; {}", s.name, s.length,
                 s.width, s.height, s.slope_deg,
                 open_top ? fmt::format("open above the walls to {:.2f} m (grains over the walls leave)",
                                        s.bounds.domain_height)
                          : std::string("a lid on the walls"),
                 s.bounds.end == scenario::ChannelEnd::open ? "the end open (grains past it leave)"
                                                            : "a wall at the end");
    if (s.channel_mesh) spdlog::info("{}", scenario::describe_channel_mesh(*s.channel_mesh));
    if (const std::string w = scenario::open_top_mesh_warning(s.bounds, s.channel_mesh.get(), s.height);
        !w.empty())
        spdlog::warn("{}", w);
    for (const std::string& w :
         scenario::fine_mesh_warnings(s.barrier.mesh.get(), s.channel_mesh.get(), s.release.r_min))
        spdlog::warn("{}", w);
    spdlog::info(
        "release: {} grains, V_s = {:.4f} m3, r in [{:.4f}, {:.4f}] m, extents X [{:.3f}, {:.3f}] "
        "Y [{:.3f}, {:.3f}] Z [{:.3f}, {:.3f}] m",
        s.release.count, s.release.solid_volume, s.release.r_min, s.release.r_max, s.release.lo.x,
        s.release.hi.x, s.release.lo.y, s.release.hi.y, s.release.lo.z, s.release.hi.z);
    spdlog::info("release lattice rule: {}", s.release.lattice_rule);
    if (const auto& in = s.inflow) {
        const auto& h = in->hydrograph;
        spdlog::info(
            "inflow: {} rows over t [{:.3g}, {:.3g}] s, solid volume {:.4g} m3 (of {:.4g} m3 in all), Q up "
            "to "
            "{:.4g} m3/s; grains r = {:.4f} m{} +-{:.0f} %, placed in X [{:.3f}, {:.3f}] m at {:.3g} m/s{}",
            h.rows(), h.start(), h.end(), h.solid_volume(h.start(), h.end()), h.volume(h.start(), h.end()),
            h.largest_discharge(), in->radius, h.graded() ? " (graded: the hydrograph's radius_mean_m)" : "",
            100.0 * in->spread, in->x0, in->x0 + in->length, in->velocity, scenario::inflow_bed_note(*in));
    }
    if (s.release.mixture == scenario::Mixture::bidisperse) {
        spdlog::info(
            "bidisperse: R = {:.4f} m, r = {:.4f} m, phi_small = {:.3f}, r* = {:.4f} m, {} compaction",
            s.release.r_large, s.release.r_small, s.release.phi_small, s.release.equivalent_radius,
            scenario::name(s.release.compaction));
    }
    if (s.barrier.mesh) {
        spdlog::info("barrier: from a mesh, face X = {:.3f} m, first outlet {:.3f} m, {} parts as walls",
                     s.barrier.face_x, s.barrier.outlet_width, s.barrier.wall_count);
        spdlog::info("{}", scenario::describe_mesh(s.barrier));
    } else if (s.barrier.present()) {
        spdlog::info(
            "barrier: {} {}, {} model, face X = {:.3f} m, outlet {:.3f} m, {} fixed spheres, {} boxes",
            scenario::name(s.barrier.type), scenario::name(s.barrier.orientation),
            scenario::name(s.barrier.model), s.barrier.face_x, s.barrier.outlet_width, s.barrier.sphere_count,
            s.barrier.wall_count);
    }
    spdlog::info("{}", dem::describe_contact(d));
    spdlog::info("time step: t_c = {:.4e} s, dt = {:.4e} s, dt/t_c = 1/{:.1f}; {:.0f} steps to t = {:.3g} s",
                 d.contact_time, d.dt, d.steps_per_contact, std::ceil(s.end_time / d.dt), s.end_time);
    sim::log_expected_overlap(s.velocity_scale, d.expected_max_overlap_ratio, "d_min");
    const std::size_t spheres = s.particles.n_fixed() + s.release.count;  // `sabo check` places no grains
    spdlog::info("memory estimate: {:.1f} MiB ({} spheres incl. fixed); neighbour skin {:.4f} m",
                 dem::memory_estimate_bytes(static_cast<double>(spheres)) / 1048576.0, spheres, d.skin);
}

}  // namespace sabo::cases
