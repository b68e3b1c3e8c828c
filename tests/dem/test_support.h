// SPDX-License-Identifier: MIT
// Builders shared by the DEM tests: contact-law sets with explicit coefficients.
#pragma once
#include "dem/contact_law.h"
#include "dem/dem_solver.h"

namespace sabo::test {

struct LawSpec {
    double kn = 1e5;
    double restitution = 0.5;
    bool clip = true;
    double mu_s = 0.5;
    double mu_d_ratio = 0.9;
    double alpha_t = 1.0;
    double mu_r = 0.0;
    double kt_ratio = 2.0 / 7.0;
    dem::RollingModel rolling_model = dem::RollingModel::constraint;
};

inline dem::ContactLaw<dem::LinearNormal> linear_law(const LawSpec& s) {
    dem::ContactLaw<dem::LinearNormal> law;
    law.normal.kn = s.kn;
    law.normal.alpha_n = s.restitution >= 1.0 ? 0.0 : dem::damping_ratio_from_restitution(s.restitution);
    law.normal.kt_ratio = s.kt_ratio;
    law.normal.clip_attractive = s.clip;
    law.tangential = {s.alpha_t, s.mu_s, s.mu_d_ratio * s.mu_s, dem::FrictionMemory::hysteresis};
    law.rolling.mu_r = s.mu_r;
    law.rolling.model = s.rolling_model;
    return law;
}

inline dem::AnyContactLaws same_everywhere(const dem::ContactLaw<dem::LinearNormal>& law) {
    return dem::ContactLawSet<dem::LinearNormal>{law, law, law};
}

inline double mass_of(double r, double rho) {
    return rho * 4.0 / 3.0 * 3.141592653589793 * r * r * r;
}

}  // namespace sabo::test
