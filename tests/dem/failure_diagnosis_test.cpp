// SPDX-License-Identifier: MIT
// A failed DEM step says where: the step, the time, and the grains (by release id) or the wall of the
// contact with the largest overlap, or the first grain whose state is not finite.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "dem/test_support.h"

namespace sabo {
namespace {

constexpr double r = 0.05, rho = 2500.0, dt = 1e-5;

std::string failure_of(dem::DemSolver& s, int steps) {
    try {
        for (int k = 0; k < steps; ++k) s.step();
    } catch (const RunError& e) {
        return e.what();
    }
    return {};
}

TEST(FailureDiagnosis, AnOverlapBeyondTheLimitNamesThePairAndTheStep) {
    dem::Particles p;
    p.add_mobile({5.0, 0, 0}, r, rho);  // a grain far away, so that the pair's ids are not 0 and 1
    p.add_mobile({0.0, 0, 0}, r, rho);
    p.add_mobile({0.09, 0, 0}, r, rho);  // overlaps the previous one by 10 % of d
    dem::DemSolver s(p, {}, test::same_everywhere(test::linear_law({})), {0, 0, 0}, dt, 0.01);
    EXPECT_EQ(failure_of(s, 10), "") << "the default limit is half a diameter";
    s.set_overlap_limit(0.05);
    const std::string message = failure_of(s, 1);
    EXPECT_NE(message.find("step 11, t = 0.00011 s: overlap reached 10 % of a diameter (limit 5 %, "
                           "dem.max_overlap_over_d): grain 1 and grain 2 at ("),
              std::string::npos)
        << message;
}

TEST(FailureDiagnosis, AWallOverlapNamesTheWall) {
    dem::Particles p;
    p.add_mobile({0, 0, 0.03}, r, rho);  // 2 cm into the bed: 20 % of d
    dem::DemSolver s(p, {dem::Wall::plane("bed", {0, 0, 0}, {0, 0, 1})},
                     test::same_everywhere(test::linear_law({})), {0, 0, 0}, dt, 0.01);
    s.set_overlap_limit(0.1);
    const std::string message = failure_of(s, 1);
    EXPECT_NE(message.find("overlap reached 20 % of a diameter (limit 10 %"), std::string::npos) << message;
    EXPECT_NE(message.find("grain 0 and wall 'bed'"), std::string::npos) << message;
}

TEST(FailureDiagnosis, AFreeGrainThatBlewUpIsFoundByTheStateCheck) {
    dem::Particles p;
    p.add_mobile({0, 0, 0}, r, rho);
    p.add_mobile({1, 0, 0}, r, rho, {std::numeric_limits<double>::quiet_NaN(), 0, 0});
    dem::DemSolver s(p, {}, test::same_everywhere(test::linear_law({})), {0, 0, -9.81}, dt, 0.01);
    EXPECT_EQ(failure_of(s, 3), "") << "no contact sees a free grain's NaN";
    try {
        s.check_finite();
        FAIL() << "check_finite() passed a NaN velocity";
    } catch (const RunError& e) {
        EXPECT_STREQ(e.what(),
                     "step 3, t = 3e-05 s: grain 1 has a non-finite position or velocity (the run "
                     "blew up)");
    }
}

// A grain that passed through a wall is named with where it is: the box is that of the walls enclosing the
// run; a grain past it by less than its radius (touching the wall's outside) is still inside.
TEST(FailureDiagnosis, AGrainThatLeftTheDomainIsNamed) {
    dem::Particles p;
    p.add_mobile({0.5, 0.5, 0.5}, r, rho);
    p.add_mobile({1.0 + 0.5 * r, 0.5, 0.5}, r, rho);
    p.add_mobile({0.5, 0.5, -2.0}, r, rho, {0, 0, -30});
    dem::DemSolver s(p, {}, test::same_everywhere(test::linear_law({})), {0, 0, 0}, dt, 0.01);
    try {
        s.check_inside({0, 0, 0}, {1, 1, 1});
        FAIL() << "check_inside() passed a grain 2 m below the bed";
    } catch (const RunError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("step 0, t = 0 s: grain 2 left the domain: its centre is at (0.5, 0.5, -2) m"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("moving at 30 m/s"), std::string::npos) << what;
    }
    dem::Particles q;
    q.add_mobile({1.0 + 0.5 * r, 0.5, 0.5}, r, rho);
    dem::DemSolver inside(q, {}, test::same_everywhere(test::linear_law({})), {0, 0, 0}, dt, 0.01);
    EXPECT_NO_THROW(inside.check_inside({0, 0, 0}, {1, 1, 1}));
}

}  // namespace
}  // namespace sabo
