// SPDX-License-Identifier: MIT
#include "sim/sandpile_run.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "analysis/stop_detector.h"
#include "core/error.h"
#include "dem/grain_budget.h"
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

using io::not_a_number;

PreparedSandpile prepare_sandpile(const RunRequest& req, const Config& cfg) {
    PreparedSandpile pc;
    pc.scene = scenario::build_sandpile_case(cfg, req.place_grains);
    const auto& s = pc.scene;
    const double r = 0.5 * s.diameter;
    pc.dem = dem::read_dem_settings(cfg, {r, r, s.density, s.velocity_scale});
    const double end = s.end_time;
    pc.output = read_output_settings(cfg, req, s.name, end / 50.0, end / 1000.0);
    if (pc.output.series_interval < pc.dem.dt)
        cfg.fail("output.series_interval_s",
                 fmt::format("must be at least the time step {:.4g} s", pc.dem.dt));
    pc.remove_drained = cfg.boolean_or("sandpile.remove_drained", true);
    // Complete stop: mean grain speed below ε sqrt(g d) (as kinetic energy) for a hold of h sqrt(d/g);
    // both scale with the grain size, so one setting serves d = 2 mm and d = 10 cm.
    const double g = std::abs(s.gravity.z);
    const double eps = cfg.real_or("stop.speed_over_sqrt_gd", 0.01, Range::positive());
    const double grain_mass = s.density * dem::sphere_volume(r);
    pc.stop_energy_per_grain = 0.5 * grain_mass * eps * eps * g * s.diameter;
    pc.stop_hold =
        cfg.real_or("stop.hold_over_sqrt_d_g", 20.0, Range::positive()) * std::sqrt(s.diameter / g);
    cfg.record("derived.particles", static_cast<std::int64_t>(s.count));
    cfg.record("derived.fill_height_over_d", s.fill_height / s.diameter);
    cfg.record("derived.fill_solid_fraction", s.fill_fraction);
    cfg.record("derived.stop_kinetic_energy_per_grain_J", pc.stop_energy_per_grain);
    cfg.record("derived.stop_hold_s", pc.stop_hold);
    cfg.finish();
    check_memory(cfg, s.count);
    return pc;
}

void print_derived(const PreparedSandpile& pc) {
    const auto& s = pc.scene;
    const auto& d = pc.dem;
    spdlog::info(
        "case '{}': sandpile box {:.4f} x {:.4f} x {:.4f} m, plate X [{:.4f}, {:.4f}] m at Z = {:.4f} m, "
        "outlets {:.4f} m",
        s.name, s.length, s.width, s.height, s.plate_x_lo, s.plate_x_hi, s.plate_z, s.plate_x_lo);
    spdlog::info(
        "grains: {} spheres, d = {} m, rho = {} kg/m3, generated at random in {:.1f} d above the plate "
        "(solid fraction {:.3f})",
        s.count, s.diameter, s.density, s.fill_height / s.diameter, s.fill_fraction);
    spdlog::info("{}", dem::describe_contact(d));
    spdlog::info(
        "time step: t_c = {:.4e} s, dt = {:.4e} s, dt/t_c = 1/{:.1f}; at most {:.0f} steps to t = {:.3g} s",
        d.contact_time, d.dt, d.steps_per_contact, std::ceil(s.end_time / d.dt), s.end_time);
    spdlog::info("expected max overlap (grain at {:.2f} m/s on a fixed one): {:.2f} % of d (aim < 2 %)",
                 s.velocity_scale, 100.0 * d.expected_max_overlap_ratio);
    spdlog::info("memory estimate: {:.1f} MiB; neighbour skin {:.4g} m",
                 dem::memory_estimate_bytes(static_cast<double>(s.count)) / 1048576.0, d.skin);
    spdlog::info(
        "settling at most {:.3g} s, then the outlets open; complete stop: mean kinetic energy of the "
        "grains above the plate below {:.3g} J for {:.3g} s",
        s.settle_max_time, pc.stop_energy_per_grain, pc.stop_hold);
}

