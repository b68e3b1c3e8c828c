// SPDX-License-Identifier: MIT
// The gauge section upstream of the barrier as an observer of a channel or debris run (docs/design.md,
// "The approaching flow"): a reading of the grains and the fluid in the section at every series sample,
// written to gauge.csv and kept for the end, when the approaching flow is taken from the record.
#pragma once
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "analysis/barrier_forces.h"
#include "analysis/flow_gauge.h"
#include "cases/common/gauge_settings.h"
#include "io/json_writer.h"
#include "io/run_output.h"
#include "lbm/units.h"
#include "sim/observer.h"

namespace sabo::cases {

class GaugeObserver final : public sim::Checkpointed<GaugeObserver> {
  public:
    // `forces`: the barrier's (first impact, largest normal force); `fluid_units`: the lattice's, in a run
    // with fluid; `domain`: a run divided among ranks (each tallies its own planes; the first writes
    // gauge.csv).
    GaugeObserver(const GaugeSettings& gauge, const analysis::BarrierForceMonitor& forces,
                  const std::filesystem::path& out_dir, std::optional<lbm::UnitConverter> fluid_units = {},
                  const parallel::Domain& domain = {})
        : gauge_(gauge),
          forces_(forces),
          units_(fluid_units),
          series_(domain.writes_outputs() ? out_dir / "gauge.csv" : std::filesystem::path(),
                  {"time_s", "depth_m", "velocity_m_s", "discharge_m3_s", "solid_fraction",
                   "bulk_density_kg_m3", "solid_discharge_m3_s"}) {}

    bool sample(sim::Simulation& sim) override {
        analysis::GaugeTally tally(gauge_.section);
        if (sim.has_grains()) {  // every grain of the run, counted once: by the first rank when divided
            const dem::GrainView grains = sim.grain_view();
            if (sim.domain().writes_outputs()) tally.add_grains(grains.particles);
        }
        if (sim.has_fluid()) add_fluid(sim, tally);
        if (const parallel::Domain& d = sim.domain(); d.divided())
            tally.combine([&](std::span<double> maxima, std::span<double> sums) {
                d.world->max_reals(maxima);
                d.world->sum_reals(sums);
            });
        const analysis::GaugeReading g = tally.reading(sim.time());
        record_.push_back(g);
        series_.row(
            {g.time, g.depth, g.velocity, g.discharge, g.solid_fraction, g.bulk_density, g.solid_discharge});
        return false;
    }

    // The approaching flow from the record so far.
    [[nodiscard]] analysis::ApproachFlow approach() const {
        return analysis::approach_flow(record_, gauge_.arrival_depth, gauge_.distance,
                                       forces_.first_impact_time(), forces_.time_of_max_normal());
    }

    // Its keys of summary.json (docs/outputs.md).
    void summarise(io::JsonObject& js) const {
        const analysis::ApproachFlow a = approach();
        if (!record_.empty() && record_.front().depth >= gauge_.arrival_depth)
            spdlog::warn(
                "the gauge section (X = {:.2f} m) lies in the released mass at the start: no front arrival "
                "or "
                "front velocity is measured; move it down-slope (analysis.gauge_distance_m)",
                gauge_.section.centre_x);
        else if (std::isfinite(a.front_velocity) && a.at_source.velocity < 0.25 * a.front_velocity)
            spdlog::warn(
                "at the gauge (X = {:.2f} m) the flow that reached the barrier at its largest force moved at "
                "{:.2f} m/s, a quarter of the front's {:.2f} m/s or less: the deposit had probably reached "
                "the gauge; move it up-slope (analysis.gauge_distance_m)",
                gauge_.section.centre_x, a.at_source.velocity, a.front_velocity);
        js.number("gauge_distance_m", gauge_.distance)
            .number("gauge_x_m", gauge_.section.centre_x)
            .number("gauge_length_m", gauge_.section.length)
            .number("gauge_arrival_depth_m", gauge_.arrival_depth)
            .number("front_arrival_at_gauge_s", a.arrival_time)
            .number("approach_impact_time_s", forces_.first_impact_time())
            .number("approach_peak_time_s", forces_.time_of_max_normal())
            .number("approach_front_velocity_m_s", a.front_velocity)
            .number("approach_time_at_gauge_s", a.source_time)
            .number("approach_flow_depth_m", a.at_source.depth)
            .number("approach_velocity_m_s", a.at_source.velocity)
            .number("approach_discharge_m3_s", a.at_source.discharge)
            .number("approach_solid_fraction", a.at_source.solid_fraction)
            .number("approach_bulk_density_kg_m3", a.at_source.bulk_density)
            .number("approach_solid_discharge_m3_s", a.at_source.solid_discharge)
            .number("approach_max_flow_depth_m", a.max_depth)
            .number("approach_max_velocity_m_s", a.max_velocity)
            .number("approach_peak_discharge_m3_s", a.max_discharge);
    }

    template <class Archive>
    void transfer(Archive& a) {
        a(record_, series_);
    }

  private:
    // The fluid cells of the section: their fluid's height, volume, mass and momentum (cells a grain covers
    // hold fluid moving with the grain, counted with the grain).
    void add_fluid(sim::Simulation& sim, analysis::GaugeTally& tally) const {
        const parallel::Domain& d = sim.domain();
        const lbm::UnitConverter& units = *units_;
        const double cell = d.dx * d.dx * d.dx;
        const auto& s = gauge_.section;
        // the section's planes (global x), then those among the fields' (x from their first plane)
        const int first = static_cast<int>(std::floor((s.centre_x - 0.5 * s.length - d.origin.x) / d.dx));
        const int last = static_cast<int>(std::ceil((s.centre_x + 0.5 * s.length - d.origin.x) / d.dx));
        const lbm::FluidFields& l = sim.fluid_fields(first, last);
        const int shift = d.global_x(l.first_x);
        const int x0 = std::max(0, first - shift);
        const int x1 = std::min(l.nx, last - shift);
        for (int z = 0; z < l.nz; ++z)
            for (int y = 0; y < l.ny; ++y)
                for (int x = x0; x < x1; ++x) {
                    const std::size_t k = l.cell(x, y, z);
                    if (!l.wet(k)) continue;
                    const Vec3 c = d.cell_centre(l.first_x + x, y, z);
                    if (!s.contains(c.x) || l.covered[k] != 0) continue;
                    const double rho = l.density[k];
                    const double fill = std::clamp(l.fill[k], 0.0, 1.0);
                    const double mass = units.mass_si(fill * rho);
                    tally.add(c.x, c.y, c.z + (fill - 0.5) * d.dx, fill * cell, mass,
                              mass * units.velocity_si(l.velocity[k].x), false);
                }
    }

    GaugeSettings gauge_;
    const analysis::BarrierForceMonitor& forces_;
    std::optional<lbm::UnitConverter> units_;
    io::CsvSeries series_;
    std::vector<analysis::GaugeReading> record_;
};

}  // namespace sabo::cases
