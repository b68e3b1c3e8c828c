// SPDX-License-Identifier: MIT
// The load on each triangle of a mesh barrier (docs/geometry.md, "Force maps on the mesh"): the grains' and
// the fluid's, taken at the steps the barrier's force maps are (first impact t1, the largest local force t2,
// the largest global force t3, the end: analysis/barrier_forces.h), so that a part's triangles add up to its
// element's map, and at the grains' and the fluid's own peaks.
#pragma once
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "analysis/barrier_forces.h"
#include "core/vec3.h"

namespace sabo::analysis {

struct FacetMaps {
    // t1, t2, t3, end, the grains' own peak (the largest normal force of their contacts: in a run with a
    // fluid its front often loads the barrier first and most, while the grains touch it later) and the
    // fluid's
    static constexpr std::size_t count = 6;
    static constexpr std::size_t grains_peak = 4, fluid_peak = 5;
    // per map, per triangle, N (empty: never taken, or a run without that component)
    std::array<std::vector<Vec3>, count> grains, fluid;

    // After `monitor` recorded the step at `time_now` (or took its end map: `end`): the maps that fall on
    // this step, from the triangles' forces of this step that `fetch(grains, fluid)` writes (asked for only
    // when one does; a component the run lacks left empty).
    template <class Fetch>
    void take(const BarrierForceMonitor& monitor, double time_now, bool end, Fetch&& fetch) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const std::array<double, count> due{
            monitor.map_t1().time,
            monitor.map_t2().time,
            monitor.map_t3().time,
            monitor.map_end().time,
            monitor.max_solid_normal() > 0.0 ? monitor.time_of_max_solid_normal() : nan,
            monitor.max_fluid_normal() > 0.0 ? monitor.time_of_max_fluid_normal() : nan};
        bool fetched = false;
        for (std::size_t k = 0; k < count; ++k) {
            if ((k == 3) != end || due[k] != time_now) continue;
            if (!fetched) fetch(grains_now_, fluid_now_);
            fetched = true;
            grains[k] = grains_now_;
            fluid[k] = fluid_now_;
        }
    }
    template <class Archive>
    void transfer(Archive& a) {
        for (std::size_t k = 0; k < count; ++k) a(grains[k], fluid[k]);
    }

  private:
    std::vector<Vec3> grains_now_, fluid_now_;  // scratch: this step's
};

}  // namespace sabo::analysis
