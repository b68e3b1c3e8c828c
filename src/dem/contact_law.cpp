// SPDX-License-Identifier: MIT
#include "dem/contact_law.h"

#include <numbers>

namespace sabo::dem {

double damping_ratio_from_restitution(double restitution) {
    const double l = std::log(restitution);
    return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

double clipped_linear_restitution(double alpha) {
    const double s = std::sqrt(1.0 - alpha * alpha);
    // the force vanishes at ω t = π − atan2(2αs, 1 − 2α²): past the half period for α < 1/√2, before it above
    const double phase = std::numbers::pi - std::atan2(2.0 * alpha * s, 1.0 - 2.0 * alpha * alpha);
    return std::exp(-(alpha / s) * phase);
}

double LinearNormal::contact_time(double m_eff) const {
    return std::numbers::pi / std::sqrt(kn / m_eff * (1.0 - alpha_n * alpha_n));
}

double HertzNormal::contact_time(double m_eff, double r_eff, double impact_speed) const {
    return 2.8683 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * impact_speed), 0.2);
}

template <class Normal>
double effective_restitution(const Normal& law, double m_eff, double r_eff, double impact_speed,
                             double contact_time) {
    // state: overlap δ and its rate δ' (= v_n); contact ends when δ ≤ 0 or the clipped force is 0
    // while separating.
    const double h = contact_time / 20000.0;
    double d = 0.0, v = impact_speed;
    auto acc = [&](double dd, double vv) {
        return dd > 0.0 ? -law.force(dd, vv, m_eff, r_eff).fn / m_eff : 0.0;
    };
    for (long step = 0; step < 10'000'000; ++step) {
        const double k1d = v, k1v = acc(d, v);
        const double k2d = v + 0.5 * h * k1v, k2v = acc(d + 0.5 * h * k1d, v + 0.5 * h * k1v);
        const double k3d = v + 0.5 * h * k2v, k3v = acc(d + 0.5 * h * k2d, v + 0.5 * h * k2v);
        const double k4d = v + h * k3v, k4v = acc(d + h * k3d, v + h * k3v);
        d += h / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
        v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
        if (v < 0.0 && d <= 0.0) break;  // after a clipped force reaches 0 the velocity stays constant
    }
    return -v / impact_speed;
}

template double effective_restitution(const LinearNormal&, double, double, double, double);
template double effective_restitution(const HertzNormal&, double, double, double, double);

}  // namespace sabo::dem
