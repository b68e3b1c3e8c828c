// SPDX-License-Identifier: MIT
#include "analysis/design/impact_force.h"

#include <cmath>
#include <limits>

namespace sabo::analysis::design {

namespace {
constexpr double standard_gravity = 9.80665;  // m/s²: 1 tf = 9.80665 kN
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double Flow::froude() const {
    return depth > 0.0 ? velocity / std::sqrt(g * depth) : nan;
}

double hydrostatic_force_per_width(const Flow& f, double k) {
    return 0.5 * k * f.density * f.g * f.depth * f.depth;
}

double hydrodynamic_force_per_width(const Flow& f, double k) {
    return k * f.density * f.velocity * f.velocity * f.depth;
}

double kherkheulidze_pressure(const Flow& f) {
    // 0.1 γ[tf/m³] (5 h + v²) tf/m², γ[tf/m³] = ρ/1000, 1 tf/m² = 1000 g_n Pa
    return 0.1 * standard_gravity * f.density * (5.0 * f.depth + f.velocity * f.velocity);
}

double hubl_holzinger_pressure(const Flow& f, double c) {
    return c * f.density * std::pow(f.velocity, 0.8) * std::pow(f.g * f.depth, 0.6);
}

double zanuttigh_lamberti_force_per_width(const Flow& f, double k) {
    const double runup = 1.0 + std::sqrt(2.0) * f.froude();
    return 0.5 * k * f.density * f.g * f.depth * f.depth * runup * runup;
}

double arattano_franzi_force_per_width(const Flow& f) {
    const double q = f.velocity * f.depth;
    return f.density * q * f.velocity + 0.5 * f.density * f.g * f.depth * f.depth;
}

const std::vector<ImpactFormula>& impact_formulas() {
    static const std::vector<ImpactFormula> all = [] {
        const auto hs = [](const Flow& f, double k) { return hydrostatic_force_per_width(f, k); };
        const auto hd = [](const Flow& f, double k) { return hydrodynamic_force_per_width(f, k); };
        const std::string p_hs = "p = k rho g h", p_hd = "p = k rho v^2";
        return std::vector<ImpactFormula>{
            {"hydrostatic", "Lichtenhahn (1973)", p_hs, 3.0, 11.0, hs},
            {"hydrostatic", "Armanini (1997)", p_hs, 5.0, 5.0, hs},
            {"hydrostatic", "Scotton & Deganutti (1997)", p_hs, 2.5, 7.5, hs},
            {"hydrodynamic", "Watanabe & Ikeya (1981)", p_hd, 2.0, 2.0, hd},
            {"hydrodynamic", "Lo (2000), Hong Kong", p_hd, 3.0, 3.0, hd},
            {"hydrodynamic", "Egli (2005)", p_hd, 2.0, 4.0, hd},
            {"hydrodynamic", "Wendeler (2008)", p_hd, 0.7, 2.0, hd},
            {"hydrodynamic", "Bugnion et al. (2012)", p_hd, 0.4, 2.0, hd},
            {"mixed", "Kherkheulidze (1967)", "p = 0.1 gamma (5 h + v^2) [tf/m2]", 1.0, 1.0,
             [](const Flow& f, double k) { return k * kherkheulidze_pressure(f) * f.depth; }},
            {"mixed", "Hübl & Holzinger (2003)", "p = k rho v^0.8 (g h)^0.6", 4.5, 5.0,
             [](const Flow& f, double k) { return hubl_holzinger_pressure(f, k) * f.depth; }},
            {"mixed", "Zanuttigh & Lamberti (2006)", "F/W = k/2 rho g h^2 (1 + sqrt(2) Fr)^2", 1.0, 1.0,
             [](const Flow& f, double k) { return zanuttigh_lamberti_force_per_width(f, k); }},
            {"mixed", "Arattano & Franzi (2003)", "F/W = rho q v + rho g h^2 / 2", 1.0, 1.0,
             [](const Flow& f, double k) { return k * arattano_franzi_force_per_width(f); }},
        };
    }();
    return all;
}

double back_calculated_hydrostatic_k(double force_per_width, const Flow& f) {
    const double unit = hydrostatic_force_per_width(f, 1.0);
    return unit > 0.0 ? force_per_width / unit : nan;
}

double back_calculated_hydrodynamic_k(double force_per_width, const Flow& f) {
    const double unit = hydrodynamic_force_per_width(f, 1.0);
    return unit > 0.0 ? force_per_width / unit : nan;
}

}  // namespace sabo::analysis::design
