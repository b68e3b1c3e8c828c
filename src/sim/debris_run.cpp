// SPDX-License-Identifier: MIT
#include "sim/debris_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "analysis/barrier_forces.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/barrier_output.h"
#include "io/checkpoint.h"
#include "io/json_writer.h"
#include "io/report_script.h"
#include "io/run_output.h"
#include "scenario/debris_lattice.h"
#include "sim/frame_observers.h"
#include "sim/run_control.h"
#include "sim/run_loop.h"
#include "sim/run_summary.h"
#include "sim/simulation.h"

namespace sabo::sim {

PreparedDebris prepare_debris(const RunRequest& req, const Config& cfg) {
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
    pc.output = read_output_settings(cfg, req, s.name, s.end_time / 30.0, s.end_time / 1000.0);
    pc.checkpoint_interval = cfg.real_or("output.checkpoint_interval_wall_s", 600.0, Range::non_negative());
    pc.resume = req.resume;
    cfg.finish();
    pc.identity = io::case_identity(cfg);
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

// The fluid's force on the barrier after every step (no peak is lost to the decimation), the fluid
// downstream of the barrier, the front and the lattice's health at every series row.
class DebrisObserver final : public Observer {
  public:
    DebrisObserver(const PreparedDebris& pc, double weight_along)
        : pc_(pc),
          weight_along_(weight_along),
          forces_(pc.scene.barrier),
          fluid_on_element_(pc.scene.barrier.elements.size()) {}

    // What a checkpoint holds of the observer besides its series' row count.
    struct State {
        double m0 = 0.0;  // lattice mass at the start of the run (a resumed run keeps its start's)
        double worst_drift = 0.0, non_retained = 0.0;
    };
    [[nodiscard]] State& state() { return state_; }
    [[nodiscard]] analysis::BarrierForceMonitor& forces() { return forces_; }
    // The series: a new file, or (resuming) the file cut back to the rows the checkpoint had.
    void open_series(std::optional<std::uint64_t> resume_rows) {
        series_.emplace(
            pc_.output.out_dir / "series.csv",
            std::vector<std::string>{"time_s", "fluid_force_x_N", "fluid_force_y_N", "fluid_force_z_N",
                                     "fluid_force_normal_N", "fluid_force_normal_over_W_sin_theta",
                                     "fluid_force_peak_N", "fluid_non_retained_fraction", "front_x_m",
                                     "mass_relative_drift", "max_speed_m_s", "interface_cells",
                                     "tau_min_cells", "tau_max_cells"},
            resume_rows);
    }
    [[nodiscard]] std::uint64_t series_rows() const { return series_->rows(); }

    void after_step(Simulation& sim) override {
        const double force_unit = pc_.fluid.units.force_si(1.0);
        sim.with_fluid([&](const auto& l) {
            const auto& f = l.element_forces();
            for (std::size_t e = 0; e < fluid_on_element_.size(); ++e)
                fluid_on_element_[e] = f[e + 1] * force_unit;
        });
        forces_.record(sim.time(), {}, {}, fluid_on_element_);
    }

    bool sample(Simulation& sim) override {
        const auto& s = pc_.scene;
        const auto& u = pc_.fluid.units;
        const Domain& d = sim.domain();
        const double t = sim.time();
        sim.with_fluid([&](const auto& l) {
            double downstream = 0.0, all = 0.0, front = 0.0;
            // one pass for the mass, the largest speed, the fluid downstream of the barrier and the front
            const lbm::FluidTotals now = l.totals([&](std::size_t k, double rho, const Vec3&) {
                const double m = l.fill(k) * rho;
                const auto [x, y, z] = l.coords(k);
                const Vec3 c = d.cell_centre(x, y, z);
                all += m;
                if (s.barrier.present() && s.barrier.downstream(c)) downstream += m;
                if (l.fill(k) >= 0.1) front = std::max(front, c.x + 0.5 * d.dx);
            });
            state_.non_retained = all > 0.0 ? downstream / all : 0.0;
            const double drift = (now.mass - state_.m0) / state_.m0;
            state_.worst_drift = std::max(state_.worst_drift, std::abs(drift));
            const double vmax = now.max_speed;
            const Vec3& total = forces_.fluid_global();
            const double normal = forces_.fluid_normal();
            series_->row({t, total.x, total.y, total.z, normal, normal / weight_along_,
                          forces_.take_interval_peak(), state_.non_retained, front, drift,
                          u.velocity_si(vmax), static_cast<double>(l.interface_count()),
                          static_cast<double>(l.clamps().at_min), static_cast<double>(l.clamps().at_max)});
            lbm::check_fluid_stable(t, drift, vmax);
        });
        return false;
    }

  private:
    const PreparedDebris& pc_;
    double weight_along_;
    analysis::BarrierForceMonitor forces_;
    std::vector<Vec3> fluid_on_element_;
    std::optional<io::CsvSeries> series_;
    State state_;
};

template <class Real>
std::unique_ptr<lbm::FluidLattice<Real>> debris_lattice(const PreparedDebris& pc,
                                                        std::vector<std::size_t>& barrier_cells) {
    const auto& s = pc.scene;
    const auto& u = pc.fluid.units;
    auto l = std::make_unique<lbm::FluidLattice<Real>>(pc.shape, pc.fluid.rheology);
    scenario::fill_fluid_block(*l, s, u.dx());
    barrier_cells = scenario::mark_barrier(*l, s, u.dx());
    l->prepare();
    l->set_acceleration({u.acceleration(s.gravity.x), 0.0, u.acceleration(s.gravity.z)});
    return l;
}

}  // namespace

int run_debris(const RunRequest& req, const Config& cfg) {
    PreparedDebris pc = prepare_debris(req, cfg);
    const auto& out = pc.output;
    open_run_folder(out.out_dir, req.case_file, cfg, req.resume);
    print_derived(pc);
    const auto& s = pc.scene;
    const auto& fs = pc.fluid;
    const auto& u = fs.units;
    const double dx = u.dx();
    std::vector<std::size_t> barrier_cells;
    const Domain domain{{}, dx, {s.channel.length, s.channel.width, s.channel.height}};
    Simulation sim = fs.single_precision
                         ? Simulation(debris_lattice<float>(pc, barrier_cells), u.dt(), domain)
                         : Simulation(debris_lattice<double>(pc, barrier_cells), u.dt(), domain);
    std::size_t blocked = 0;
    for (const auto n : barrier_cells) blocked += n;
    const double m_start = sim.with_fluid([](const auto& l) { return l.total_mass(); });
    const double fluid_volume = m_start * dx * dx * dx;  // lattice density 1 per cell
    const double sin_theta = std::sin(s.channel.slope_deg * std::numbers::pi / 180.0);
    // W sin θ, N (NaN on a level channel: the normalised columns are then empty)
    const double weight_along = sin_theta > 0.0 ? u.density() * s.channel.gravity * fluid_volume * sin_theta
                                                : std::numeric_limits<double>::quiet_NaN();
    spdlog::info(
        "fluid block {:.3f} m3 ({:.0f} kg), W sin(theta) = {:.4g} N; barrier: {} elements on {} lattice "
        "cells",
        fluid_volume, u.density() * fluid_volume, weight_along, barrier_cells.size(), blocked);

    RunControl control(out.progress_interval, 0);
    control.set_ends_at_end_time();
    const std::size_t ne = s.barrier.elements.size();
    DebrisObserver debris(pc, weight_along);
    debris.state().m0 = m_start;
    FluidFrames frames(out.out_dir, u);
    // everything the run has accumulated, in the order a checkpoint holds it after the case's identity;
    // wall time, cell updates and series rows of the run's earlier parts (a resumed run)
    double wall_before = 0.0, updates_before = 0.0;
    std::uint64_t series_rows = 0;
    const auto transfer = [&](auto& archive, double& wall, double& updates) {
        auto& st = debris.state();
        sim.with_fluid([&](auto& l) {
            archive(st.m0, st.worst_drift, st.non_retained, wall, updates, series_rows, l, debris.forces(),
                    frames);
        });
    };
    // a resumed run reads and checks the whole checkpoint before it touches the folder's files
    const std::filesystem::path checkpoint_file = out.out_dir / "checkpoint.bin";
    if (req.resume) {
        if (!std::filesystem::exists(checkpoint_file))
            throw InputError(
                fmt::format("--resume: no checkpoint {} (a debris run writes one every "
                            "output.checkpoint_interval_wall_s, when interrupted and at its end)",
                            checkpoint_file.string()));
        io::CheckpointIn in(checkpoint_file);
        std::string identity;
        in(identity);
        io::check_same_case(checkpoint_file, identity, pc.identity);
        transfer(in, wall_before, updates_before);
        in.expect_end();
        sim.with_fluid([](auto& l) { l.restored(); });
        sim.restored();
        spdlog::info("resumed from {} at t = {:.4f} s (step {})", checkpoint_file.string(), sim.time(),
                     sim.steps());
    }
    debris.open_series(req.resume ? std::optional<std::uint64_t>(series_rows) : std::nullopt);
    Schedule at = make_schedule(u.dt(), s.end_time, out.series_interval, out.frame_interval);
    at.start_outputs = !req.resume;
    at.progress_every = 16;
    at.checkpoint_wall_s = pc.checkpoint_interval;
    at.checkpoint = [&](double updates) {
        io::CheckpointOut cp(checkpoint_file);
        std::string identity = pc.identity;
        double wall = wall_before + control.elapsed_s(), all_updates = updates_before + updates;
        series_rows = debris.series_rows();
        cp(identity);
        transfer(cp, wall, all_updates);
        cp.commit();
        spdlog::debug("checkpoint at t = {:.4f} s", sim.time());
    };
    const RunEnd end = run(sim, at, {&debris, &frames}, control);
    const int exit_code = end.exit_code;
    const double t_end = end.time;
    auto& forces = debris.forces();
    forces.finish(t_end);
    io::write_force_maps(out.out_dir, s.barrier, forces);
    const double peak_normal = forces.max_fluid_normal();
    // per element: where it is and the largest fluid force it received
    std::string csv = "element,pile,x_m,y_m,z_m,height_m,lattice_cells,max_fluid_force_N\n";
    for (std::size_t e = 0; e < ne; ++e) {
        const auto& el = s.barrier.elements[e];
        csv += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.6g}\n", e, el.pile, el.centre.x,
                           el.centre.y, el.centre.z, el.height, barrier_cells[e], forces.fluid_envelope()[e]);
    }
    io::write_text_atomically(out.out_dir / "barrier_fluid_elements.csv", csv);
    const double wall = wall_before + control.elapsed_s();
    io::JsonObject js = summary_header(s.name, "debris", end, sim, "lattice_cells", pc.shape.cells());
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
        .number("fluid_non_retained_fraction", debris.state().non_retained);
    add_lattice_summary(js, fs, debris.state().worst_drift, wall, updates_before + end.work);
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    spdlog::info(
        "{}: t = {:.4f} s, {} steps in {}; fluid force on the barrier: peak normal {:.4g} N = {:.3f} "
        "W sin(theta) at t = {:.3f} s; fluid non-retained {:.3f}; max relative mass drift {:.2e}",
        run_status(exit_code), t_end, sim.steps(), format_duration(wall), peak_normal,
        peak_normal / weight_along, forces.time_of_max_fluid_normal(), debris.state().non_retained,
        debris.state().worst_drift);
    if (out.report) io::run_report_script(out.out_dir, "debris_report.py");
    return exit_code;
}

}  // namespace sabo::sim
