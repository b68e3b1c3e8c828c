// SPDX-License-Identifier: MIT
#include "cases/channel/channel_type.h"

#include <spdlog/spdlog.h>

#include "cases/channel/presettle.h"
#include "cases/common/design_comparison.h"
#include "core/error.h"
#include "io/barrier_output.h"
#include "io/geometry_output.h"
#include "sim/run_control.h"
#include "sim/run_summary.h"

namespace sabo::cases {

parallel::Domain ChannelType::domain(const MpiWorld* world) const {
    const auto& scene = pc_.scene;
    parallel::Domain grains{
        .origin = {}, .dx = 0.0, .box = {scene.length, scene.width, scene.bounds.domain_height}};
    if (scene.inflow) grains.fed_radius_max = scene.inflow->r_max();
    if (world != nullptr) grains.divide_grains(*world);
    return grains;
}

std::optional<sim::Simulation> ChannelType::build(const parallel::Domain& domain, sim::RunControl& control,
                                                  bool resume) {
    const auto& scene = pc_.scene;
    // a resumed run's grains come from its checkpoint (settled before it was written)
    const bool settle = scene.release.compaction == scenario::Compaction::high && !resume;
    const dem::Particles start = settle ? presettle(pc_, control) : scene.particles;
    if (control.stop_requested()) {
        spdlog::warn(
            "interrupted while the block settled (release.compaction = \"high\"): no checkpoint is written "
            "before the release; run the case again");
        return std::nullopt;
    }
    // divided among ranks, each takes its slab of grains (every rank built the same whole set)
    return sim::Simulation(dem::make_solver(start, scene.walls, scene.gravity, pc_.dem), domain);
}

std::vector<sim::Observer*> ChannelType::observers(const sim::Simulation& sim) {
    const parallel::Domain& domain = sim.domain();
    analysis_.emplace(pc_, domain);
    gauge_.emplace(pc_.analysis.gauge, analysis_->forces(), pc_.output.out_dir,
                   std::optional<lbm::UnitConverter>{}, domain);
    frames_.emplace(pc_.output.out_dir);
    // the channel and the barrier around every view (once, when the run starts)
    if (domain.writes_outputs())
        io::write_geometry(pc_.output.out_dir / "geometry.vtp", pc_.scene.walls, pc_.scene.particles,
                           domain.box, pc_.scene.barrier.mesh.get());
    if (!pc_.scene.inflow) return {&*analysis_, &*gauge_, &*frames_};
    // (after the analysis: the grains that left are out before the new ones come in)
    inflow_.emplace(*pc_.scene.inflow, pc_.dem.dt, pc_.output.out_dir, domain.writes_outputs());
    return {&*analysis_, &*gauge_, &*frames_, &*inflow_};
}

void ChannelType::finish(sim::Simulation& sim, const sim::RunEnd&) {
    grains_.emplace(sim.grain_view());  // every grain (divided: collective, as finish and the sums)
    analysis_->finish(sim);
}

void ChannelType::write_end_files(const sim::Simulation&, const sim::RunEnd&) {
    const auto& scene = pc_.scene;
    if (scene.release.mixture == scenario::Mixture::bidisperse && scene.barrier.present())
        io::write_deposit_composition(pc_.output.out_dir, scene, grains_->particles);
}

sim::SummaryHead ChannelType::summary_head(const sim::Simulation&) const {
    return {pc_.scene.name, "channel", "particles", pc_.scene.release.count};
}

int ChannelType::summarise(io::JsonObject& js, const sim::Simulation&, const sim::RunEnd& end) {
    const auto& scene = pc_.scene;
    const auto& release = scene.release;
    const bool bidisperse = release.mixture == scenario::Mixture::bidisperse;
    const auto ke = grains_->kinetic_energy();
    js.number("solid_volume_m3", release.solid_volume)
        .text("mixture", scenario::name(release.mixture))
        .text("compaction", scenario::name(release.compaction))
        .number("phi_small", bidisperse ? release.phi_small : io::not_a_number)
        .number("radius_large_m", bidisperse ? release.r_large : io::not_a_number)
        .number("radius_small_m", bidisperse ? release.r_small : io::not_a_number)
        .number("equivalent_radius_m", release.equivalent_radius)
        .number("outlet_width_over_r_star", scene.barrier.outlet_width / release.equivalent_radius)
        .number("slope_deg", scene.slope_deg)
        .text("barrier_type", scenario::name(scene.barrier.type))
        .text("barrier_orientation", scenario::name(scene.barrier.orientation))
        .text("barrier_model", scenario::name(scene.barrier.model))
        .text("barrier_configuration", scene.barrier.configuration)
        .number("outlet_width_m", scene.barrier.outlet_width)
        .number("outlet_width_over_r", scene.barrier.outlet_width / release.r_mean)
        .number("pile_width_m", scene.barrier.pile_width)
        .integer("pile_count", static_cast<std::int64_t>(scene.barrier.piles.size()))
        .number("barrier_height_m", scene.barrier.height)
        .number("final_kinetic_energy_J", ke.translational + ke.rotational)
        .number("max_overlap_over_d", grains_->max_overlap_seen);
    io::add_barrier_face(js, scene.barrier);
    analysis_->summarise(js);
    if (inflow_) inflow_->summarise(js);
    gauge_->summarise(js);
    if (scene.barrier.present()) {
        const auto& f = analysis_->forces();
        add_design_comparison(
            js, pc_.output.out_dir,
            measured_run(gauge_->approach(),
                         {f.max_normal(), analysis_->deposit_at_rest() ? f.normal() : std::nan("")},
                         analysis_->deposit(), grains_->particles, release.density, 0.0, scene.barrier,
                         scene.width, scene.slope_deg, norm(scene.gravity), analysis_->retained()));
    }
    return end.exit_code;
}

void ChannelType::summarise_rate(io::JsonObject& js, const sim::RunTotals& totals) const {
    sim::add_grain_rate(js, grains_->list_builds, totals.wall_s, totals.work);
}

void ChannelType::log_end(const sim::Simulation& sim, const sim::RunEnd& end,
                          const sim::RunTotals& totals) const {
    const std::string status = sim::run_status(end.exit_code);
    const double overlap = grains_->max_overlap_seen;
    spdlog::info("{} ({}): t = {:.4f} s, {} steps in {} ({:.3g} particle-steps/s); max overlap {:.2f} % of d",
                 status, sim::ended_by(end), sim.time(), sim.steps(), sim::format_duration(totals.wall_s),
                 totals.work / totals.wall_s, 100.0 * overlap);
    sim::warn_large_overlap(overlap, "stiffer contacts or smaller impact speeds");
    const auto ke = grains_->kinetic_energy();
    const double energy = ke.translational + ke.rotational;
    if (end.exit_code == 0 && end.ending == sim::RunEnding::end_time && pc_.analysis.stop_enabled &&
        energy > pc_.analysis.stop_threshold) {
        spdlog::warn(
            "the grains had not stopped by the end time: kinetic energy {:.3g} J, above the complete-stop "
            "threshold {:.3g} J (stop.kinetic_energy_per_grain_J x grains); the barrier's force "
            "at the end is not yet its static load — raise case.end_time_s",
            energy, pc_.analysis.stop_threshold);
    }
}

}  // namespace sabo::cases