namespace {

struct HeapState {
    std::size_t on_plate = 0;   // PlateGeometry::holds
    std::size_t above = 0;      // PlateGeometry::above
    double above_energy = 0.0;  // J, kinetic energy of those
};

HeapState heap_state(const dem::Particles& p, const analysis::PlateGeometry& plate) {
    HeapState h;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        if (!plate.above(p.x[i])) continue;
        ++h.above;
        h.above_energy += p.kinetic_energy(i);
        h.on_plate += plate.holds(p.x[i]) ? 1 : 0;
    }
    return h;
}

io::JsonObject side_json(const analysis::HeapSide& side) {
    io::JsonObject o;
    o.number("angle_deg", side.angle_deg)
        .number("slope", side.slope)
        .number("intercept_m", side.intercept)
        .number("r2", side.r2)
        .number("rms_m", side.rms)
        .integer("points", static_cast<std::int64_t>(side.points.size()))
        .number("x_from_m", side.x_from)
        .number("x_to_m", side.x_to);
    return o;
}

void write_heap_csv(const std::filesystem::path& dir, const analysis::HeapAngle& h) {
    std::string csv = "side,x_m,top_z_m,fit_z_m\n";
    for (const auto* side : {&h.left, &h.right}) {
        for (const auto& p : side->points) {
            csv += fmt::format("{},{:.9g},{:.9g},{:.9g}\n", side == &h.left ? "left" : "right", p.x, p.z,
                               side->intercept + side->slope * p.x);
        }
    }
    io::write_text_atomically(dir / "heap.csv", csv);
}

// Final grain positions for the heap picture of the report.
void write_grains_csv(const std::filesystem::path& dir, const dem::Particles& p) {
    std::string csv = "x_m,y_m,z_m,r_m\n";
    for (std::size_t i = 0; i < p.n_mobile; ++i)
        csv += fmt::format("{:.7g},{:.7g},{:.7g},{:.7g}\n", p.x[i].x, p.x[i].y, p.x[i].z, p.r[i]);
    io::write_text_atomically(dir / "final_grains.csv", csv);
}

// The sandpile's phases as an observer of the run: settling with the outlets closed until the mass is at
// rest (or sandpile.settle_max_time_s), then draining to the complete stop of the heap; grains that fell
// below the plate leave the run (sandpile.remove_drained).
class SandpileObserver final : public Checkpointed<SandpileObserver> {
  public:
    // `domain`: a run divided among ranks (every rank analyses every grain; the first writes series.csv).
    SandpileObserver(const PreparedSandpile& pc, const analysis::PlateGeometry& plate, const Domain& domain)
        : pc_(pc),
          plate_(plate),
          settle_steps_(static_cast<std::uint64_t>(std::ceil(pc.scene.settle_max_time / pc.dem.dt - 1e-9))),
          // Grains that fell through an outlet to 2 d below the plate's underside can no longer touch the
          // heap: with remove_drained they leave the run there instead of piling up on the floor, where
          // they cost as much as the heap itself and change nothing that is measured.
          drained_z_(pc.scene.plate_z - pc.scene.plate_thickness - 2.0 * pc.scene.diameter),
          // the stop is judged on the grains above the plate (grains that drained to the floor do not
          // change the heap; frictionless ones would roll there for ever), as mean energy per grain
          quiet_(pc.stop_energy_per_grain, pc.stop_hold),
          series_(domain.writes_outputs() ? pc.output.out_dir / "series.csv" : std::filesystem::path(),
                  {"time_s", "phase", "kinetic_energy_J", "above_plate_kinetic_energy_J", "contacts",
                   "sliding_fraction", "grains_on_plate", "max_overlap_over_d"}) {}

    void before_step(Simulation& sim) override {
        if (phase_ == 0 && sim.steps() >= settle_steps_) open_outlets(sim, "settle_max_time_s reached");
    }

