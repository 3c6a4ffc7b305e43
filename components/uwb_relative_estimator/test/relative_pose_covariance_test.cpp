#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "common/angle.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "components/uwb_relative_estimator/test/true_ranges.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

using testing::true_ranges;

/// Sample covariance of error vectors (mean removed).
Eigen::Matrix3d sample_covariance(const std::vector<Eigen::Vector3d>& errors) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& e : errors) mean += e;
  mean /= static_cast<double>(errors.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& e : errors) cov += (e - mean) * (e - mean).transpose();
  return cov / static_cast<double>(errors.size() - 1);
}

/// Mean normalised estimation error squared as the evaluator judges an estimate
/// (sim/evaluator/consistency.hpp): x-y against the reported x-y block (2 for a consistent one)
/// and theta against the reported theta variance (1).
Eigen::Vector2d mean_nees(const std::vector<Eigen::Vector3d>& errors, const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix2d information = covariance.topLeftCorner<2, 2>().inverse();
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& e : errors) {
    sum.x() += e.head<2>().dot(information * e.head<2>());
    sum.y() += e.z() * e.z() / covariance(2, 2);
  }
  return sum / static_cast<double>(errors.size());
}

void expect_consistent(const std::vector<Eigen::Vector3d>& errors, const Eigen::Matrix3d& covariance) {
  const Eigen::Vector2d nees = mean_nees(errors, covariance);
  EXPECT_NEAR(nees.x(), 2.0, 2.0 * 0.15) << "position";
  EXPECT_NEAR(nees.y(), 1.0, 0.15) << "heading";
}

// 2000 draws: the sample variances scatter by sqrt(2 / 2000) ~ 3 %; the linearisation adds a few %.
constexpr int kDraws = 2000;
constexpr double kTolerance = 0.15;

void expect_matches(const Eigen::Matrix3d& empirical, const Eigen::Matrix3d& reported) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(empirical(i, i) / reported(i, i), 1.0, kTolerance) << "variance " << i << ": empirical\n"
                                                                   << empirical << "\nreported\n" << reported;
  }
  // Correlations agree too (the common mode makes x and y strongly correlated along the bearing).
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      const double empirical_corr = empirical(i, j) / std::sqrt(empirical(i, i) * empirical(j, j));
      const double reported_corr = reported(i, j) / std::sqrt(reported(i, i) * reported(j, j));
      EXPECT_NEAR(empirical_corr, reported_corr, 0.1) << "correlation " << i << ", " << j;
    }
  }
}

TEST(RangeFixCovariance, MatchesTheSpreadOfLeastSquaresFitsOverManyNoiseDraws) {
  const UwbArray array = square_array(0.5);
  const model::Pose2 truth{4.0, 2.0, 0.7};
  SolverOptions plain;
  plain.loss = RobustLoss::kNone;
  // Without a common mode the radial error is tiny (std_i / 4) and the tangential one large; at
  // 0.1 m the curvature of the tangential error (t^2 / 2R) already exceeds the radial std and the
  // linearisation no longer holds: 0.03 m keeps the test about the covariance, not the banana.
  for (const auto& [independent_std, common_std] : {std::pair{0.03, 0.0}, std::pair{0.1, 0.3}}) {
    RandomEngine engine(7);
    std::vector<Eigen::Vector3d> errors;
    for (int draw = 0; draw < kDraws; ++draw) {
      Eigen::MatrixXd ranges = true_ranges(array, array, truth);
      const double common = common_std * standard_normal(engine);
      for (Eigen::Index i = 0; i < ranges.size(); ++i) {
        ranges(i) += independent_std * standard_normal(engine) + common;
      }
      const SolverResult fit = solve_relative_pose(array, array, ranges, truth, plain);
      ASSERT_TRUE(fit.converged);
      errors.emplace_back(fit.pose.x - truth.x, fit.pose.y - truth.y, wrap_angle(fit.pose.theta - truth.theta));
    }
    SCOPED_TRACE("common std " + std::to_string(common_std));
    const Eigen::Matrix3d reported = range_fix_covariance(array, array, truth, independent_std, common_std);
    expect_matches(sample_covariance(errors), reported);
    expect_consistent(errors, reported);
  }
}

