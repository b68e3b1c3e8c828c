// SPDX-License-Identifier: MIT
// The memory a DEM run of a given number of spheres needs, known before any sphere is placed: case
// builders refuse a request too large for the machine arithmetically (a release of 1e9 m³ is refused in
// microseconds, not after the placement has exhausted the memory).
#pragma once
#include <string_view>

namespace sabo {
class Config;
}

namespace sabo::dem {

// Bytes a run needs per sphere (state, list entries with their history and force slots, wall
// candidates, the previous lists kept for the history transfer).
[[nodiscard]] double memory_estimate_bytes(double spheres);

// What `spheres` need against what the machine has: a run may take 80 % of the available memory.
struct MemoryNeed {
    double need_bytes = 0.0, available_bytes = 0.0;
    [[nodiscard]] bool fits() const { return need_bytes <= 0.8 * available_bytes; }  // false for NaN too
};
[[nodiscard]] MemoryNeed memory_need(double spheres);

// Expected number of grains of radii uniform in r_mean (1 ± spread) that make up `solid_volume`:
// E[r³] = r_mean³ (1 + spread²).
[[nodiscard]] double expected_grain_count(double solid_volume, double r_mean, double spread);

// Fails `key` of `cfg` when `spheres` (an arithmetic estimate: it may be fractional or huge) would need
// more than 80 % of the available memory; `what` names them in the message ("grains", "barrier spheres").
void check_sphere_budget(const Config& cfg, std::string_view key, double spheres, std::string_view what);

}  // namespace sabo::dem