    bool sample(Simulation& sim) override {
        const GrainView grains = sim.grain_view();  // every rank: a collective call when divided
        const auto ke = grains.kinetic_energy();
        const HeapState h = heap_state(grains.particles, plate_);
        const auto& st = grains.stats;
        series_.row(
            {grains.time, static_cast<double>(phase_), ke.translational + ke.rotational, h.above_energy,
             static_cast<double>(st.contacts),
             st.contacts > 0 ? static_cast<double>(st.sliding) / static_cast<double>(st.contacts) : 0.0,
             static_cast<double>(h.on_plate), st.max_overlap_ratio});
        const bool quiet =
            quiet_.sample(grains.time, h.above > 0 ? h.above_energy / static_cast<double>(h.above) : 0.0);
        if (sim.steps() == 0) return false;  // the first row, before any step
        if (quiet && phase_ == 1) {
            stopped_at_ = grains.time;
            spdlog::info("complete stop at t = {:.4f} s", stopped_at_);
            return true;
        }
        if (quiet) open_outlets(sim, "the settling mass came to rest");
        if (phase_ == 1 && pc_.remove_drained)
            sim.remove_grains([&](const Vec3& x) { return x.z < drained_z_; });
        return false;
    }

    [[nodiscard]] std::string phase() const override { return phase_ == 0 ? "settling" : "draining"; }
    [[nodiscard]] bool draining() const { return phase_ == 1; }
    [[nodiscard]] double opened_at() const { return opened_at_; }
    [[nodiscard]] double stopped_at() const { return stopped_at_; }
    // The phase and what was measured so far (io/checkpoint.h); the gates' state is the solver's.
    template <class Archive>
    void transfer(Archive& a) {
        a(quiet_, series_, phase_, opened_at_, stopped_at_);
    }

  private:
    void open_outlets(Simulation& sim, const char* why) {
        for (const std::size_t gate : pc_.scene.gates) sim.grains().set_wall_active(gate, false);
        phase_ = 1;
        opened_at_ = sim.time();
        quiet_ = analysis::StopDetector(pc_.stop_energy_per_grain, pc_.stop_hold);
        spdlog::info("outlets opened at t = {:.4f} s ({})", opened_at_, why);
    }

    const PreparedSandpile& pc_;
    analysis::PlateGeometry plate_;
    std::uint64_t settle_steps_;
    double drained_z_;
    analysis::StopDetector quiet_;
    io::CsvSeries series_;
    int phase_ = 0;  // 0 settling (outlets closed), 1 draining
    double opened_at_ = -1.0, stopped_at_ = -1.0;
};

}  // namespace