TEST(RangeErrorMap, PerNodeBiasesThatTheFitAbsorbsAreCoveredByTheNodeTerm) {
  // Issue 27, experiment 1-b: a board in view biases every link of the nodes behind it. A node's
  // bias looks like the node moved, so the fit turns it into heading and bearing and leaves little
  // in the residuals. Ranges with a bias per node (std 0.08 m, own and peer nodes) and 0.02 m
  // white noise: the map with node_bias_std_m covers the fits' errors; without it the heading is
  // far outside what it reports.
  const UwbArray array = square_array(0.5);
  const model::Pose2 truth{4.0, 2.0, 0.7};
  SolverOptions plain;
  plain.loss = RobustLoss::kNone;
  constexpr double kWhite = 0.02;
  constexpr double kNode = 0.08;
  RandomEngine engine(11);
  std::vector<Eigen::Vector3d> errors;
  for (int draw = 0; draw < kDraws; ++draw) {
    Eigen::MatrixXd ranges = true_ranges(array, array, truth);
    Eigen::VectorXd own(4);
    Eigen::VectorXd peer(4);
    for (int n = 0; n < 4; ++n) {
      own(n) = kNode * standard_normal(engine);
      peer(n) = kNode * standard_normal(engine);
    }
    for (Eigen::Index k = 0; k < 4; ++k) {
      for (Eigen::Index l = 0; l < 4; ++l) {
        ranges(k, l) += own(k) + peer(l) + kWhite * standard_normal(engine);
      }
    }
    const SolverResult fit = solve_relative_pose(array, array, ranges, truth, plain);
    ASSERT_TRUE(fit.converged);
    errors.emplace_back(fit.pose.x - truth.x, fit.pose.y - truth.y, wrap_angle(fit.pose.theta - truth.theta));
  }
  // The node biases' means over each array are a common mode of std kNode sqrt(2 / 4).
  const double common = kNode * std::sqrt(0.5);
  RangeErrorMap with_nodes;
  ASSERT_TRUE(range_error_map(array, array, truth, kWhite, common, with_nodes, kNode));
  EXPECT_EQ(with_nodes.node_map.cols(), 8);
  expect_matches(sample_covariance(errors), with_nodes.covariance());
  // The bearing's spread bends the fits towards this robot (the mean radial offset R phi^2 / 2):
  // the reported covariance carries that term too (with_bearing_curvature).
  expect_consistent(errors, with_bearing_curvature(with_nodes.covariance(), truth));
  RangeErrorMap without;
  ASSERT_TRUE(range_error_map(array, array, truth, kWhite, common, without));
  EXPECT_GT(mean_nees(errors, without.covariance()).y(), 5.0) << "without the node term the heading is over-confident";
}

TEST(RangeFixCovariance, IsNotFiniteWhenTheGeometryDeterminesNoPose) {
  UwbArray single;
  single.nodes_m = {Eigen::Vector2d::Zero()};
  // One range between two single nodes: one equation, three unknowns.
  EXPECT_FALSE(range_fix_covariance(single, single, model::Pose2{3.0, 0.0, 0.0}, 0.1, 0.3).allFinite());
}

TEST(ResidualStd, TheRobustOneEstimatesTheRangeNoiseAndIgnoresAnOutlierThePlainOneSeesIt) {
  const UwbArray array = square_array(0.5);
  const model::Pose2 truth{-3.0, 4.0, 2.0};
  SolverOptions plain;
  plain.loss = RobustLoss::kNone;
  RandomEngine engine(11);
  UncertaintyParams params;
  params.range_std_floor_m = 0.01;
  params.noise_window_epochs = 1000;
  RangeNoiseLevel level(params);
  RangeNoiseLevel with_outliers(params);
  double plain_std_sum = 0.0;
  for (int draw = 0; draw < 400; ++draw) {
    Eigen::MatrixXd ranges = true_ranges(array, array, truth);
    for (Eigen::Index i = 0; i < ranges.size(); ++i) {
      ranges(i) += 0.1 * standard_normal(engine);
    }
    level.add(robust_residual_std_m(array, array, ranges, solve_relative_pose(array, array, ranges, truth, plain).pose));
    ranges(3) += 1.5;  // a non-line-of-sight excess on one range of every epoch
    const model::Pose2 pulled = solve_relative_pose(array, array, ranges, truth, plain).pose;
    with_outliers.add(robust_residual_std_m(array, array, ranges, pulled));
    plain_std_sum += residual_rms_std_m(array, array, ranges, pulled);
  }
  // The plain std sees the outlier that pulled the fit (what this epoch's covariance must show).
  EXPECT_GT(plain_std_sum / 400.0, 0.3);
  EXPECT_NEAR(level.std_m(), 0.1, 0.01);
  // A 15-sigma outlier on one of 16 ranges: the residuals' plain RMS would say ~0.4 m; the median
  // moves by < 2x (plain least squares spreads the outlier over the other residuals).
  EXPECT_LT(with_outliers.std_m(), 0.2);
}

