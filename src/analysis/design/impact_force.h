// SPDX-License-Identifier: MIT
// The empirical debris-flow impact formulas of the design guidelines (docs/design.md): hydrostatic
// p = k ρ g h, hydrodynamic p = k ρ v², and the mixed forms of Kherkheulidze, Hübl & Holzinger,
// Zanuttigh & Lamberti and Arattano & Franzi. SI units throughout: ρ the flow's bulk density (kg/m³),
// h its depth (m), v its depth-averaged velocity (m/s); pressures in Pa, forces per metre of barrier
// width in N/m.
#pragma once
#include <functional>
#include <string>
#include <vector>

namespace sabo::analysis::design {

// The approaching flow.
struct Flow {
    double depth = 0.0;                   // h, m
    double velocity = 0.0;                // v, m/s
    double density = 0.0;                 // ρ, kg/m³ (bulk)
    double g = 9.81;                      // m/s²
    [[nodiscard]] double froude() const;  // v / sqrt(g h)
};

// Hydrostatic: peak pressure k ρ g h at the base, triangular over h: F/W = ½ k ρ g h².
[[nodiscard]] double hydrostatic_force_per_width(const Flow& f, double k);
// Hydrodynamic: p = k ρ v² uniform over h: F/W = k ρ v² h.
[[nodiscard]] double hydrodynamic_force_per_width(const Flow& f, double k);
// Kherkheulidze (1967): p = 0.1 γ (5 h + v²) with γ in tf/m³ and p in tf/m² (h in m, v in m/s as
// numbers), in SI p = (g_n/10) ρ (5 h + v²) ≈ ρ (g h/2 + v²); uniform over h: F/W = p h.
[[nodiscard]] double kherkheulidze_pressure(const Flow& f);
// Hübl & Holzinger (2003): peak pressure p = c ρ v^0.8 (g h)^0.6 (= c ρ v² Fr^−1.2), applied over h.
[[nodiscard]] double hubl_holzinger_pressure(const Flow& f, double c);
// Zanuttigh & Lamberti (2006): F/W = k/2 ρ g h² (1 + √2 Fr)², hydrostatic over the run-up h(1 + √2 Fr).
[[nodiscard]] double zanuttigh_lamberti_force_per_width(const Flow& f, double k);
// Arattano & Franzi (2003): F/W = ρ q v + ρ g h²/2 with the discharge per width q = v h.
[[nodiscard]] double arattano_franzi_force_per_width(const Flow& f);

// One formula of the catalogue: its force per width for a coefficient in [k_low, k_high] (equal for a
// single value; the force grows with k in every formula).
struct ImpactFormula {
    std::string approach;   // hydrostatic | hydrodynamic | mixed
    std::string reference;  // "Armanini (1997)"
    std::string formula;    // as the guideline writes it
    double k_low = 0.0, k_high = 0.0;
    std::function<double(const Flow&, double)> force_per_width;  // N/m
};
// Every formula with the coefficients its reference gives (docs/design.md lists their sources).
[[nodiscard]] const std::vector<ImpactFormula>& impact_formulas();

// Back-calculated coefficients of a measured force per width, the way the literature defines them:
// k_hydrostatic = (F/W) / (½ ρ g h²), k_hydrodynamic = (F/W) / (ρ v² h); NaN when the denominator is 0.
[[nodiscard]] double back_calculated_hydrostatic_k(double force_per_width, const Flow& f);
[[nodiscard]] double back_calculated_hydrodynamic_k(double force_per_width, const Flow& f);

}  // namespace sabo::analysis::design