int run_sandpile(const RunRequest& req, const Config& cfg) {
    PreparedSandpile pc = prepare_sandpile(req, cfg);
    const auto& out = pc.output;
    const auto& s = pc.scene;
    Domain grains_domain{.origin = {}, .dx = 0.0, .box = {s.length, s.width, s.height}};
    if (req.world != nullptr) grains_domain.divide_grains(*req.world);
    open_run_folder(out.out_dir, req.case_file, cfg, req.resume, grains_domain);
    print_derived(pc);

    const analysis::PlateGeometry plate{s.plate_x_lo, s.plate_x_hi, s.plate_z, s.diameter, s.parts_per_side};
    // divided among ranks, each takes its slab of grains (every rank built the same whole set)
    Simulation sim(dem::make_solver(s.particles, s.walls, s.gravity, pc.dem), grains_domain);
    const Domain& domain = sim.domain();
    ParticleFrames frames(out.out_dir);
    SandpileObserver sandpile(pc, plate, domain);
    const std::vector<Observer*> observers{&frames, &sandpile};
    RunControl control(out.progress_interval, s.count);
    RunCheckpoint checkpoint(out.out_dir, cfg, domain);
    if (req.resume) checkpoint.load(sim, observers);
    Schedule at = make_schedule(pc.dem.dt, s.end_time, out.series_interval, out.frame_interval);
    checkpoint.schedule(at, out, sim, observers, control, req.resume);
    const RunEnd end = run(sim, at, observers, control);
    int exit_code = end.exit_code;
    const GrainView grains = sim.grain_view();  // every grain (divided: collective, as the sums below)
    const double own_work = checkpoint.work_before() + end.work;
    const double work = domain.sum(own_work);
    const DivisionSummary division = summarise_division(sim, own_work, control.elapsed_s());
    const std::size_t removed = sim.removed_grains();
    if (!domain.writes_outputs()) return exit_code;  // the first rank writes the run's files
    write_grains_csv(out.out_dir, grains.particles);
    if (exit_code == 0 && end.ending != "complete stop")
        spdlog::warn(
            "the heap did not come to a complete stop by t = {:.3g} s (case.end_time_s): the angle is "
            "measured on a moving heap",
            s.end_time);

    const double wall = checkpoint.wall_before() + control.elapsed_s();
    const auto ke = grains.kinetic_energy();
    const std::string status = run_status(exit_code);
    io::JsonObject js = summary_header(s.name, "sandpile", end, sim, "particles", s.count);
    js.number("diameter_m", s.diameter)
        .number("plate_length_m", s.plate_x_hi - s.plate_x_lo)
        .number("outlets_opened_at_s", sandpile.opened_at() >= 0.0 ? sandpile.opened_at() : not_a_number)
        .number("stopped_at_s", sandpile.stopped_at() >= 0.0 ? sandpile.stopped_at() : not_a_number)
        .number("final_kinetic_energy_J", ke.translational + ke.rotational)
        .integer("grains_removed_below_plate", static_cast<std::int64_t>(removed))
        .number("max_overlap_over_d", grains.max_overlap_seen);
    const auto& laws = pc.dem.laws;
    std::visit(
        [&](const auto& l) {
            js.number("mu_s_pp", l.particle_particle.tangential.mu_s)
                .number("mu_r_pp", l.particle_particle.rolling.mu_r)
                .number("mu_s_pw", l.particle_wall.tangential.mu_s)
                .number("mu_r_pw", l.particle_wall.rolling.mu_r);
        },
        laws);
    if (sandpile.draining()) {
        try {
            const auto& p = grains.particles;
            const auto heap = analysis::measure_heap(p.x, p.r, p.n_mobile, plate);
            js.number("angle_of_repose_deg", heap.angle_deg)
                .object("left", side_json(heap.left))
                .object("right", side_json(heap.right))
                .number("heap_height_m", heap.height)
                .boolean("flat_top", heap.flat_top)
                .integer("grains_on_plate", static_cast<std::int64_t>(heap.on_plate));
            write_heap_csv(out.out_dir, heap);
            spdlog::info(
                "angle of repose {:.2f} deg (left {:.2f}, R2 {:.3f}; right {:.2f}, R2 {:.3f}); heap {:.4f} m "
                "high, {} grains on the plate{}",
                heap.angle_deg, heap.left.angle_deg, heap.left.r2, heap.right.angle_deg, heap.right.r2,
                heap.height, heap.on_plate, heap.flat_top ? "; flat top (sides end at the plateau)" : "");
            if (std::min(heap.left.r2, heap.right.r2) < 0.8)
                spdlog::warn("a side's fit is poor (R2 < 0.8): the heap is irregular; look at heap.png");
        } catch (const RunError& e) {
            spdlog::error("{}", e.what());
            js.text("heap_error", e.what());
            if (exit_code == 0) exit_code = 3;
        }
    }
    add_division_summary(js, division);
    js.integer("neighbor_list_builds", static_cast<std::int64_t>(grains.list_builds))
        .number("wall_time_s", wall)
        .number("particle_steps_per_s", work / wall);
    io::write_text_atomically(out.out_dir / "summary.json", js.dump());
    spdlog::info("{} ({}): t = {:.4f} s, {} steps in {}; max overlap {:.2f} % of d", status,
                 exit_code == 0 ? end.ending : status, grains.time, sim.steps(), format_duration(wall),
                 100.0 * grains.max_overlap_seen);
    if (grains.max_overlap_seen > 0.02) {
        spdlog::warn("max overlap {:.2f} % of a diameter exceeded the recommended 2 % (stiffer contacts)",
                     100.0 * grains.max_overlap_seen);
    }
    if (out.report) io::run_report_script(out.out_dir, "sandpile_report.py");
    checkpoint.tell_how_to_resume(exit_code);
    return exit_code;
}

}  // namespace sabo::sim
