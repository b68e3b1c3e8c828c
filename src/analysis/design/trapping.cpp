// SPDX-License-Identifier: MIT
#include "analysis/design/trapping.h"

#include <algorithm>
#include <cmath>

namespace sabo::analysis::design {

double silva_trapping_efficiency(const SilvaInputs& in) {
    const double v_d = 2.1 * std::pow(in.peak_discharge, 0.33) * std::pow(in.slope_deg, 0.33);
    const double e =
        1.55 * std::pow(1.0 - in.open_ratio, 0.7) / (std::pow(in.s_over_d95, 1.40) * std::exp(v_d));
    return std::clamp(e, 0.0, 1.0);
}

double mizuyama_peak_discharge_ratio(double s_over_dmax, double sediment_concentration) {
    const double ratio = 0.11 * std::pow(s_over_dmax, 0.36) * std::pow(sediment_concentration, -0.96);
    return std::clamp(ratio, 0.0, 1.0);
}

const std::vector<SlitRange>& slit_width_ranges() {
    static const std::vector<SlitRange> all{
        {"China (guideline)", "S/D_max", 2.0, 4.5},
        {"Taiwan (guideline)", "S/D_max", 1.5, 2.0},
        {"Japan (technical standard 2007: S = D_max)", "S/D_max", 1.0, 1.0},
        {"Japan (earlier criterion)", "S/D_max", 1.5, 1.5},
        {"silo clogging (Zuriguel et al. 2005; To et al. 2001)", "S/D", 3.0, 6.0},
    };
    return all;
}

std::string place_in_range(double s_over_d, const SlitRange& range) {
    if (s_over_d < range.low) return "below";
    if (s_over_d > range.high) return "above";
    return "within";
}

}  // namespace sabo::analysis::design
