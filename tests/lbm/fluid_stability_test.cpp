// SPDX-License-Identifier: MIT
// The fluid's run-time checks: a mass drift beyond lattice.max_mass_drift or a lattice speed beyond 0.5
// stops the run with the time, the quantity and the limit; round-off-sized drifts pass.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "lbm/fluid_setup.h"

namespace sabo {
namespace {

std::string failure(double drift, double speed, double limit) {
    try {
        lbm::check_fluid_stable(1.25, drift, speed, limit);
    } catch (const RunError& e) {
        return e.what();
    }
    return {};
}

TEST(FluidStability, MassDriftBeyondTheLimitStopsTheRun) {
    EXPECT_EQ(failure(1e-13, 0.1, 1e-6), "");
    EXPECT_EQ(failure(-9e-7, 0.1, 1e-6), "");
    EXPECT_EQ(
        failure(-2e-6, 0.1, 1e-6),
        "t = 1.25 s: the fluid's mass drifted by -2e-06 (relative; limit 1e-06, lattice.max_mass_drift): "
        "the free surface lost or made mass");
}

TEST(FluidStability, NonFiniteMassOrFastLatticeStopsTheRun) {
    EXPECT_NE(failure(NAN, 0.1, 1e-6).find("the fluid became unstable"), std::string::npos);
    EXPECT_NE(failure(0.0, 0.6, 1e-6).find("the fluid became unstable (lattice speed 0.6)"),
              std::string::npos);
    EXPECT_NE(failure(0.0, NAN, 1e-6).find("the fluid became unstable"), std::string::npos);
}

}  // namespace
}  // namespace sabo
