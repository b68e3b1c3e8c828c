// SPDX-License-Identifier: MIT
#include "analysis/flow_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sabo::analysis {

double non_retained_fraction(const dem::Particles& p, const scenario::BarrierInfo& barrier,
                             double removed_mass, double passed_mass) {
    double out = passed_mass, total = removed_mass + passed_mass;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        total += p.m[i];
        if (barrier.downstream(p.x[i])) out += p.m[i];
    }
    return total > 0.0 ? out / total : 0.0;
}

DownstreamEnergy downstream_energy(const dem::Particles& p, const scenario::BarrierInfo& barrier) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        if (!barrier.downstream(p.x[i])) continue;
        sum += p.kinetic_energy(i);
        ++n;
    }
    return {n > 0 ? sum / static_cast<double>(n) : 0.0, n};
}

UpstreamFlow upstream_flow(const dem::Particles& p, const scenario::BarrierInfo& barrier,
                           double channel_width, double length, double strip) {
    const auto n_strips =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(channel_width / strip)));
    const double dy = channel_width / static_cast<double>(n_strips);
    std::vector<double> top(n_strips, 0.0);
    UpstreamFlow flow;
    double mass = 0.0, momentum = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const double d = barrier.upstream_distance(p.x[i]);
        if (d < 0.0 || d > length) continue;
        const auto s = std::min(n_strips - 1, static_cast<std::size_t>(std::max(0.0, p.x[i].y / dy)));
        top[s] = std::max(top[s], p.x[i].z + p.r[i]);
        mass += p.m[i];
        volume += dem::sphere_volume(p.r[i]);
        momentum += p.m[i] * p.v[i].x;
        ++flow.grains;
    }
    double sum = 0.0;
    for (double t : top) sum += t;
    flow.height = sum / static_cast<double>(n_strips);
    flow.velocity = mass > 0.0 ? momentum / mass : 0.0;
    const double bulk = length * channel_width * flow.height;
    flow.solid_fraction = bulk > 0.0 ? volume / bulk : 0.0;
    return flow;
}

double mass_percentile_diameter(const dem::Particles& p, double fraction) {
    std::vector<std::pair<double, double>> by_radius;  // (r, m)
    double total = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) by_radius.emplace_back(p.r[i], p.m[i]), total += p.m[i];
    std::sort(by_radius.begin(), by_radius.end());
    double below = 0.0;
    for (const auto& [r, m] : by_radius) {
        below += m;
        if (below >= fraction * total) return 2.0 * r;
    }
    return by_radius.empty() ? 0.0 : 2.0 * by_radius.back().first;
}

double k_static(double force_per_width, double density, double g, double h) {
    const double q = density * g * h * h;
    return q > 0.0 ? force_per_width / q : std::numeric_limits<double>::quiet_NaN();
}

double k_dynamic(double force_per_width, double density, double v, double h) {
    const double q = density * v * v * h;
    return q > 0.0 ? force_per_width / q : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace sabo::analysis
