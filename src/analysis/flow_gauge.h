// SPDX-License-Identifier: MIT
// The incoming flow as the design formulas need it (docs/design.md, "The approaching flow"): a gauge
// section a stated distance upstream of the barrier reads the flow depth, the depth-averaged velocity and
// the discharge at every series sample, as a flume's depth sensor and velocity gauge would; from its
// record, the front velocity (gauge-to-barrier travel time of the front) and the state of the flow that
// reaches the barrier at the time of the largest force, measured before the barrier could affect it.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "dem/particles.h"

namespace sabo::analysis {

// A slab across the channel, [centre − length/2, centre + length/2) in X (down-slope), the full width.
struct GaugeSection {
    double centre_x = 0.0;  // m
    double length = 0.5;    // m, along X
    double width = 0.0;     // m, the channel's
    double strip = 0.1;     // m, across-channel strips the depth is averaged over
    // the bed's level under each cell of the depth map (bin b along X, strip s across: [b · strips() + s]),
    // m above the bed plane, from which the depth is measured (empty: the plane, z = 0)
    std::vector<double> bed;
    [[nodiscard]] bool contains(double x) const {
        return x >= centre_x - 0.5 * length && x < centre_x + 0.5 * length;
    }
    // The depth map: cells about `strip` on a side, strips() across and bins() along X.
    [[nodiscard]] std::size_t strips() const { return cells(width); }
    [[nodiscard]] std::size_t bins() const { return cells(length); }
    // the X and Y of cell (b, s)'s centre, m
    [[nodiscard]] double cell_x(std::size_t b) const {
        return centre_x - 0.5 * length +
               (static_cast<double>(b) + 0.5) * length / static_cast<double>(bins());
    }
    [[nodiscard]] double cell_y(std::size_t s) const {
        return (static_cast<double>(s) + 0.5) * width / static_cast<double>(strips());
    }

  private:
    [[nodiscard]] std::size_t cells(double extent) const {
        return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(extent / strip)));
    }
};

// One reading of the gauge.
struct GaugeReading {
    double time = 0.0;   // s
    double depth = 0.0;  // m: mean over the strips of the highest surface above the bed (0 in an empty strip)
    double velocity = 0.0;   // m/s: mass-weighted mean down-slope velocity (depth-averaged), grains and fluid
    double discharge = 0.0;  // m³/s of the mixture: depth × velocity × width
    double solid_fraction = 0.0;  // grain volume / occupied bulk volume
    double bulk_density = 0.0;    // kg/m³: (grain + fluid mass) / occupied bulk volume
    // m³/s of grains: Σ V_i v_x,i over the grains in the section / its length — their flux through it, which
    // in a steady flow is the grains' discharge whatever their arrangement (depth and solid fraction above
    // describe a dense surge; a sparse or pulsing flow's top is not its bulk)
    double solid_discharge = 0.0;
};

// Sums one reading from the grains and fluid cells inside the section.
class GaugeTally {
  public:
    explicit GaugeTally(const GaugeSection& section);
    // Matter inside the section: its X and Y, the top of its surface (grain: z + r; fluid cell: its fluid's
    // height), its volume, mass and down-slope momentum. Grains count in the solid fraction.
    void add(double x, double y, double top, double volume, double mass, double momentum_x, bool grain);
    // The mobile grains of `p` whose centre lies inside the section.
    void add_grains(const dem::Particles& p);
    [[nodiscard]] GaugeReading reading(double time) const;
    // Joins the tallies of the other parts of the section (a run divided among ranks): `reduce(maxima,
    // sums)` must replace each value by its largest / its sum over the parts.
    template <class Reduce>
    void combine(Reduce&& reduce) {
        double sums[4] = {grain_volume_, mass_, momentum_, grain_flux_};
        reduce(std::span<double>(top_), std::span<double>(sums));
        grain_volume_ = sums[0];
        mass_ = sums[1];
        momentum_ = sums[2];
        grain_flux_ = sums[3];
    }

  private:
    GaugeSection section_;
    double dx_ = 0.0, dy_ = 0.0;
    std::size_t strips_ = 1, bins_ = 1;
    std::vector<double> top_;  // [bin × strips_ + strip]: the surface over a cell of the map
    double grain_volume_ = 0.0, mass_ = 0.0, momentum_ = 0.0;
    double grain_flux_ = 0.0;  // Σ V_i v_x,i of the grains, m⁴/s
};

// The flow that approaches the barrier, from a gauge's record (readings in time order).
// NaN where a value does not exist.
struct ApproachFlow {
    static constexpr double none = std::numeric_limits<double>::quiet_NaN();
    double arrival_time =
        none;  // s: the front reaches the gauge (depth first at the arrival depth, interpolated)
    double front_velocity = none;  // m/s: distance / (first impact − arrival)
    double source_time = none;     // s: when the flow reaching the barrier at the peak passed the gauge,
                                   // t_peak − distance / front velocity
    GaugeReading at_source{none, none, none, none, none, none};  // the reading then (interpolated)
    double max_depth = none;      // m, over [arrival, source time]: the approaching flow only
    double max_discharge = none;  // m³/s, the same window (the peak discharge Q_peak)
    double max_velocity = none;   // m/s, the same window
};
// `distance`: from the gauge's centre to the barrier's upstream face, m. `t_impact`, `t_peak`: the first
// impact and the time of the largest normal force (NaN: no impact; then only the arrival and the maxima
// over the whole record are given). NaN where a value does not exist (the front never reached the gauge,
// or reached the barrier first).
[[nodiscard]] ApproachFlow approach_flow(std::span<const GaugeReading> record, double arrival_depth,
                                         double distance, double t_impact, double t_peak);

}  // namespace sabo::analysis
