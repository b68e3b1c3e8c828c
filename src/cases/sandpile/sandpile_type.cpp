// SPDX-License-Identifier: MIT
#include "cases/sandpile/sandpile_type.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/geometry_output.h"
#include "io/json_writer.h"
#include "sim/run_control.h"
#include "sim/run_summary.h"

namespace sabo::cases {

using io::not_a_number;

namespace {

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

}  // namespace

parallel::Domain SandpileType::domain(const MpiWorld* world) const {
    const auto& s = pc_.scene;
    parallel::Domain grains{.origin = {}, .dx = 0.0, .box = {s.length, s.width, s.height}};
    if (world != nullptr) grains.divide_grains(*world);
    return grains;
}

std::optional<sim::Simulation> SandpileType::build(const parallel::Domain& domain, sim::RunControl&, bool) {
    const auto& s = pc_.scene;
    // divided among ranks, each takes its slab of grains (every rank built the same whole set)
    return sim::Simulation(dem::make_solver(s.particles, s.walls, s.gravity, pc_.dem), domain);
}

std::vector<sim::Observer*> SandpileType::observers(const sim::Simulation& sim) {
    const auto& s = pc_.scene;
    plate_.emplace(
        analysis::PlateGeometry{s.plate_x_lo, s.plate_x_hi, s.plate_z, s.diameter, s.parts_per_side});
    frames_.emplace(pc_.output.out_dir);
    // the box, the plate and the gates around every view (once, when the run starts)
    if (sim.domain().writes_outputs())
        io::write_geometry(pc_.output.out_dir / "geometry.vtp", s.walls, s.particles, sim.domain().box);
    sandpile_.emplace(pc_, *plate_, sim.domain());
    return {&*frames_, &*sandpile_};
}

void SandpileType::finish(sim::Simulation& sim, const sim::RunEnd&) {
    grains_.emplace(sim.grain_view());  // every grain (divided: collective, as the sums)
    removed_ = sim.removed_grains();
}

void SandpileType::write_end_files(const sim::Simulation&, const sim::RunEnd& end) {
    write_grains_csv(pc_.output.out_dir, grains_->particles);
    if (end.exit_code == 0 && end.ending != sim::RunEnding::complete_stop)
        spdlog::warn(
            "the heap did not come to a complete stop by t = {:.3g} s (case.end_time_s): the angle is "
            "measured on a moving heap",
            pc_.scene.end_time);
}

sim::SummaryHead SandpileType::summary_head(const sim::Simulation&) const {
    return {pc_.scene.name, "sandpile", "particles", pc_.scene.count};
}

int SandpileType::summarise(io::JsonObject& js, const sim::Simulation&, const sim::RunEnd& end) {
    const auto& s = pc_.scene;
    const auto& grains = *grains_;
    const auto ke = grains.kinetic_energy();
    js.number("diameter_m", s.diameter)
        .number("plate_length_m", s.plate_x_hi - s.plate_x_lo)
        .number("outlets_opened_at_s", sandpile_->opened_at() >= 0.0 ? sandpile_->opened_at() : not_a_number)
        .number("stopped_at_s", sandpile_->stopped_at() >= 0.0 ? sandpile_->stopped_at() : not_a_number)
        .number("final_kinetic_energy_J", ke.translational + ke.rotational)
        .integer("grains_removed_below_plate", static_cast<std::int64_t>(removed_))
        .number("max_overlap_over_d", grains.max_overlap_seen);
    std::visit(
        [&](const auto& l) {
            js.number("mu_s_pp", l.particle_particle.tangential.mu_s)
                .number("mu_r_pp", l.particle_particle.rolling.mu_r)
                .number("mu_s_pw", l.particle_wall.tangential.mu_s)
                .number("mu_r_pw", l.particle_wall.rolling.mu_r);
        },
        pc_.dem.laws);
    if (!sandpile_->draining()) return end.exit_code;
    try {
        const auto& p = grains.particles;
        const auto heap = analysis::measure_heap(p.x, p.r, p.n_mobile, *plate_);
        js.number("angle_of_repose_deg", heap.angle_deg)
            .object("left", side_json(heap.left))
            .object("right", side_json(heap.right))
            .number("heap_height_m", heap.height)
            .boolean("flat_top", heap.flat_top)
            .integer("grains_on_plate", static_cast<std::int64_t>(heap.on_plate));
        write_heap_csv(pc_.output.out_dir, heap);
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
        if (end.exit_code == 0) return 3;
    }
    return end.exit_code;
}

void SandpileType::summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const {
    sim::add_grain_rate(js, grains_->list_builds, totals.wall_s, totals.work);
}

void SandpileType::log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                           const sim::RunTotals& totals) const {
    const std::string status = sim::run_status(end.exit_code);
    const double overlap = grains_->max_overlap_seen;
    spdlog::info("{} ({}): t = {:.4f} s, {} steps in {}; max overlap {:.2f} % of d", status,
                 sim::ended_by(end), grains_->time, sim.steps(), sim::format_duration(totals.wall_s),
                 100.0 * overlap);
    sim::warn_large_overlap(overlap, "stiffer contacts");
}

}  // namespace sabo::cases
