// SPDX-License-Identifier: MIT
#include "app/debris_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "analysis/barrier_forces.h"
#include "app/case_setup.h"
#include "app/fluid_loop.h"
#include "app/report_script.h"
#include "app/run_control.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/checkpoint.h"
#include "io/fluid_frames.h"
#include "io/json_writer.h"
#include "io/run_output.h"

namespace sabo::app {

PreparedDebris prepare_debris(const CaseRequest& req, const Config& cfg) {
    PreparedDebris pc;
    pc.scene = scenario::build_debris_case(cfg);
    const auto& s = pc.scene;
    pc.fluid = lbm::read_fluid_settings(cfg);
    const double dx = pc.fluid.units.dx();
    const auto cells = [&](double length) { return static_cast<int>(std::lround(length / dx)); };
    pc.shape = {
        cells(s.channel.length), cells(s.channel.width), cells(s.channel.height), {false, false, false}};
    if (s.barrier.present() && s.barrier.outlet_width > 0.0 && s.barrier.outlet_width < 2.0 * dx)
        cfg.fail("lattice.dx_m", fmt::format("the barrier's outlets ({} m) must span at least 2 cells",
                                             s.barrier.outlet_width));
    lbm::check_fluid_settings(cfg, pc.fluid, {s.velocity_scale, pc.shape}, available_memory_bytes());
    pc.frame_interval = cfg.real_or("output.frame_interval_s", s.end_time / 30.0, Range::positive());
    pc.series_interval = cfg.real_or("output.series_interval_s", s.end_time / 1000.0, Range::positive());
    pc.progress_interval = cfg.real_or("output.progress_interval_wall_s", 5.0, Range::positive());
    pc.report = cfg.boolean_or("output.report", true);
    pc.out_dir =
        req.out_dir ? *req.out_dir : std::filesystem::path(cfg.text_or("output.dir", "out/" + s.name));
    pc.checkpoint_interval = cfg.real_or("output.checkpoint_interval_wall_s", 600.0, Range::non_negative());
    pc.resume = req.resume;
    cfg.finish();
    pc.identity = case_identity(cfg);
    return pc;
}

void print_derived(const PreparedDebris& pc) {
    const auto& s = pc.scene;
    spdlog::info(
        "case '{}': debris (fluid only) in a {:.2f} x {:.2f} x {:.2f} m channel at {} deg; block X [{:.2f}, "
        "{:.2f}] x Z [0, {:.2f}] m; barrier {} {} {} at X = {:.2f} m ({} elements)",
        s.name, s.channel.length, s.channel.width, s.channel.height, s.channel.slope_deg, s.block_lo.x,
        s.block_hi.x, s.block_hi.z, s.barrier.type, s.barrier.orientation, s.barrier.model, s.barrier.face_x,
        s.barrier.elements.size());
    for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
    spdlog::info("velocity scale {:.3f} m/s; {} steps to t = {} s", s.velocity_scale,
                 static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time);
}

namespace {

Vec3 cell_centre(int x, int y, int z, double dx) {
    return {(x + 0.5) * dx, (y + 0.5) * dx, (z + 0.5) * dx};
}

// Barrier cells: a cell whose centre lies in a barrier element is an obstacle of element 1 + e
// (0 is the channel walls); inside several overlapping spheres it belongs to the nearest centre
// (SPEC §2.3). Returns the obstacle cell count per element.
template <class Real>
std::vector<std::size_t> mark_barrier(lbm::FluidLattice<Real>& l, const scenario::DebrisCase& s, double dx) {
    const auto& sh = l.shape();
    const std::size_t ne = s.barrier.elements.size();
    std::vector<std::size_t> count(ne, 0);
    std::vector<std::uint16_t> ids(ne);
    for (std::size_t e = 0; e < ne; ++e) ids[e] = l.add_element();
    // per stored cell (l.index)
    std::vector<float> best(lbm::FluidLattice<Real>::stored_cells(sh),
                            std::numeric_limits<float>::infinity());
    std::vector<std::int32_t> owner(best.size(), -1);
    for (std::size_t e = 0; e < ne; ++e) {
        const auto& el = s.barrier.elements[e];
        Vec3 lo, hi;
        if (el.sphere) {
            const double r = s.barrier_spheres.r[el.index];
            lo = el.centre - Vec3{r, r, r};
            hi = el.centre + Vec3{r, r, r};
        } else {
            const auto& w = s.walls[el.index];
            Vec3 ext{};
            for (int a = 0; a < 3; ++a) {
                const double h = a == 0 ? w.half.x : (a == 1 ? w.half.y : w.half.z);
                ext += Vec3{std::abs(w.axes[a].x), std::abs(w.axes[a].y), std::abs(w.axes[a].z)} * h;
            }
            lo = w.point - ext;
            hi = w.point + ext;
        }
        const auto first = [&](double v, int n) {
            return std::clamp(static_cast<int>(std::floor(v / dx - 0.5)), 0, n - 1);
        };
        const auto last = [&](double v, int n) {
            return std::clamp(static_cast<int>(std::ceil(v / dx - 0.5)), 0, n - 1);
        };
        for (int z = first(lo.z, sh.nz); z <= last(hi.z, sh.nz); ++z)
            for (int y = first(lo.y, sh.ny); y <= last(hi.y, sh.ny); ++y)
                for (int x = first(lo.x, sh.nx); x <= last(hi.x, sh.nx); ++x) {
                    const std::size_t k = l.index(x, y, z);
                    const Vec3 c = cell_centre(x, y, z, dx);
                    if (!scenario::inside_element(s, e, c)) continue;
                    const auto d = static_cast<float>(norm2(c - el.centre));
                    if (d < best[k]) {
                        best[k] = d;
                        owner[k] = static_cast<std::int32_t>(e);
                    }
                }
    }
    for (int z = 0; z < sh.nz; ++z)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = 0; x < sh.nx; ++x) {
                const std::int32_t e = owner[l.index(x, y, z)];
                if (e < 0) continue;
                l.set_obstacle(x, y, z, ids[static_cast<std::size_t>(e)]);
                ++count[static_cast<std::size_t>(e)];
            }
    return count;
}

template <class Real>
int run_lattice(const PreparedDebris& pc) {
    const auto& s = pc.scene;
    const auto& fs = pc.fluid;
    const auto& u = fs.units;
    const double dx = u.dx();
    lbm::FluidLattice<Real> l(pc.shape, fs.rheology);
    const auto& sh = l.shape();
    for (int z = 0; z < sh.nz; ++z)  // the block (cells whose centre lies inside)
        for (int y = 0; y < sh.ny; ++y)
            for (int x = 0; x < sh.nx; ++x) {
                const Vec3 c = cell_centre(x, y, z, dx);
                if (c.x < s.block_hi.x && c.y > s.block_lo.y && c.y < s.block_hi.y && c.z < s.block_hi.z)
                    l.set_fluid(x, y, z, 1.0, {});
            }
    const auto barrier_cells = mark_barrier(l, s, dx);
    std::size_t blocked = 0;
    for (const auto n : barrier_cells) blocked += n;
    l.prepare();
    l.set_acceleration({u.acceleration(s.gravity.x), 0.0, u.acceleration(s.gravity.z)});
    double m0 = l.total_mass();                     // a resumed run takes its start's
    const double fluid_volume = m0 * dx * dx * dx;  // lattice density 1 per cell
    const double sin_theta = std::sin(s.channel.slope_deg * std::numbers::pi / 180.0);
    // W sin θ, N (NaN on a level channel: the normalised columns are then empty)
    const double weight_along = sin_theta > 0.0 ? u.density() * s.channel.gravity * fluid_volume * sin_theta
                                                : std::numeric_limits<double>::quiet_NaN();
    spdlog::info(
        "fluid block {:.3f} m3 ({:.0f} kg), W sin(theta) = {:.4g} N; barrier: {} elements on {} lattice "
        "cells",
        fluid_volume, u.density() * fluid_volume, weight_along, barrier_cells.size(), blocked);

    RunControl control = lattice_run_control(pc.progress_interval);
    const std::size_t ne = s.barrier.elements.size();
    // the barrier force accounting of every run (SPEC §3), here with its fluid component only
    analysis::BarrierForceMonitor forces(s.barrier);
    io::FluidFrameWriter frames(pc.out_dir, u);
    double non_retained = 0.0, worst_drift = 0.0;
    // everything the run has accumulated, in the order a checkpoint holds it after the case's identity;
    // wall time, cell updates and series rows of the run's earlier parts (a resumed run)
    double wall_before = 0.0, updates_before = 0.0;
    std::uint64_t series_rows = 0;
    const auto transfer = [&](auto& archive, double& wall, double& updates) {
        archive(m0, worst_drift, non_retained, wall, updates, series_rows, l, forces, frames);
    };
    // a resumed run reads and checks the whole checkpoint before it touches the folder's files
    const std::filesystem::path checkpoint_file = pc.out_dir / "checkpoint.bin";
    if (pc.resume) {
        if (!std::filesystem::exists(checkpoint_file))
            throw InputError(
                fmt::format("--resume: no checkpoint {} (a debris run writes one every "
                            "output.checkpoint_interval_wall_s, when interrupted and at its end)",
                            checkpoint_file.string()));
        io::CheckpointIn in(checkpoint_file);
        std::string identity;
        in(identity);
        check_same_case(checkpoint_file, identity, pc.identity);
        transfer(in, wall_before, updates_before);
        in.expect_end();
        l.restored();
        spdlog::info("resumed from {} at t = {:.4f} s (step {})", checkpoint_file.string(),
                     static_cast<double>(l.steps()) * u.dt(), l.steps());
    }
    io::CsvSeries series(pc.out_dir / "series.csv",
                         {"time_s", "fluid_force_x_N", "fluid_force_y_N", "fluid_force_z_N",
                          "fluid_force_normal_N", "fluid_force_normal_over_W_sin_theta", "fluid_force_peak_N",
                          "fluid_non_retained_fraction", "front_x_m", "mass_relative_drift", "max_speed_m_s",
                          "interface_cells", "tau_min_cells", "tau_max_cells"},
                         pc.resume ? std::optional<std::uint64_t>(series_rows) : std::nullopt);
    std::vector<Vec3> fluid_on_element(ne);
    // the fluid's force on the barrier this step, N (every step: no peak is lost to the decimation)
    auto barrier_force = [&](double t) {
        const auto& f = l.element_forces();
        for (std::size_t e = 0; e < ne; ++e) fluid_on_element[e] = f[e + 1] * u.force_si(1.0);
        forces.record(t, {}, {}, fluid_on_element);
    };
    auto sample = [&](double t) {
        double downstream = 0.0, all = 0.0, front = 0.0;
        // one pass for the mass, the largest speed, the fluid downstream of the barrier and the front
        const lbm::FluidTotals now = l.totals([&](std::size_t k, double rho, const Vec3&) {
            const double m = l.fill(k) * rho;
            const auto [x, y, z] = l.coords(k);
            const Vec3 c = cell_centre(x, y, z, dx);
            all += m;
            if (s.barrier.present() && s.barrier.downstream(c)) downstream += m;
            if (l.fill(k) >= 0.1) front = std::max(front, c.x + 0.5 * dx);
        });
        non_retained = all > 0.0 ? downstream / all : 0.0;
        const double drift = (now.mass - m0) / m0;
        worst_drift = std::max(worst_drift, std::abs(drift));
        const double vmax = now.max_speed;
        const Vec3& total = forces.fluid_global();
        const double normal = forces.fluid_normal();
        series.row({t, total.x, total.y, total.z, normal, normal / weight_along, forces.take_interval_peak(),
                    non_retained, front, drift, u.velocity_si(vmax), static_cast<double>(l.interface_count()),
                    static_cast<double>(l.clamps().at_min), static_cast<double>(l.clamps().at_max)});
        check_fluid_stable(t, drift, vmax);
    };
    if (!pc.resume) {
        sample(0.0);
        frames.write(l, 0.0);
    }
    const auto checkpoint = [&](double t, double updates) {
        io::CheckpointOut out(checkpoint_file);
        std::string identity = pc.identity;
        double wall = wall_before + control.elapsed_s(), all_updates = updates_before + updates;
        series_rows = series.rows();
        out(identity);
        transfer(out, wall, all_updates);
        out.commit();
        spdlog::debug("checkpoint at t = {:.4f} s", t);
    };
    FluidLoopSchedule schedule = fluid_schedule(u.dt(), s.end_time, pc.series_interval, pc.frame_interval);
    schedule.checkpoint_wall_s = pc.checkpoint_interval;
    const FluidLoopEnd end = run_fluid_loop(
        l, schedule, control, barrier_force, sample, [&](double t) { frames.write(l, t); }, checkpoint);
    const int exit_code = end.exit_code;
    const std::string& failure = end.failure;
    const double t_end = end.time;
    forces.finish(t_end);
    io::write_force_maps(pc.out_dir, s.barrier, forces);
    const double peak_normal = forces.max_fluid_normal();
    // per element: where it is and the largest fluid force it received
    std::string csv = "element,pile,x_m,y_m,z_m,height_m,lattice_cells,max_fluid_force_N\n";
    for (std::size_t e = 0; e < ne; ++e) {
        const auto& el = s.barrier.elements[e];
        csv += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.6g}\n", e, el.pile, el.centre.x,
                           el.centre.y, el.centre.z, el.height, barrier_cells[e], forces.fluid_envelope()[e]);
    }
    io::write_text_atomically(pc.out_dir / "barrier_fluid_elements.csv", csv);
    const double wall = wall_before + control.elapsed_s();
    io::JsonObject js = summary_header(s.name, "debris", exit_code, failure, "end time", t_end, l.steps(),
                                       u.dt(), "lattice_cells", pc.shape.cells());
    js.number("solid_fraction", 0.0)
        .text("rheology", fs.rheology_name)
        .number("fluid_volume_m3", fluid_volume)
        .number("W_sin_theta_N", weight_along)
        .number("channel_width_m", s.channel.width)
        .number("barrier_face_x_m", s.barrier.face_x)
        .integer("barrier_elements", static_cast<std::int64_t>(ne))
        .integer("barrier_cells", static_cast<std::int64_t>(blocked))
        .number("fluid_force_normal_max_N", peak_normal)
        .number("fluid_force_normal_max_over_W_sin_theta", peak_normal / weight_along)
        .number("time_of_fluid_force_normal_max_s", forces.time_of_max_fluid_normal())
        .number("fluid_force_normal_end_N", forces.fluid_normal())
        .number("fluid_non_retained_fraction", non_retained);
    add_lattice_summary(js, fs, worst_drift, wall, updates_before + end.cell_updates);
    io::write_text_atomically(pc.out_dir / "summary.json", js.dump());
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {}; fluid force on the barrier: peak normal {:.4g} N = {:.3f} "
        "W sin(theta) at t = {:.3f} s; fluid non-retained {:.3f}; max relative mass drift {:.2e}",
        run_status(exit_code), t_end, l.steps(), format_duration(wall), peak_normal,
        peak_normal / weight_along, forces.time_of_max_fluid_normal(), non_retained, worst_drift);
    if (pc.report) run_report_script(pc.out_dir, "debris_report.py");
    return exit_code;
}

}  // namespace

int run_debris(const CaseRequest& req, const Config& cfg) {
    PreparedDebris pc = prepare_debris(req, cfg);
    open_run_folder(pc.out_dir, req.case_file, cfg, req.resume);
    print_derived(pc);
    return pc.fluid.single_precision ? run_lattice<float>(pc) : run_lattice<double>(pc);
}

}  // namespace sabo::app
