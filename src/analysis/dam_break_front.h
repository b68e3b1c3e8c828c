// SPDX-License-Identifier: MIT
// The dam break's surge front against the experiment of Martin & Moyce (1952): the front Z = x/a at their
// scaled times T = t sqrt(2g/a), read off a run's series by linear interpolation.
#pragma once
#include <vector>

namespace sabo::analysis {

struct FrontComparison {
    struct Point {
        double t_scaled = 0.0;    // T
        double experiment = 0.0;  // Z measured
        double simulation = 0.0;  // Z of the run at T
    };
    std::vector<Point> points;        // the experiment's times the run reached
    double rms_relative_error = 0.0;  // sqrt(mean (Z_sim/Z_exp − 1)²), 0 if no point
};

// `t_scaled` ascending, `front_over_a` the run's front at those times.
[[nodiscard]] FrontComparison compare_with_martin_moyce(const std::vector<double>& t_scaled,
                                                        const std::vector<double>& front_over_a);

}  // namespace sabo::analysis