TEST(RangeNoiseLevel, IsTheRunningMedianAboveTheFloor) {
  UncertaintyParams params;
  params.range_std_floor_m = 0.05;
  params.noise_window_epochs = 3;
  RangeNoiseLevel level(params);
  EXPECT_DOUBLE_EQ(level.std_m(), 0.05);  // nothing seen yet: the floor
  level.add(0.02);
  EXPECT_DOUBLE_EQ(level.std_m(), 0.05);  // below the floor
  level.add(0.2);
  level.add(0.1);
  EXPECT_DOUBLE_EQ(level.std_m(), 0.1);
  level.add(5.0);  // the window keeps 0.2, 0.1, 5: one spike does not move the median much
  EXPECT_DOUBLE_EQ(level.std_m(), 0.2);
  params.noise_window_epochs = 0;
  EXPECT_THROW(RangeNoiseLevel{params}, std::invalid_argument);
}

TEST(PropagateRelativeCovariance, MatchesTheSpreadOfNoisyDeadReckoning) {
  const model::Pose2 start{3.0, 1.0, 0.4};
  const model::Pose2 own_step{0.02, 0.0, 0.03};     // robot i turns left while driving
  const model::Pose2 other_step{0.02, 0.001, -0.02};
  const double xy_std = 0.005;
  const double theta_std = 0.005;
  constexpr int kEpochs = 100;
  Eigen::Matrix3d reported = Eigen::Matrix3d::Zero();
  model::Pose2 nominal = start;
  for (int e = 0; e < kEpochs; ++e) {
    reported = propagate_relative_covariance(reported, nominal, own_step, other_step, xy_std, theta_std);
    nominal = model::compose(model::between(own_step, nominal), other_step);
  }
  RandomEngine engine(3);
  const auto noisy = [&](const model::Pose2& step) {
    return model::Pose2{step.x + xy_std * standard_normal(engine), step.y + xy_std * standard_normal(engine),
                        step.theta + theta_std * standard_normal(engine)};
  };
  std::vector<Eigen::Vector3d> errors;
  for (int draw = 0; draw < kDraws; ++draw) {
    model::Pose2 x = start;
    for (int e = 0; e < kEpochs; ++e) {
      x = model::compose(model::between(noisy(own_step), x), noisy(other_step));
    }
    errors.emplace_back(x.x - nominal.x, x.y - nominal.y, wrap_angle(x.theta - nominal.theta));
  }
  expect_matches(sample_covariance(errors), reported);
  expect_consistent(errors, reported);
  // Known start, one epoch: only the increments' noise, both robots' (2 x 0.005^2 on theta).
  const Eigen::Matrix3d one = propagate_relative_covariance(Eigen::Matrix3d::Zero(), start, own_step, other_step, xy_std, theta_std);
  EXPECT_NEAR(one(2, 2), 2.0 * theta_std * theta_std, 1e-12);
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator

namespace robodds::uwb_relative_estimator {
namespace {

using testing::true_ranges;

/// x-y Mahalanobis distance squared of `e` against `covariance`.
double position_d2(const Eigen::Vector3d& e, const Eigen::Matrix3d& covariance) {
  return e.head<2>().dot(covariance.topLeftCorner<2, 2>().inverse() * e.head<2>());
}

TEST(RangeErrorVariances, AnOutlierGetsItsLeaveOneOutResidualAndTheFitItMovedIsCovered) {
  const UwbArray array = square_array(0.5);
  const model::Pose2 truth{4.0, 1.0, 0.4};
  SolverOptions plain;
  plain.loss = RobustLoss::kNone;
  Eigen::MatrixXd ranges = true_ranges(array, array, truth);
  ranges(1, 2) += 0.5;  // one non-line-of-sight range, the others exact
  const SolverResult fit = solve_relative_pose(array, array, ranges, truth, plain);
  ASSERT_TRUE(fit.converged);
  const double noise = 0.05;
  const Eigen::VectorXd variances = range_error_variances(array, array, ranges, fit.pose, noise, noise, 3.0);
  ASSERT_EQ(variances.size(), 16);
  // The outlier's own error, recovered by r / (1 - h); the ranges it pulled the fit away from get
  // leave-one-out residuals beyond 3 sigma too (a fraction of it), never more than the outlier.
  EXPECT_NEAR(std::sqrt(variances(1 * 4 + 2)), 0.5, 0.05);
  for (Eigen::Index k = 0; k < 16; ++k) {
    if (k != 1 * 4 + 2) {
      EXPECT_LT(variances(k), 0.25 * variances(1 * 4 + 2)) << k;
      EXPECT_GE(variances(k), noise * noise) << k;
    }
  }
  RangeErrorMap error;
  ASSERT_TRUE(range_error_map(array, array, fit.pose, noise, 0.0, error));
  const Eigen::Vector3d e(fit.pose.x - truth.x, fit.pose.y - truth.y, wrap_angle(fit.pose.theta - truth.theta));
  EXPECT_GT(position_d2(e, error.covariance()), 11.829) << "the noise level alone: far outside 3 sigma";
  error.independent_variance_m2 = variances;
  std::printf("outlier +0.5 m: fit error %.3f %.3f %.3f, d^2 %.2f; the outlier's column of B: %.3f %.3f %.3f\n", e.x(), e.y(), e.z(),
              position_d2(e, error.covariance()), error.independent_map(0, 6), error.independent_map(1, 6), error.independent_map(2, 6));
  // Inside 3 sigma (the fit is not quite linear in a 0.5 m outlier: ~2 sigma, not 1).
  EXPECT_LT(position_d2(e, error.covariance()), 11.829) << "with the outlier's variance";
  EXPECT_LT(e.z() * e.z(), 9.0 * error.covariance()(2, 2));
  // Noise alone (every residual within 3 sigma) changes nothing.
  const Eigen::VectorXd clean =
      range_error_variances(array, array, true_ranges(array, array, truth), truth, noise, noise, 3.0);
  EXPECT_TRUE(clean.isApprox(Eigen::VectorXd::Constant(16, noise * noise)));
}

TEST(WithBearingCurvature, SmallArraysPutThePeerOnAnArcThatTheLinearisedEllipseMisses) {
  // Side 0.25 m at 5 m, range noise 0.15 m: the bearing sigma is ~0.3 rad and the fits lie on a
  // banana bent towards this robot. Linearised: the radial 3 sigma (common mode 0) is a few cm.
  const UwbArray array = square_array(0.25);
  const model::Pose2 truth{5.0, 0.0, 0.0};
  SolverOptions plain;
  plain.loss = RobustLoss::kNone;
  RandomEngine engine(3);
  const double noise = 0.15;
  const Eigen::Matrix3d linear = range_fix_covariance(array, array, truth, noise, 0.0);
  const Eigen::Matrix3d curved = with_bearing_curvature(linear, truth);
  int outside_linear = 0;
  int outside_curved = 0;
  int draws = 0;
  for (int draw = 0; draw < 1000; ++draw) {
    Eigen::MatrixXd ranges = true_ranges(array, array, truth);
    for (Eigen::Index i = 0; i < ranges.size(); ++i) {
      ranges(i) += noise * standard_normal(engine);
    }
    const SolverResult fit = solve_relative_pose(array, array, ranges, truth, plain);
    if (!fit.converged) {
      continue;
    }
    ++draws;
    const Eigen::Vector3d e(fit.pose.x - truth.x, fit.pose.y - truth.y, 0.0);
    outside_linear += position_d2(e, linear) > 11.829;
    outside_curved += position_d2(e, curved) > 11.829;
  }
  ASSERT_GT(draws, 900);
  std::printf("side 0.25 m at 5 m, noise 0.15 m: outside 3 sigma linearised %.1f %%, with the curvature %.1f %%\n",
              100.0 * outside_linear / draws, 100.0 * outside_curved / draws);
  EXPECT_GT(outside_linear, draws / 50) << "the linearised ellipse misses the arc";
  EXPECT_LT(outside_curved, draws / 20) << "the rest: the heading-bearing coupling of so poor a fit";
  EXPECT_LT(5 * outside_curved, outside_linear);
  // The tangential and heading variances stay; a well-known bearing gains nothing measurable.
  EXPECT_DOUBLE_EQ(curved(2, 2), linear(2, 2));
  const Eigen::Matrix3d tight = range_fix_covariance(square_array(0.5), square_array(0.5), truth, 0.05, 0.3);
  EXPECT_LT((with_bearing_curvature(tight, truth) - tight).norm(), 0.002 * tight.norm());
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
