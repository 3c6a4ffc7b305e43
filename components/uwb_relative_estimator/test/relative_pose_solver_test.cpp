#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "components/uwb_relative_estimator/test/true_ranges.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/random.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

using testing::true_ranges;

double position_error(const model::Pose2& a, const model::Pose2& b) { return std::hypot(a.x - b.x, a.y - b.y); }
double heading_error(const model::Pose2& a, const model::Pose2& b) { return std::abs(wrap_angle(a.theta - b.theta)); }

TEST(PredictedRange, IsTheDistanceOfTheTransformedNodes) {
  // j at (3, 4) turned by 90 deg: its node (1, 0) sits at (3, 5) in i's frame.
  EXPECT_DOUBLE_EQ(predicted_range(model::Pose2{3.0, 4.0, kPi / 2.0}, Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.0)),
                   std::hypot(3.0, 5.0));
}

TEST(SolveRelativePose, RecoversAnyPoseFromNoiseFreeRangesWithoutAGuess) {
  const UwbArray array = square_array(0.5);
  for (const model::Pose2 truth : {model::Pose2{5.0, 0.0, 0.0}, model::Pose2{-3.0, 4.0, 2.5}, model::Pose2{0.5, -8.0, -1.2},
                                   model::Pose2{-6.0, -6.0, kPi}}) {
    const SolverResult r = solve_relative_pose(array, array, true_ranges(array, array, truth), std::nullopt, SolverOptions{});
    EXPECT_LT(position_error(r.pose, truth), 1e-6) << truth.x << ", " << truth.y;
    EXPECT_LT(heading_error(r.pose, truth), 1e-6) << truth.theta;
    EXPECT_EQ(r.starts, 32);
    EXPECT_TRUE(r.converged);
  }
}

TEST(SolveRelativePose, AWarmStartNeedsOneSolve) {
  const UwbArray array = square_array(0.3);
  const model::Pose2 truth{2.0, 1.0, 0.4};
  const SolverResult r = solve_relative_pose(array, array, true_ranges(array, array, truth), model::Pose2{1.8, 1.2, 0.3}, SolverOptions{});
  EXPECT_EQ(r.starts, 1);
  EXPECT_LT(position_error(r.pose, truth), 1e-6);
}

struct Rmse {
  double position_m = 0.0;
  double heading_rad = 0.0;
};

/// Monte Carlo of single-epoch solves at 5 m with white range noise `sigma_m`, a fraction
/// `outliers` of the ranges biased by +2 m (non-line-of-sight), for a given loss.
Rmse monte_carlo(double side_m, double sigma_m, double outliers, RobustLoss loss, int trials) {
  const UwbArray array = square_array(side_m);
  RandomEngine engine(derive_seed(5, "uwb_monte_carlo"));
  SolverOptions options;
  options.loss = loss;
  double sum_p = 0.0;
  double sum_h = 0.0;
  for (int t = 0; t < trials; ++t) {
    const double bearing = 2.0 * kPi * uniform01(engine);
    const model::Pose2 truth{5.0 * std::cos(bearing), 5.0 * std::sin(bearing), kPi - 2.0 * kPi * uniform01(engine)};
    Eigen::MatrixXd ranges = true_ranges(array, array, truth);
    for (Eigen::Index i = 0; i < ranges.size(); ++i) {
      ranges(i) += sigma_m * standard_normal(engine) + (uniform01(engine) < outliers ? 2.0 : 0.0);
    }
    const SolverResult r = solve_relative_pose(array, array, ranges, truth, options);  // warm start: the error, not the search
    sum_p += std::pow(position_error(r.pose, truth), 2);
    sum_h += std::pow(heading_error(r.pose, truth), 2);
  }
  return {std::sqrt(sum_p / trials), std::sqrt(sum_h / trials)};
}

TEST(SolveRelativePose, ErrorsShrinkAsTheArrayGrows) {
  // NOTES.md: single-epoch errors scale as sigma / side. 0.7 m against 0.3 m: ~2.3x smaller.
  const Rmse small = monte_carlo(0.3, 0.05, 0.0, RobustLoss::kNone, 200);
  const Rmse large = monte_carlo(0.7, 0.05, 0.0, RobustLoss::kNone, 200);
  std::printf("sigma 0.05 m at 5 m: side 0.3 m: %.3f m / %.2f deg; side 0.7 m: %.3f m / %.2f deg\n", small.position_m,
              small.heading_rad * 180.0 / kPi, large.position_m, large.heading_rad * 180.0 / kPi);
  EXPECT_GT(small.position_m / large.position_m, 1.6);
  EXPECT_LT(small.position_m / large.position_m, 3.5);
  EXPECT_GT(small.heading_rad / large.heading_rad, 1.6);
  EXPECT_LT(small.heading_rad / large.heading_rad, 3.5);
}

