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
