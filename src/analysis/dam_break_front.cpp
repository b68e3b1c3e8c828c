// SPDX-License-Identifier: MIT
#include "analysis/dam_break_front.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sabo::analysis {

namespace {

// Martin & Moyce (1952), column height 2a (n² = 2): front Z = x/a at T = t sqrt(2g/a).
struct FrontPoint {
    double t_scaled, front_over_a;
};
constexpr FrontPoint martin_moyce_front[] = {{0.41, 1.11}, {0.84, 1.22}, {1.19, 1.44}, {1.43, 1.67},
                                             {1.63, 1.89}, {1.83, 2.11}, {1.98, 2.33}, {2.20, 2.56},
                                             {2.32, 2.78}, {2.51, 3.00}, {2.65, 3.22}, {2.83, 3.44},
                                             {2.97, 3.67}, {3.11, 3.89}, {3.33, 4.11}};

}  // namespace

FrontComparison compare_with_martin_moyce(const std::vector<double>& times,
                                          const std::vector<double>& fronts) {
    FrontComparison c;
    double sum2 = 0.0;
    for (const auto& p : martin_moyce_front) {
        if (times.empty() || p.t_scaled > times.back()) break;
        const auto it = std::lower_bound(times.begin(), times.end(), p.t_scaled);
        const auto j = static_cast<std::size_t>(it - times.begin());
        double z = fronts[j];
        if (j > 0) {
            const double w = (p.t_scaled - times[j - 1]) / (times[j] - times[j - 1]);
            z = fronts[j - 1] + w * (fronts[j] - fronts[j - 1]);
        }
        c.points.push_back({p.t_scaled, p.front_over_a, z});
        sum2 += (z / p.front_over_a - 1.0) * (z / p.front_over_a - 1.0);
    }
    if (!c.points.empty()) c.rms_relative_error = std::sqrt(sum2 / static_cast<double>(c.points.size()));
    return c;
}

}  // namespace sabo::analysis
