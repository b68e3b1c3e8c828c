// SPDX-License-Identifier: MIT
#include "dem/grain_budget.h"

#include <fmt/format.h>

#include "core/config.h"
#include "core/memory.h"
#include "dem/particles.h"

namespace sabo::dem {

namespace {
// 5 vectors + 4 scalars of state; ~10 list partners (index, slot, history 32 B, force 48 B) and ~4 wall
// candidates, each twice (the current and the previous lists).
constexpr double bytes_per_sphere = 5 * 24 + 4 * 8 + 10 * (4 + 4 + 32 + 48) * 2 + 4 * (2 + 32 + 24) * 2;
}  // namespace

double memory_estimate_bytes(double spheres) {
    return bytes_per_sphere * spheres;
}

MemoryNeed memory_need(double spheres) {
    return {memory_estimate_bytes(spheres), available_memory_bytes()};
}

double expected_grain_count(double solid_volume, double r_mean, double spread) {
    return solid_volume / (sphere_volume(r_mean) * (1.0 + spread * spread));
}

void check_sphere_budget(const Config& cfg, std::string_view key, double spheres, std::string_view what) {
    const MemoryNeed m = memory_need(spheres);
    // (summed over the kinds of spheres: `sabo check` weighs the whole run's memory against the machine's)
    cfg.record("derived.grains_memory_MiB",
               cfg.recorded_number("derived.grains_memory_MiB") + m.need_bytes / 1048576.0);
    if (!m.fits()) {
        cfg.fail(key,
                 fmt::format("about {:.3g} {} would need {:.3g} GiB of memory; {:.1f} GiB is available "
                             "(at most 80 % of it is used)",
                             spheres, what, m.need_bytes / 1073741824.0, m.available_bytes / 1073741824.0));
    }
}

}  // namespace sabo::dem