TEST(SolveRelativePose, RobustLossResistsNonLineOfSightOutliers) {
  // NOTES.md: 2 % outliers took plain LM from 0.32 to 0.46 m; a robust loss kept 0.32 m.
  const Rmse clean = monte_carlo(0.5, 0.05, 0.0, RobustLoss::kNone, 300);
  const Rmse plain = monte_carlo(0.5, 0.05, 0.02, RobustLoss::kNone, 300);
  const Rmse huber = monte_carlo(0.5, 0.05, 0.02, RobustLoss::kHuber, 300);
  std::printf("2 %% outliers of +2 m: clean %.3f m, plain %.3f m, huber %.3f m\n", clean.position_m, plain.position_m,
              huber.position_m);
  EXPECT_GT(plain.position_m, 1.2 * clean.position_m);
  EXPECT_LT(huber.position_m, 0.8 * plain.position_m);
}

TEST(SolveRelativePose, ALabelShiftedByOneTurnsTheHeadingBy90DegreesUnnoticed) {
  // NOTES.md: a node-label mismatch gives a silent 90/180 deg heading offset.
  const UwbArray array = square_array(0.5);
  const model::Pose2 truth{4.0, 1.0, 0.3};
  const Eigen::MatrixXd ranges = true_ranges(array, array, truth);
  UwbArray mislabelled = array;
  for (std::size_t l = 0; l < 4; ++l) {
    mislabelled.nodes_m[l] = array.nodes_m[(l + 1) % 4];
  }
  const SolverResult r = solve_relative_pose(array, mislabelled, ranges, std::nullopt, SolverOptions{});
  EXPECT_LT(r.final_cost, 1e-12);  // a perfect fit: nothing in the cost reveals the mistake
  EXPECT_LT(position_error(r.pose, truth), 1e-6);
  EXPECT_NEAR(std::abs(wrap_angle(r.pose.theta - truth.theta)), kPi / 2.0, 1e-6);
}

TEST(SolveRelativePose, BadInputNamesWhatIsWrong) {
  const UwbArray array = square_array(0.5);
  Eigen::MatrixXd ranges = true_ranges(array, array, model::Pose2{3.0, 0.0, 0.0});
  ranges(2, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    solve_relative_pose(array, array, ranges, std::nullopt, SolverOptions{});
    FAIL() << "accepted a NaN range";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "solve_relative_pose: range (2, 1): must be >= 0 and finite (got nan)");
  }
  EXPECT_THROW(solve_relative_pose(array, array, Eigen::MatrixXd::Ones(3, 4), std::nullopt, SolverOptions{}), std::invalid_argument);
  ranges(2, 1) = -1.0;
  EXPECT_THROW(solve_relative_pose(array, array, ranges, std::nullopt, SolverOptions{}), std::invalid_argument);
  SolverOptions bad;
  bad.loss_scale_m = 0.0;
  ranges(2, 1) = 3.0;
  EXPECT_THROW(solve_relative_pose(array, array, ranges, std::nullopt, bad), std::invalid_argument);
  try {
    solve_relative_pose(array, array, ranges, model::Pose2{std::numeric_limits<double>::infinity(), 0.0, 0.0}, SolverOptions{});
    FAIL() << "accepted a non-finite initial pose";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "solve_relative_pose: initial pose is not finite (got x=inf, y=0, theta=0)");
  }
  EXPECT_EQ(robust_loss_from_string("soft_l1"), RobustLoss::kSoftL1);
  EXPECT_THROW(robust_loss_from_string("cauchy"), std::invalid_argument);
}

TEST(SolverParamTable, LossNamesRoundTripAndEveryOptionIsDocumented) {
  for (const RobustLoss loss : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kSoftL1}) {
    EXPECT_EQ(robust_loss_from_string(to_string(loss)), loss);
  }
  const params::ParamDoc doc = solver_param_table().doc();
  ASSERT_EQ(doc.params.size(), 5u);
  EXPECT_EQ(doc.params[0].key, "loss");
  EXPECT_EQ(doc.params[0].default_yaml, "huber");
  EXPECT_EQ(doc.params[0].range, "none | huber | soft_l1");
  EXPECT_EQ(doc.params[2].range, ">= 1");
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
