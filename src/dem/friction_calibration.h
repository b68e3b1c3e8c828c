// SPDX-License-Identifier: MIT
// Friction coefficients from a measured angle of repose (docs/calibration.md).
//   φ_rep = 151.7 sqrt(μ_r μ_s) for μ_r ≤ 0.12;  φ_rep = 53.0 sqrt(μ_s) for μ_r > 0.12  (φ in degrees)
// Valid for μ_s ≤ 0.7, μ_r ≤ 0.12 (the range of the sandpile sweep it was fitted on).
#pragma once

namespace sabo::dem {

struct FrictionPair {
    double mu_s;  // static sliding friction [-]
    double mu_r;  // rolling friction, fraction of the rolling radius [-]
};

inline constexpr double calibration_a_low = 151.7;  // deg, μ_r ≤ 0.12 branch
inline constexpr double calibration_a_high = 53.0;  // deg, μ_r > 0.12 branch
inline constexpr double calibration_mu_s_max = 0.7;
inline constexpr double calibration_mu_r_max = 0.12;

// Forward law φ(μ_s, μ_r) in degrees.
[[nodiscard]] double repose_angle_deg(double mu_s, double mu_r);

// Default inverse: μ_s = tan φ, μ_r = φ² / (151.7² μ_s). Throws InputError (naming `what`) when
// tan φ > 0.7 or μ_r > 0.12.
[[nodiscard]] FrictionPair friction_from_repose_angle(double phi_deg,
                                                      const char* what = "friction_angle_deg");

// Inverse with μ_s chosen: μ_r = φ² / (151.7² μ_s). Throws InputError when μ_s is outside (0, 0.7]
// or μ_r > 0.12 (the angle is beyond the law's reach for this μ_s, 151.7 sqrt(0.12 μ_s)).
[[nodiscard]] FrictionPair friction_from_repose_angle(double phi_deg, double mu_s, const char* what);

// Zhou et al. (2002): φ = 68.61 μs_pp^0.27 μs_pw^0.22 μr_pp^0.06 μr_pw^0.12 D^−0.2, μ_r and D in mm.
[[nodiscard]] double zhou_repose_angle_deg(double mu_s_pp, double mu_s_pw, double mu_r_pp_mm,
                                           double mu_r_pw_mm, double diameter_mm);

}  // namespace sabo::dem
