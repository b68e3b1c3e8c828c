// SPDX-License-Identifier: MIT
#include "analysis/flow_gauge.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sabo::analysis {

namespace {

// The reading at time t, linear between the samples around it (the first or last outside the record).
GaugeReading interpolate(std::span<const GaugeReading> record, double t) {
    const auto later = std::lower_bound(record.begin(), record.end(), t,
                                        [](const GaugeReading& r, double time) { return r.time < time; });
    if (later == record.begin()) return record.front();
    if (later == record.end()) return record.back();
    const GaugeReading& a = *(later - 1);
    const GaugeReading& b = *later;
    const double s = (t - a.time) / (b.time - a.time);
    const auto mix = [s](double u, double v) { return u + s * (v - u); };
    return {t,
            mix(a.depth, b.depth),
            mix(a.velocity, b.velocity),
            mix(a.discharge, b.discharge),
            mix(a.solid_fraction, b.solid_fraction),
            mix(a.bulk_density, b.bulk_density),
            mix(a.solid_discharge, b.solid_discharge)};
}

}  // namespace

GaugeTally::GaugeTally(const GaugeSection& section) : section_(section) {
    strips_ = section.strips();
    bins_ = section.bins();
    if (!section.bed.empty() && section.bed.size() != strips_ * bins_)
        throw std::logic_error("GaugeTally: a bed level for another depth map");
    dy_ = section.width / static_cast<double>(strips_);
    dx_ = section.length / static_cast<double>(bins_);
    top_.assign(strips_ * bins_, 0.0);
}

void GaugeTally::add(double x, double y, double top, double volume, double mass, double momentum_x,
                     bool grain) {
    const auto s = std::min(strips_ - 1, static_cast<std::size_t>(std::max(0.0, y / dy_)));
    const double from_start = x - (section_.centre_x - 0.5 * section_.length);
    const auto b = std::min(bins_ - 1, static_cast<std::size_t>(std::max(0.0, from_start / dx_)));
    double& cell = top_[b * strips_ + s];
    cell = std::max(cell, top);
    if (grain) grain_volume_ += volume;
    mass_ += mass;
    momentum_ += momentum_x;
}

void GaugeTally::add_grains(const dem::Particles& p) {
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        if (!section_.contains(p.x[i].x)) continue;
        grain_flux_ += dem::sphere_volume(p.r[i]) * p.v[i].x;
        add(p.x[i].x, p.x[i].y, p.x[i].z + p.r[i], dem::sphere_volume(p.r[i]), p.m[i], p.m[i] * p.v[i].x,
            true);
    }
}

GaugeReading GaugeTally::reading(double time) const {
    GaugeReading g;
    g.time = time;
    double depths = 0.0, bulk = 0.0;
    for (std::size_t s = 0; s < strips_; ++s) {
        double highest = 0.0;
        for (std::size_t b = 0; b < bins_; ++b) {
            const std::size_t c = b * strips_ + s;
            // (an empty cell's top is 0: below a raised bed, no depth)
            const double above_bed = std::max(0.0, top_[c] - (section_.bed.empty() ? 0.0 : section_.bed[c]));
            highest = std::max(highest, above_bed);
            bulk += above_bed * dx_ * dy_;
        }
        depths += highest;
    }
    g.depth = depths / static_cast<double>(strips_);
    g.velocity = mass_ > 0.0 ? momentum_ / mass_ : 0.0;
    g.discharge = g.depth * g.velocity * section_.width;
    g.solid_fraction = bulk > 0.0 ? grain_volume_ / bulk : 0.0;
    g.bulk_density = bulk > 0.0 ? mass_ / bulk : 0.0;
    g.solid_discharge = grain_flux_ / section_.length;
    return g;
}

ApproachFlow approach_flow(std::span<const GaugeReading> record, double arrival_depth, double distance,
                           double t_impact, double t_peak) {
    ApproachFlow a;
    const auto first = std::find_if(record.begin(), record.end(),
                                    [&](const GaugeReading& r) { return r.depth >= arrival_depth; });
    if (first == record.end()) return a;
    a.arrival_time = first->time;
    if (first != record.begin()) {  // the crossing of the arrival depth between the two samples
        const GaugeReading& before = *(first - 1);
        a.arrival_time = before.time + (arrival_depth - before.depth) / (first->depth - before.depth) *
                                           (first->time - before.time);
    }
    double window_end = record.back().time;
    if (std::isfinite(t_impact) && t_impact > a.arrival_time) {
        a.front_velocity = distance / (t_impact - a.arrival_time);
        if (std::isfinite(t_peak)) {
            a.source_time = t_peak - distance / a.front_velocity;
            a.at_source = interpolate(record, a.source_time);
            window_end = a.source_time;
        }
    }
    a.max_depth = a.max_discharge = a.max_velocity = 0.0;
    for (auto r = first; r != record.end() && r->time <= window_end; ++r) {
        a.max_depth = std::max(a.max_depth, r->depth);
        a.max_discharge = std::max(a.max_discharge, r->discharge);
        a.max_velocity = std::max(a.max_velocity, r->velocity);
    }
    if (std::isfinite(a.source_time)) {  // the window ends between two samples
        a.max_depth = std::max(a.max_depth, a.at_source.depth);
        a.max_discharge = std::max(a.max_discharge, a.at_source.discharge);
        a.max_velocity = std::max(a.max_velocity, a.at_source.velocity);
    }
    return a;
}

}  // namespace sabo::analysis
