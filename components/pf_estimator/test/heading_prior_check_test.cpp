#include "components/pf_estimator/heading_prior_check.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "common/random.hpp"

namespace robodds::pf_estimator {
namespace {

using Verdict = HeadingPriorCheck::Verdict;

// A robot from (10, 20) with true heading true_theta, driving v on a gentle arc; 50 Hz odometry,
// 10 Hz fixes of std fix_std. The check is given prior_theta. Returns the verdict after `seconds`
// and the distance driven when it came (m; -1 if pending).
struct Outcome {
  Verdict verdict;
  double distance_m;
};

Outcome drive(double true_theta, double prior_theta, double fix_std, double v, double seconds, std::uint64_t seed) {
  HeadingPriorCheck check(0.5236);
  check.start(prior_theta);
  RandomEngine world(seed);
  model::Pose2 truth{10.0, 20.0, true_theta};
  const model::Twist twist{v, 0.01};  // radius 30 m at 0.3 m/s
  Outcome outcome{check.verdict(), -1.0};
  const int steps = static_cast<int>(seconds / 0.02);
  for (int step = 1; step <= steps; ++step) {
    truth = model::integrate_exact(truth, twist, 0.02);
    check.predict(twist.v + 0.05 * standard_normal(world), twist.omega + 0.02 * standard_normal(world), 0.02);
    if (step % 5 == 0) {
      outcome.verdict = check.add_fix(truth.x + fix_std * standard_normal(world),
                                      truth.y + fix_std * standard_normal(world), fix_std);
      if (outcome.verdict != Verdict::kPending && outcome.distance_m < 0.0) {
        outcome.distance_m = v * step * 0.02;
      }
    }
  }
  return outcome;
}

TEST(HeadingPriorCheck, ARightPriorIsConfirmedOnceTheRobotHasMovedAFewMetres) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Outcome outcome = drive(0.7, 0.7 + 0.1, 1.51, 0.3, 60.0, seed);
    EXPECT_EQ(outcome.verdict, Verdict::kConfirmed) << seed;
    EXPECT_LT(outcome.distance_m, 10.0) << seed;
  }
}

TEST(HeadingPriorCheck, APriorOff120DegIsContradictedNeverConfirmed) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    for (const double error : {2.0944, -2.0944, 1.2, kPi}) {  // 1.2 rad: beyond the tolerance by 3 of its sigmas
      const Outcome outcome = drive(0.7, 0.7 + error, 1.51, 0.3, 60.0, seed);
      EXPECT_EQ(outcome.verdict, Verdict::kContradicted) << seed << " " << error << " " << outcome.distance_m;
    }
  }
}

TEST(HeadingPriorCheck, WaitsWhileTheRobotStandsOrNoisierFixesNeedALongerWay) {
  EXPECT_EQ(drive(0.7, 0.7, 1.51, 0.0, 60.0, 3).verdict, Verdict::kPending);
  const Outcome noisy = drive(0.7, 0.7, 3.0 * 1.51, 0.3, 120.0, 3);
  EXPECT_EQ(noisy.verdict, Verdict::kConfirmed);
  EXPECT_GT(noisy.distance_m, drive(0.7, 0.7, 1.51, 0.3, 60.0, 3).distance_m);
}

TEST(HeadingPriorCheck, ToleranceZeroConfirmsAtOnceAndStopMeansNotNeeded) {
  HeadingPriorCheck check(0.0);
  EXPECT_EQ(check.verdict(), Verdict::kNotNeeded);
  check.start(1.0);
  EXPECT_EQ(check.verdict(), Verdict::kConfirmed);
  HeadingPriorCheck checked(0.5);
  checked.start(1.0);
  EXPECT_EQ(checked.verdict(), Verdict::kPending);
  checked.stop();
  EXPECT_EQ(checked.verdict(), Verdict::kNotNeeded);
}

}  // namespace
}  // namespace robodds::pf_estimator
