// SPDX-License-Identifier: MIT
// Measures of the flow relative to the barrier (docs/analysis.md), computed from a synchronous state:
// non-retained fraction, mean kinetic energy downstream, and the flow height and velocity in the
// first metre upstream used by the design coefficients k_st and k_dyn.
#pragma once
#include "dem/particles.h"
#include "scenario/barrier.h"

namespace sabo::analysis {

// Mass of grains whose centre is downstream of the barrier's downstream face / total mass. Grains no longer
// in `p` count in the whole: `removed_mass` (kg) neither retained nor passed (those that went over an open
// channel's side walls), `passed_mass` (kg) as passed (those that left through its open end).
[[nodiscard]] double non_retained_fraction(const dem::Particles& p, const scenario::BarrierInfo& barrier,
                                           double removed_mass = 0.0, double passed_mass = 0.0);

// Mean kinetic energy (translational + rotational) per grain downstream of the barrier, J (0 when
// no grain is downstream), and their count.
struct DownstreamEnergy {
    double mean_J = 0.0;
    std::size_t grains = 0;
};
[[nodiscard]] DownstreamEnergy downstream_energy(const dem::Particles& p,
                                                 const scenario::BarrierInfo& barrier);

// Flow in the reach [0, length] upstream of the barrier face (X distance at the grain's height):
// height h = mean over strips of width `strip` across the channel of the highest grain top
// (z + r) in the strip (0 for an empty strip); velocity v = mass-weighted mean down-slope (X)
// velocity of the grains in the reach; solid fraction: their volume over the reach's length × width × h.
struct UpstreamFlow {
    double height = 0.0;          // m
    double velocity = 0.0;        // m/s
    double solid_fraction = 0.0;  // grain volume / (length × channel width × h): bulk density / grain density
    std::size_t grains = 0;
};
[[nodiscard]] UpstreamFlow upstream_flow(const dem::Particles& p, const scenario::BarrierInfo& barrier,
                                         double channel_width, double length = 1.0, double strip = 0.1);

// The grain diameter below which the given fraction of the mobile grains' mass lies (D95: 0.95), m.
[[nodiscard]] double mass_percentile_diameter(const dem::Particles& p, double fraction);

// Design coefficients (docs/analysis.md) from the peak normal force per metre of barrier width:
// k_st = F/(ρ g h²), k_dyn = F/(ρ v² h). NaN when h (or v) is zero.
[[nodiscard]] double k_static(double force_per_width, double density, double g, double h);
[[nodiscard]] double k_dynamic(double force_per_width, double density, double v, double h);

}  // namespace sabo::analysis
