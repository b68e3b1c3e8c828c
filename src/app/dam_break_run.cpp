// SPDX-License-Identifier: MIT
#include "app/dam_break_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "app/case_setup.h"
#include "app/fluid_loop.h"
#include "app/report_script.h"
#include "app/run_control.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/fluid_frames.h"
#include "io/json_writer.h"
#include "io/run_output.h"

namespace sabo::app {

PreparedDamBreak prepare_dam_break(const CaseRequest& req, const Config& cfg) {
    PreparedDamBreak pc;
    pc.scene = scenario::read_dam_break_case(cfg);
    const auto& s = pc.scene;
    pc.fluid = lbm::read_fluid_settings(cfg);
    const double dx = pc.fluid.units.dx();
    const auto cells = [&](double length) { return static_cast<int>(std::lround(length / dx)); };
    pc.shape = {cells(s.tank_length), s.width_cells, cells(s.tank_height), {false, true, false}};
    pc.column_cells = cells(s.column_width);
    pc.height_cells = cells(s.column_height);
    if (pc.column_cells < 4 || pc.height_cells < 4)
        cfg.fail("lattice.dx_m",
                 fmt::format("the column must span at least 4 cells each way (a = {} cells, h = {} "
                             "cells): refine dx",
                             pc.column_cells, pc.height_cells));
    lbm::check_fluid_settings(cfg, pc.fluid, {s.velocity_scale(), pc.shape}, available_memory_bytes());
    pc.frame_interval = cfg.real_or("output.frame_interval_s", s.end_time / 20.0, Range::positive());
    pc.series_interval = cfg.real_or("output.series_interval_s", s.end_time / 500.0, Range::positive());
    pc.progress_interval = cfg.real_or("output.progress_interval_wall_s", 5.0, Range::positive());
    pc.report = cfg.boolean_or("output.report", true);
    pc.out_dir =
        req.out_dir ? *req.out_dir : std::filesystem::path(cfg.text_or("output.dir", "out/" + s.name));
    cfg.record("derived.column_width_cells", static_cast<std::int64_t>(pc.column_cells));
    cfg.record("derived.column_height_cells", static_cast<std::int64_t>(pc.height_cells));
    cfg.finish();
    return pc;
}

void print_derived(const PreparedDamBreak& pc) {
    const auto& s = pc.scene;
    const double dx = pc.fluid.units.dx();
    spdlog::info(
        "case '{}': dam break, column a = {:.4f} m x h = {:.4f} m ({} x {} cells) in a tank {:.4f} x {:.4f} "
        "m, "
        "{} cells across (periodic)",
        s.name, pc.column_cells * dx, pc.height_cells * dx, pc.column_cells, pc.height_cells, s.tank_length,
        s.tank_height, s.width_cells);
    for (const auto& line : lbm::describe(pc.fluid)) spdlog::info("{}", line);
    spdlog::info("velocity scale 2 sqrt(g h) = {:.3f} m/s; {} steps to t = {} s", s.velocity_scale(),
                 static_cast<long>(std::ceil(s.end_time / pc.fluid.units.dt())), s.end_time);
}

namespace {

// The front along the floor (mid-slab row): the downstream face of the last bottom cell holding at
// least a tenth of a cell of fluid (the tip the experiment's observers followed, not the body of the
// surge: with 0.5 the front lags the tip by a cell or two and reads up to 7 % short late in the run).
template <class Real>
double front_cells(const lbm::FluidLattice<Real>& l) {
    const auto& sh = l.shape();
    int last = -1;
    for (int x = 0; x < sh.nx; ++x)
        if (l.fill(l.index(x, sh.ny / 2, 0)) >= 0.1) last = x;
    return last + 1.0;
}

// Height of the water at the left wall (the column's remains), cells.
template <class Real>
double wall_height_cells(const lbm::FluidLattice<Real>& l) {
    const auto& sh = l.shape();
    double h = 0.0;
    for (int z = 0; z < sh.nz; ++z) h += l.fill(l.index(0, sh.ny / 2, z));
    return h;
}

template <class Real>
int run_lattice(const PreparedDamBreak& pc) {
    const auto& s = pc.scene;
    const auto& fs = pc.fluid;
    const auto& u = fs.units;
    lbm::FluidLattice<Real> l(pc.shape, fs.rheology);
    for (int z = 0; z < pc.height_cells; ++z)
        for (int y = 0; y < pc.shape.ny; ++y)
            for (int x = 0; x < pc.column_cells; ++x) l.set_fluid(x, y, z, 1.0, {});
    l.prepare();  // the column's faces toward the gas become interface cells
    l.set_acceleration({0.0, 0.0, -u.acceleration(s.gravity)});
    const double a = pc.column_cells * u.dx();
    const double t_scale = std::sqrt(2.0 * s.gravity / a);
    const double m0 = l.total_mass();

    io::FluidFrameWriter frames(pc.out_dir, u);
    io::CsvSeries series(pc.out_dir / "series.csv", {"time_s", "T_scaled", "front_m", "front_over_a",
                                                     "wall_height_m", "mass_relative_drift", "max_speed_m_s",
                                                     "interface_cells", "tau_min_cells", "tau_max_cells"});
    RunControl control = lattice_run_control(pc.progress_interval);
    std::vector<double> times, fronts;
    double worst_drift = 0.0;
    auto sample = [&](double t) {
        const lbm::FluidTotals now = l.totals();
        const double vmax = now.max_speed;
        const double drift = (now.mass - m0) / m0;
        worst_drift = std::max(worst_drift, std::abs(drift));
        const double front = front_cells(l) * u.dx();
        times.push_back(t * t_scale);
        fronts.push_back(front / a);
        series.row({t, t * t_scale, front, front / a, wall_height_cells(l) * u.dx(), drift,
                    u.velocity_si(vmax), static_cast<double>(l.interface_count()),
                    static_cast<double>(l.clamps().at_min), static_cast<double>(l.clamps().at_max)});
        check_fluid_stable(t, drift, vmax);
    };
    sample(0.0);
    frames.write(l, 0.0);
    const FluidLoopEnd end = run_fluid_loop(
        l, fluid_schedule(u.dt(), s.end_time, pc.series_interval, pc.frame_interval), control, [](double) {},
        sample, [&](double t) { frames.write(l, t); }, [](double, double) {});  // minutes: no checkpoints
    const int exit_code = end.exit_code;
    const std::string& failure = end.failure;
    const double t_end = end.time;

    // the front against Martin & Moyce at their times (linear interpolation of the series)
    std::vector<io::JsonObject> points;
    double sum2 = 0.0;
    int compared = 0;
    for (const auto& p : scenario::martin_moyce_front) {
        if (times.empty() || p.t_scaled > times.back()) break;
        const auto it = std::lower_bound(times.begin(), times.end(), p.t_scaled);
        const auto j = static_cast<std::size_t>(it - times.begin());
        double z = fronts[j];
        if (j > 0) {
            const double w = (p.t_scaled - times[j - 1]) / (times[j] - times[j - 1]);
            z = fronts[j - 1] + w * (fronts[j] - fronts[j - 1]);
        }
        io::JsonObject o;
        o.number("T", p.t_scaled)
            .number("front_over_a_experiment", p.front_over_a)
            .number("front_over_a_sabo", z);
        points.push_back(o);
        sum2 += (z / p.front_over_a - 1.0) * (z / p.front_over_a - 1.0);
        ++compared;
    }
    const double wall = control.elapsed_s();
    io::JsonObject js = summary_header(s.name, "dam_break", exit_code, failure, "end time", t_end, l.steps(),
                                       u.dt(), "lattice_cells", pc.shape.cells());
    js.number("column_width_m", a)
        .number("column_height_m", pc.height_cells * u.dx())
        .number("front_final_over_a", fronts.empty() ? 0.0 : fronts.back())
        .number("front_rms_relative_error_vs_martin_moyce",
                compared > 0 ? std::sqrt(sum2 / compared) : io::not_a_number)
        .objects("front_vs_martin_moyce", points);
    add_lattice_summary(js, fs, worst_drift, wall, end.cell_updates);
    io::write_text_atomically(pc.out_dir / "summary.json", js.dump());
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {}; front {:.3f} a; RMS deviation from Martin & Moyce {:.1f} % "
        "over {} points; max relative mass drift {:.2e}",
        run_status(exit_code), t_end, l.steps(), format_duration(wall), fronts.empty() ? 0.0 : fronts.back(),
        compared > 0 ? 100.0 * std::sqrt(sum2 / compared) : 0.0, compared, worst_drift);
    if (pc.report) run_report_script(pc.out_dir, "dam_break_report.py");
    return exit_code;
}

}  // namespace

int run_dam_break(const CaseRequest& req, const Config& cfg) {
    PreparedDamBreak pc = prepare_dam_break(req, cfg);
    open_run_folder(pc.out_dir, req.case_file, cfg);
    print_derived(pc);
    return pc.fluid.single_precision ? run_lattice<float>(pc) : run_lattice<double>(pc);
}

}  // namespace sabo::app
