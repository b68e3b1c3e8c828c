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

TEST(FrictionCalibration, ZhouLawValue) {
    // all factors 1 except the diameter: 68.61 · 10^−0.2
    EXPECT_NEAR(zhou_repose_angle_deg(1, 1, 1, 1, 10.0), 68.61 * std::pow(10.0, -0.2), 1e-9);
}

}  // namespace sabo::dem
