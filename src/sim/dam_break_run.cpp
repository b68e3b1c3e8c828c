// SPDX-License-Identifier: MIT
#include "sim/dam_break_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "analysis/dam_break_front.h"
#include "core/error.h"
#include "core/memory.h"
#include "io/atomic_file.h"
#include "io/json_writer.h"
#include "io/report_script.h"
#include "io/run_output.h"
#include "sim/frame_observers.h"
#include "sim/run_checkpoint.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/run_summary.h"
#include "sim/simulation.h"

namespace sabo::sim {

PreparedDamBreak prepare_dam_break(const RunRequest& req, const Config& cfg) {
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
    pc.output = read_output_settings(cfg, req, s.name, s.end_time / 20.0, s.end_time / 500.0);
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
// Global cells, over every rank's own planes.
template <class Real>
double front_cells(const lbm::FluidLattice<Real>& l, const Domain& domain) {
    const auto& sh = l.shape();
    int last = -1;
    for (int x = l.own_begin(); x < l.own_end(); ++x)
        if (l.fill(l.index(x, sh.ny / 2, 0)) >= 0.1) last = domain.global_x(x);
    return domain.max(last + 1.0);
}

// Height of the water at the left wall (the column's remains), cells.
template <class Real>
double wall_height_cells(const lbm::FluidLattice<Real>& l, const Domain& domain) {
    const auto& sh = l.shape();
    double h = 0.0;
    if (domain.global_x(l.own_begin()) == 0)  // the rank that owns the first plane
        for (int z = 0; z < sh.nz; ++z) h += l.fill(l.index(l.own_begin(), sh.ny / 2, z));
    return domain.sum(h);
}

// The front, the height at the wall and the lattice's health at every series row; the front's history
// for the comparison with the experiment.
class DamBreakObserver final : public Checkpointed<DamBreakObserver> {
  public:
    DamBreakObserver(const PreparedDamBreak& pc, double mass0, const Domain& domain)
        : dx_(pc.fluid.units.dx()),
          a_(pc.column_cells * dx_),
          t_scale_(std::sqrt(2.0 * pc.scene.gravity / a_)),
          m0_(mass0),
          units_(pc.fluid.units),
          max_mass_drift_(pc.fluid.max_mass_drift),
          series_(domain.writes_outputs() ? pc.output.out_dir / "series.csv" : std::filesystem::path(),
                  {"time_s", "T_scaled", "front_m", "front_over_a", "wall_height_m", "mass_relative_drift",
                   "max_speed_m_s", "interface_cells", "tau_min_cells", "tau_max_cells"}) {}

    bool sample(Simulation& sim) override {
        const double t = sim.time();
        const Domain& domain = sim.domain();  // (a divided run's slabs may have moved)
        sim.with_fluid([&](const auto& l) {
            const lbm::FluidTotals now = l.totals();
            const double vmax = domain.max(now.max_speed);
            const double drift = (domain.sum(now.mass) - m0_) / m0_;
            worst_drift_ = std::max(worst_drift_, std::abs(drift));
            const double front = front_cells(l, domain) * dx_;
            const double wall = wall_height_cells(l, domain) * dx_;
            times_.push_back(t * t_scale_);
            fronts_.push_back(front / a_);
            // (a divided run's clamp counts include the ghost planes, counted by both neighbours)
            series_.row({t, t * t_scale_, front, front / a_, wall, drift, units_.velocity_si(vmax),
                         domain.sum(static_cast<double>(l.interface_count())),
                         domain.sum(static_cast<double>(l.clamps().at_min)),
                         domain.sum(static_cast<double>(l.clamps().at_max))});
            lbm::check_fluid_stable(t, drift, vmax, max_mass_drift_);
        });
        return false;
    }

    [[nodiscard]] double worst_drift() const { return worst_drift_; }
    [[nodiscard]] const std::vector<double>& times() const { return times_; }    // T
    [[nodiscard]] const std::vector<double>& fronts() const { return fronts_; }  // x / a
    // The history so far (io/checkpoint.h).
    template <class Archive>
    void transfer(Archive& a) {
        a(m0_, series_, times_, fronts_, worst_drift_);
    }

  private:
    double dx_, a_, t_scale_, m0_;
    lbm::UnitConverter units_;
    double max_mass_drift_;
    io::CsvSeries series_;
    std::vector<double> times_, fronts_;
    double worst_drift_ = 0.0;
};

// The rank's lattice (the whole one undivided) with the column.
template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> column_lattice(const PreparedDamBreak& pc, const Domain& domain) {
    const auto& u = pc.fluid.units;
    auto l = domain.make_lattice<Real>(pc.shape, pc.fluid.rheology);
    for (int z = 0; z < pc.height_cells; ++z)
        for (int y = 0; y < pc.shape.ny; ++y)
            for (int x = 0; x < l->shape().nx; ++x)
                if (domain.global_x(x) < pc.column_cells) l->set_fluid(x, y, z, 1.0, {});
    l->prepare();  // the column's faces toward the gas become interface cells
    l->set_acceleration({0.0, 0.0, -u.acceleration(pc.scene.gravity)});
    return l;
}

}  // namespace

int run_dam_break(const RunRequest& req, const Config& cfg) {
    PreparedDamBreak pc = prepare_dam_break(req, cfg);
    const auto& out = pc.output;
    const auto& s = pc.scene;
    const auto& fs = pc.fluid;
    const auto& u = fs.units;
    Domain whole{.origin = {}, .dx = u.dx(), .box = {s.tank_length, pc.shape.ny * u.dx(), s.tank_height}};
    if (req.world != nullptr) whole.divide(*req.world, pc.shape.nx);
    open_run_folder(out.out_dir, req.case_file, cfg, req.resume, whole);
    print_derived(pc);
    Simulation sim = fs.single_precision ? Simulation(column_lattice<float>(pc, whole), u.dt(), whole)
                                         : Simulation(column_lattice<double>(pc, whole), u.dt(), whole);
    const Domain& domain = sim.domain();
    const double m0 = domain.sum(sim.with_fluid([](const auto& l) { return l.total_mass(); }));
    DamBreakObserver front(pc, m0, domain);
    FluidFrames frames(out.out_dir, u);
    RunControl control(out.progress_interval, 0);
    control.set_ends_at_end_time();
    const std::vector<Observer*> observers{&front, &frames};
    RunCheckpoint checkpoint(out.out_dir, cfg, domain);
    if (req.resume) checkpoint.load(sim, observers);
    Schedule at = make_schedule(u.dt(), s.end_time, out.series_interval, out.frame_interval);
    at.progress_every = 16;
    checkpoint.schedule(at, out, sim, observers, control, req.resume);
    const RunEnd end = run(sim, at, observers, control);
    const int exit_code = end.exit_code;
    const double t_end = end.time;

    const analysis::FrontComparison vs = analysis::compare_with_martin_moyce(front.times(), front.fronts());
    std::vector<io::JsonObject> points;
    for (const auto& p : vs.points) {
        io::JsonObject o;
        o.number("T", p.t_scaled)
            .number("front_over_a_experiment", p.experiment)
            .number("front_over_a_sabo", p.simulation);
        points.push_back(o);
    }
    const double a = pc.column_cells * u.dx();
    const double final_front = front.fronts().empty() ? 0.0 : front.fronts().back();
    const double wall = checkpoint.wall_before() + control.elapsed_s();
    const double own_work = checkpoint.work_before() + end.work;
    const double work = domain.sum(own_work);
    const DivisionSummary division = summarise_division(sim, own_work, control.elapsed_s());
    if (!domain.writes_outputs()) return exit_code;  // the first rank writes the summary and the report
    io::JsonObject js = summary_header(s.name, "dam_break", end, sim, "lattice_cells", pc.shape.cells());
    js.number("column_width_m", a)
        .number("column_height_m", pc.height_cells * u.dx())
        .number("front_final_over_a", final_front)
        .number("front_rms_relative_error_vs_martin_moyce",
                vs.points.empty() ? io::not_a_number : vs.rms_relative_error)
        .objects("front_vs_martin_moyce", points);
    add_division_summary(js, division);
    add_lattice_summary(js, fs, front.worst_drift(), wall, work);
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {}; front {:.3f} a; RMS deviation from Martin & Moyce {:.1f} % "
        "over {} points; max relative mass drift {:.2e}",
        run_status(exit_code), t_end, sim.steps(), format_duration(wall), final_front,
        100.0 * vs.rms_relative_error, vs.points.size(), front.worst_drift());
    if (out.report) io::run_report_script(out.out_dir, "dam_break_report.py");
    checkpoint.tell_how_to_resume(exit_code);
    return exit_code;
}

}  // namespace sabo::sim
