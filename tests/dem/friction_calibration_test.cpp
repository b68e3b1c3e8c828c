// SPDX-License-Identifier: MIT
#include "dem/friction_calibration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace sabo::dem {

TEST(FrictionCalibration, ThirtyDegreesGivesTheReferenceCoefficients) {
    const auto f = friction_from_repose_angle(30.0);
    EXPECT_NEAR(f.mu_s, 0.5774, 1e-4);
    EXPECT_NEAR(f.mu_r, 0.0678, 1e-4);
    EXPECT_NEAR(repose_angle_deg(f.mu_s, f.mu_r), 30.0, 1e-9);  // inverse of the forward law
}

TEST(FrictionCalibration, UpperBranchAboveMuR012) {
    EXPECT_NEAR(repose_angle_deg(0.49, 0.2), 53.0 * 0.7, 1e-12);
}

TEST(FrictionCalibration, RefusesAnglesOutsideTheFittedRange) {
    EXPECT_THROW((void)friction_from_repose_angle(40.0), InputError);  // tan 40° = 0.84 > 0.7
    EXPECT_THROW((void)friction_from_repose_angle(0.0), InputError);
}

TEST(FrictionCalibration, InverseWithChosenMuS) {
    // φ = 25° with μ_s = 0.5: μ_r = 25² / (151.7² · 0.5) = 0.054318
    const auto f = friction_from_repose_angle(25.0, 0.5, "--angle-deg");
    EXPECT_DOUBLE_EQ(f.mu_s, 0.5);
    EXPECT_NEAR(f.mu_r, 625.0 / (151.7 * 151.7 * 0.5), 1e-12);
    for (double mu_s : {0.1, 0.3, 0.7}) {
        for (double phi : {5.0, 15.0, 25.0}) {
            if (phi * phi / (151.7 * 151.7 * mu_s) > 0.12) continue;
            const auto g = friction_from_repose_angle(phi, mu_s, "--angle-deg");
            EXPECT_NEAR(repose_angle_deg(g.mu_s, g.mu_r), phi, 1e-9) << mu_s << " " << phi;
        }
    }
    // beyond the law's reach for μ_s = 0.2 (151.7 sqrt(0.024) = 23.5°), and μ_s out of range
    EXPECT_THROW((void)friction_from_repose_angle(30.0, 0.2, "--angle-deg"), InputError);
    EXPECT_THROW((void)friction_from_repose_angle(20.0, 0.8, "--angle-deg"), InputError);
    EXPECT_THROW((void)friction_from_repose_angle(20.0, 0.0, "--angle-deg"), InputError);
}

TEST(FrictionCalibration, ZhouLawValue) {
    // all factors 1 except the diameter: 68.61 · 10^−0.2
    EXPECT_NEAR(zhou_repose_angle_deg(1, 1, 1, 1, 10.0), 68.61 * std::pow(10.0, -0.2), 1e-9);
}

}  // namespace sabo::dem
