// SPDX-License-Identifier: MIT
#include "dem/friction_calibration.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace sabo::dem {

double repose_angle_deg(double mu_s, double mu_r) {
    return mu_r <= calibration_mu_r_max ? calibration_a_low * std::sqrt(mu_r * mu_s)
                                        : calibration_a_high * std::sqrt(mu_s);
}

FrictionPair friction_from_repose_angle(double phi_deg, const char* what) {
    const double mu_s = std::tan(phi_deg * std::numbers::pi / 180.0);
    if (!(phi_deg > 0.0))
        throw InputError(fmt::format("{} = {:g}: the angle must be positive", what, phi_deg));
    if (mu_s > calibration_mu_s_max) {
        // steep angles (coarse debris: 35-40 deg) are in the law's range with a mu_s below tan(phi)
        const double reach = calibration_a_low * std::sqrt(calibration_mu_r_max * calibration_mu_s_max);
        const std::string way =
            phi_deg <= reach
                ? fmt::format(
                      "give mu_s as well (`sabo calibrate --mu-s`, or mu_s and mu_r in the case's [contact] "
                      "tables): with mu_s = {} the law gives mu_r = {:.4f}",
                      calibration_mu_s_max,
                      phi_deg * phi_deg / (calibration_a_low * calibration_a_low * calibration_mu_s_max))
                : fmt::format(
                      "the law reaches at most {:.2f} deg (mu_s = {}, mu_r = {}): give mu_s and mu_r "
                      "explicitly and check the angle with a sandpile (docs/calibration.md)",
                      reach, calibration_mu_s_max, calibration_mu_r_max);
        throw InputError(
            fmt::format("{} = {:g}: the default mu_s = tan(phi) = {:.3f} is above the calibration "
                        "law's range (0, {}], which it leaves above {:.2f} deg; {}",
                        what, phi_deg, mu_s, calibration_mu_s_max,
                        std::atan(calibration_mu_s_max) * 180.0 / std::numbers::pi, way));
    }
    const double mu_r = phi_deg * phi_deg / (calibration_a_low * calibration_a_low * mu_s);
    if (mu_r > calibration_mu_r_max) {
        throw InputError(
            fmt::format("{} = {:g}: the calibration law gives mu_r = {:.4f} > {} (outside its fitted "
                        "range); give mu_s and mu_r explicitly instead",
                        what, phi_deg, mu_r, calibration_mu_r_max));
    }
    return {mu_s, mu_r};
}

FrictionPair friction_from_repose_angle(double phi_deg, double mu_s, const char* what) {
    if (!(phi_deg > 0.0))
        throw InputError(fmt::format("{} = {:g}: the angle must be positive", what, phi_deg));
    if (!(mu_s > 0.0) || mu_s > calibration_mu_s_max) {
        throw InputError(
            fmt::format("mu_s = {:g} is outside the calibration law's range (0, {}] (docs/calibration.md)",
                        mu_s, calibration_mu_s_max));
    }
    const double mu_r = phi_deg * phi_deg / (calibration_a_low * calibration_a_low * mu_s);
    if (mu_r > calibration_mu_r_max) {
        throw InputError(fmt::format(
            "{} = {:g} with mu_s = {:g} needs mu_r = {:.4f} > {} (outside the law's fitted range): with this "
            "mu_s the law reaches at most {:.2f} deg; raise mu_s (at most {}) or leave it to the default "
            "mapping",
            what, phi_deg, mu_s, mu_r, calibration_mu_r_max, repose_angle_deg(mu_s, calibration_mu_r_max),
            calibration_mu_s_max));
    }
    return {mu_s, mu_r};
}

double zhou_repose_angle_deg(double mu_s_pp, double mu_s_pw, double mu_r_pp_mm, double mu_r_pw_mm,
                             double diameter_mm) {
    return 68.61 * std::pow(mu_s_pp, 0.27) * std::pow(mu_s_pw, 0.22) * std::pow(mu_r_pp_mm, 0.06) *
           std::pow(mu_r_pw_mm, 0.12) * std::pow(diameter_mm, -0.2);
}

}  // namespace sabo::dem
