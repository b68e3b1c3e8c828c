// SPDX-License-Identifier: MIT
#include "analysis/design/boulder_impact.h"

#include <cmath>
#include <numbers>

namespace sabo::analysis::design {

using std::numbers::pi;

double Elastic::compliance() const {
    return (1.0 - poisson * poisson) / (pi * youngs_modulus);
}

double Boulder::mass() const {
    return 4.0 / 3.0 * pi * radius * radius * radius * density;
}

HertzImpact hertz_impact(const Boulder& b, const Elastic& boulder, const Elastic& barrier) {
    HertzImpact h;
    h.stiffness = 4.0 * std::sqrt(b.radius) / (3.0 * pi * (boulder.compliance() + barrier.compliance()));
    h.indentation = std::pow(5.0 * b.mass() * b.velocity * b.velocity / (4.0 * h.stiffness), 0.4);
    h.elastic_force = h.stiffness * std::pow(h.indentation, 1.5);
    return h;
}

double hertz_closed_form_constant(double boulder_density, const Elastic& boulder, const Elastic& barrier) {
    // n α^1.5 = n^0.4 (5 m v²/4)^0.6 with n = c_n sqrt(r) and m = (4/3) π ρ r³: C r² v^1.2
    const double c_n = 4.0 / (3.0 * pi * (boulder.compliance() + barrier.compliance()));
    return std::pow(c_n, 0.4) * std::pow(5.0 * pi * boulder_density / 3.0, 0.6);
}

const std::vector<ReductionFactor>& load_reduction_factors() {
    static const std::vector<ReductionFactor> all{
        {"Hungr, Morgan & Kellerhals (1984); Kwan (2012)", 0.1},
        {"Yamaguchi; Mizuyama (variants)", 0.2},
        {"Huang et al. (2007)", 0.06},
    };
    return all;
}

double ClosedForm::force(double velocity, double radius) const {
    return k_hat * newtons_per_unit * std::pow(velocity, 1.2) * radius * radius;
}

const std::vector<ClosedForm>& hertz_closed_forms() {
    constexpr double kN = 1000.0, tf = 9806.65;
    static const std::vector<ClosedForm> all{
        {241.0, kN, "kN"}, {48.2, tf, "tf"}, {426.0, kN, "kN"},
        {50.0, tf, "tf"},  {80.8, tf, "tf"}, {30.8, tf, "tf"},
    };
    return all;
}

}  // namespace sabo::analysis::design
