// SPDX-License-Identifier: MIT
// What an open barrier retains, by the empirical relations and guideline ranges (docs/design.md):
// Silva et al. (2016) trapping efficiency, Mizuyama (1995) peak-discharge reduction, the national
// guidelines' slit width S/D_max and the silo's clogging ratio S/D.
#pragma once
#include <string>
#include <vector>

namespace sabo::analysis::design {

// Silva et al. (2016): E_tr = 1.55 (1 − ΣS/W)^0.7 / ((S/D95)^1.40 e^{v_d}), v_d = 2.1 Q_peak^0.33 θ^0.33,
// read with Q_peak in m³/s and θ the bed slope in degrees; a laboratory-flume regression, clamped to [0, 1].
struct SilvaInputs {
    double open_ratio = 0.0;      // ΣS/W: total outlet width over channel width
    double s_over_d95 = 0.0;      // S/D95
    double peak_discharge = 0.0;  // Q_peak, m³/s
    double slope_deg = 0.0;       // θ, degrees
};
[[nodiscard]] double silva_trapping_efficiency(const SilvaInputs& in);

// Mizuyama (1995): ratio of the peak discharge below a slit dam to that above it,
// Q_p,down/Q_p,up = 0.11 (S/D_max)^0.36 C_s^−0.96 (C_s the volumetric sediment concentration), clamped
// to [0, 1]; the reduction is 1 − ratio (docs/design.md: the review's "(0.11 (S/D_max)^0.36 − 1)" read so).
[[nodiscard]] double mizuyama_peak_discharge_ratio(double s_over_dmax, double sediment_concentration);

// A range of S/D a guideline or experiment gives for a barrier that retains (blocks) the coarse grains.
struct SlitRange {
    std::string source;
    std::string ratio;  // "S/D_max" | "S/D"
    double low = 0.0, high = 0.0;
};
[[nodiscard]] const std::vector<SlitRange>& slit_width_ranges();
// Where S/D falls against a range: "below" (narrower: blocks), "within", "above" (wider: passes).
[[nodiscard]] std::string place_in_range(double s_over_d, const SlitRange& range);

}  // namespace sabo::analysis::design
