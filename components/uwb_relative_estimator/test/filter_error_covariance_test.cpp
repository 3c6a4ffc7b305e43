// FilterErrorCovariance: the covariance of a filter's error when its measurements' errors are
// correlated in time (issue 27, the particle filters' reported covariance). Checked against a
// Monte Carlo of the same linear filter with Gauss-Markov range errors.
#include "components/uwb_relative_estimator/filter_error_covariance.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "common/model/uwb_array.hpp"
#include "common/random.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

constexpr double kEpochS = 0.1;

Eigen::Matrix3d diagonal(double a, double b, double c) { return Eigen::Vector3d(a, b, c).asDiagonal().toDenseMatrix(); }

double position_d2_of(const Eigen::Vector3d& e, const Eigen::Matrix3d& covariance) {
  return e.head<2>().dot(covariance.topLeftCorner<2, 2>().inverse() * e.head<2>());
}

UncertaintyParams times(double common_s, double link_s) {
  UncertaintyParams p;
  p.range_common_time_s = common_s;
  p.range_link_time_s = link_s;
  return p;
}

struct Case {
  UncertaintyParams params;
  double independent_std_m = 0.12;
  double common_std_m = 0.30;
  double odometry_xy_std_m = 0.005;
  double odometry_theta_std_rad = 0.005;
  Eigen::Matrix3d gain;  // of every update, as a particle filter with a tight cloud applies it
  int epochs = 300;
};

/// Runs the nominal relative-pose trajectory (robot i turning, j driving a curve) through
/// FilterErrorCovariance and `runs` Monte Carlo draws of the linear filter
/// eps <- (I - K)(F eps + w) + K (B u + a c), u and c first-order Gauss-Markov (exact
/// discretisation, stationary start). Returns {reported Sigma, sample covariance of eps} at the end.
std::pair<Eigen::Matrix3d, Eigen::Matrix3d> run(const Case& c, int runs, std::uint64_t seed) {
  const model::UwbArray array = model::square_array(0.5);
  const model::Pose2 own_increment{0.02, 0.0, 0.02};
  const model::Pose2 other_increment{0.02, 0.0, -0.01};
  std::vector<model::Pose2> poses{{4.0, 1.0, 0.3}};
  std::vector<RangeErrorMap> maps(1);
  EXPECT_TRUE(range_error_map(array, array, poses[0], c.independent_std_m, c.common_std_m, maps[0]));
  for (int t = 1; t <= c.epochs; ++t) {
    poses.push_back(model::compose(model::between(own_increment, poses.back()), other_increment));
    maps.emplace_back();
    EXPECT_TRUE(range_error_map(array, array, poses.back(), c.independent_std_m, c.common_std_m, maps.back()));
  }
  FilterErrorCovariance reported(c.params);
  reported.start(maps[0]);
  for (int t = 1; t <= c.epochs; ++t) {
    reported.predict(poses[t - 1], own_increment, other_increment, kEpochS, c.odometry_xy_std_m, c.odometry_theta_std_rad);
    reported.update(c.gain, maps[t]);
  }

  const double rho_u = std::exp(-kEpochS / c.params.range_link_time_s);
  const double rho_c = std::exp(-kEpochS / c.params.range_common_time_s);
  const Eigen::Index n = maps[0].independent_map.cols();
  RandomEngine random(seed);
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (int r = 0; r < runs; ++r) {
    Eigen::VectorXd u(n);
    for (Eigen::Index l = 0; l < n; ++l) u(l) = c.independent_std_m * standard_normal(random);
    double common = c.common_std_m * standard_normal(random);
    Eigen::Vector3d eps = maps[0].independent_map * u + maps[0].common_map * common;
    for (int t = 1; t <= c.epochs; ++t) {
      const Eigen::Matrix<double, 3, 9> j = relative_motion_jacobian(poses[t - 1], own_increment, other_increment);
      Eigen::Matrix<double, 6, 1> noise;
      for (int q = 0; q < 6; ++q) noise(q) = (q % 3 == 2 ? c.odometry_theta_std_rad : c.odometry_xy_std_m) * standard_normal(random);
      eps = j.leftCols<3>() * eps + j.middleCols<3>(3) * noise.head<3>() + j.rightCols<3>() * noise.tail<3>();
      for (Eigen::Index l = 0; l < n; ++l) {
        u(l) = rho_u * u(l) + std::sqrt(1.0 - rho_u * rho_u) * c.independent_std_m * standard_normal(random);
      }
      common = rho_c * common + std::sqrt(1.0 - rho_c * rho_c) * c.common_std_m * standard_normal(random);
      const Eigen::Vector3d e = maps[t].independent_map * u + maps[t].common_map * common;
      eps = (Eigen::Matrix3d::Identity() - c.gain) * eps + c.gain * e;
    }
    sum += eps * eps.transpose();  // the mean error is zero
  }
  return {reported.covariance(), sum / runs};
}

void expect_matches(const Eigen::Matrix3d& reported, const Eigen::Matrix3d& empirical, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(empirical(i, i) / reported(i, i), 1.0, tolerance) << "variance " << i << ": reported\n"
                                                                  << reported << "\nMonte Carlo\n" << empirical;
  }
  // The correlation of x and y (the error ellipse's orientation).
  const double reported_rho = reported(0, 1) / std::sqrt(reported(0, 0) * reported(1, 1));
  const double empirical_rho = empirical(0, 1) / std::sqrt(empirical(0, 0) * empirical(1, 1));
  EXPECT_NEAR(empirical_rho, reported_rho, 0.1);
}

// 2000 runs: sample variances scatter by sqrt(2 / 2000) ~ 3 %.
constexpr int kRuns = 2000;

TEST(FilterErrorCovariance, MatchesAMonteCarloOfTheFilterWithGaussMarkovRangeErrors) {
  Case c;
  c.params = times(10.0, 2.0);  // the UWB sensor's common mode and link bias
  c.gain = diagonal(0.03, 0.03, 0.05);
  const auto [reported, empirical] = run(c, kRuns, 1);
  expect_matches(reported, empirical, 0.12);
}

TEST(FilterErrorCovariance, MatchesTheMonteCarloWithAFullGainAndShortTimeConstants) {
  Case c;
  c.params = times(1.0, 0.3);
  c.gain = update_gain(diagonal(0.004, 0.002, 0.0005), diagonal(0.09, 0.05, 0.01)) ;
  c.gain(0, 1) = c.gain(1, 0) = 0.002;  // a cloud tilted against the axes
  const auto [reported, empirical] = run(c, kRuns, 2);
  expect_matches(reported, empirical, 0.12);
}

TEST(FilterErrorCovariance, ErrorsThatLastGainNothingFromAveraging) {
  // The particle filters' case: each epoch's measurement weighed as new while its error is the
  // same. With errors that never change and no odometry noise the filter's error is the
  // measurement's whatever the gain; with white errors the same gain averages ~65 epochs.
  const model::UwbArray array = model::square_array(0.5);
  const model::Pose2 pose{5.0, 0.0, 1.0};
  RangeErrorMap error;
  // With per-node biases too (they last as the common mode does).
  ASSERT_TRUE(range_error_map(array, array, pose, 0.12, 0.3, error, 0.08));
  FilterErrorCovariance lasting(times(1e9, 1e9));
  FilterErrorCovariance white(times(1e-9, 1e-9));
  lasting.start(error);
  white.start(error);
  const Eigen::Matrix3d gain = diagonal(0.03, 0.03, 0.03);
  for (int t = 0; t < 1000; ++t) {
    for (FilterErrorCovariance* f : {&lasting, &white}) {
      f->predict(pose, model::Pose2{}, model::Pose2{}, kEpochS, 0.0, 0.0);
      f->update(gain, error);
    }
  }
  const Eigen::Matrix3d measurement = error.covariance();
  EXPECT_TRUE(lasting.covariance().isApprox(measurement, 1e-6)) << lasting.covariance() << "\nvs\n" << measurement;
  // White: K / (2 - K) of the measurement's covariance.
  EXPECT_TRUE(white.covariance().isApprox(0.03 / 1.97 * measurement, 1e-6)) << white.covariance();
}

TEST(FilterErrorCovariance, StartsAtTheMeasurementsCovarianceAndDoesNothingBefore) {
  const model::UwbArray array = model::square_array(0.5);
  RangeErrorMap error;
  ASSERT_TRUE(range_error_map(array, array, model::Pose2{3.0, -2.0, 0.5}, 0.1, 0.3, error));
  FilterErrorCovariance f(UncertaintyParams{});
  f.predict(model::Pose2{3.0, -2.0, 0.5}, model::Pose2{0.1, 0.0, 0.1}, model::Pose2{}, kEpochS, 0.005, 0.005);
  f.update(diagonal(0.1, 0.1, 0.1), error);
  EXPECT_FALSE(f.started());
  EXPECT_TRUE(f.covariance().isZero());
  f.start(error);
  EXPECT_TRUE(f.started());
  EXPECT_TRUE(f.covariance().isApprox(range_fix_covariance(array, array, model::Pose2{3.0, -2.0, 0.5}, 0.1, 0.3), 1e-9));
  f.start(diagonal(0.09, 0.09, 0.01));
  EXPECT_TRUE(f.covariance().isApprox(diagonal(0.09, 0.09, 0.01)));
  f.update(diagonal(0.5, 0.5, 0.5), error);  // no cross-covariance with the ranges after this start
  EXPECT_TRUE(f.covariance().isApprox(0.25 * diagonal(0.09, 0.09, 0.01) + 0.25 * error.covariance(), 1e-9));
}

TEST(FilterErrorCovariance, UpdateGainIsPriorOverPriorPlusMeasurement) {
  const Eigen::Matrix3d k = update_gain(diagonal(0.01, 0.04, 0.001), diagonal(0.09, 0.04, 0.009));
  EXPECT_TRUE(k.isApprox(diagonal(0.1, 0.5, 0.1), 1e-12)) << k;
  EXPECT_TRUE(update_gain(Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()).isZero()) << "not positive definite: no gain";
}

TEST(FilterErrorCovariance, BadTimeConstantsNameTheKey) {
  try {
    FilterErrorCovariance f(times(10.0, 0.0));
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("range_link_time_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(FilterErrorCovariance(times(-1.0, 2.0)), std::invalid_argument);
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator

namespace robodds::uwb_relative_estimator {
namespace {

TEST(InnovationMonitor, AFilterThatFollowsItsFixesAddsLittleOneThatLostThemAddsTheDiscrepancy) {
  UncertaintyParams params;  // 50 fixes
  const Eigen::Matrix3d fix_covariance = diagonal(1.0, 0.25, 0.01);
  RandomEngine random(5);
  const auto fix_around = [&](const model::Pose2& p) {
    return model::Pose2{p.x + standard_normal(random), p.y + 0.5 * standard_normal(random),
                        p.theta + 0.1 * standard_normal(random)};
  };
  const model::Pose2 truth{5.0, 2.0, 0.3};
  InnovationMonitor following(params);
  InnovationMonitor lost(params);
  const model::Pose2 off{truth.x - 4.0, truth.y + 3.0, truth.theta};  // 5 m off
  double following_trace = 0.0;
  for (int t = 0; t < 500; ++t) {
    const model::Pose2 fix = fix_around(truth);
    following.add(truth, fix, fix_covariance);
    lost.add(off, fix, fix_covariance);
    following_trace += following.excess().trace();
  }
  EXPECT_LT(following_trace / 500, 0.05 * fix_covariance.trace()) << "a consistent filter: about nothing";
  const Eigen::Matrix3d excess = lost.excess();
  const Eigen::Vector3d e(off.x - truth.x, off.y - truth.y, 0.0);
  EXPECT_LT(position_d2_of(e, excess + fix_covariance), 2.0) << excess;  // the error is now within ~1.4 sigma
  lost.reset();
  EXPECT_TRUE(lost.excess().isZero()) << "no fixes since the restart";
  for (int t = 0; t < 9; ++t) lost.add(off, fix_around(truth), fix_covariance);
  EXPECT_TRUE(lost.excess().isZero()) << "fewer than a fifth of the window";
  lost.add(off, fix_around(truth), fix_covariance);
  EXPECT_FALSE(lost.excess().isZero());
}

TEST(InnovationMonitor, AnEstimateIndependentOfTheFixesIsExcusedByItsOwnCovarianceToo) {
  // The odometry stage's check: fixes 2 m off along x with a 0.1 m^2 variance; an estimate that
  // reports no spread of its own gets 4 - 0.1 added along x, one that reports 1 m^2 gets 2.9 less,
  // one that reports 10 m^2 gets nothing.
  InnovationMonitor monitor(UncertaintyParams{});
  for (int i = 0; i < 50; ++i) {
    monitor.add(model::Pose2{0.0, 0.0, 0.0}, model::Pose2{2.0, 0.0, 0.0}, diagonal(0.1, 0.1, 0.01));
  }
  EXPECT_NEAR(monitor.excess()(0, 0), 3.9, 1e-9);
  EXPECT_NEAR(monitor.excess(diagonal(1.0, 1.0, 0.01))(0, 0), 2.9, 1e-9);
  EXPECT_NEAR(monitor.excess(diagonal(10.0, 10.0, 0.01)).norm(), 0.0, 1e-9);
}

TEST(PositivePart, KeepsThePositiveEigenDirectionsOnly) {
  const Eigen::Matrix3d m = diagonal(2.0, -3.0, 0.5);
  EXPECT_TRUE(positive_part(m).isApprox(diagonal(2.0, 0.0, 0.5), 1e-12)) << positive_part(m);
  const Eigen::Vector3d v(1.0, 2.0, -1.0);
  EXPECT_TRUE(positive_part(v * v.transpose() - Eigen::Matrix3d::Identity()).isApprox(
      (v.squaredNorm() - 1.0) * v * v.transpose() / v.squaredNorm(), 1e-12));
}

TEST(InnovationMonitor, ADriftIsCarriedToTheNewestFixAlongItsTrend) {
  // A dead reckoning drifting 0.02 m per fix away from fixes of 0.01 m^2: after 50 fixes it is
  // 0.98 m off. The window's median innovation is the drift of half a window ago (~0.49 m);
  // carried along the trend it is the newest one. A constant offset has no trend: the same as excess().
  const Eigen::Matrix3d fix_covariance = diagonal(0.01, 0.01, 0.0001);
  InnovationMonitor drifting(UncertaintyParams{});  // 50 fixes
  InnovationMonitor constant(UncertaintyParams{});
  for (int i = 0; i < 50; ++i) {
    drifting.add(model::Pose2{0.0, 0.0, 0.0}, model::Pose2{0.02 * i, 0.0, 0.0}, fix_covariance);
    constant.add(model::Pose2{0.0, 0.0, 0.0}, model::Pose2{0.5, 0.0, 0.0}, fix_covariance);
  }
  const double newest_m = 0.98;
  EXPECT_NEAR(std::sqrt(drifting.drifting_excess(Eigen::Matrix3d::Zero())(0, 0) + 0.01), newest_m, 0.03);
  EXPECT_LT(std::sqrt(drifting.excess()(0, 0) + 0.01), 0.6 * newest_m) << "the window's median lags";
  EXPECT_NEAR(constant.drifting_excess(Eigen::Matrix3d::Zero())(0, 0), constant.excess()(0, 0), 1e-12);
  EXPECT_TRUE(InnovationMonitor(UncertaintyParams{}).drifting_excess(Eigen::Matrix3d::Zero()).isZero()) << "no fixes";
}

TEST(InnovationMonitor, LostIsCalledAtOnceWhenFarOffAfterAWhileWhenModeratelyOffNeverWhenFollowing) {
  UncertaintyParams params;  // 50 fixes; d^2 > 16.27 at once, mean d^2 > 4 over 200 tests
  const Eigen::Matrix3d fix_covariance = diagonal(1.0, 1.0, 0.01);
  RandomEngine random(9);
  const model::Pose2 truth{5.0, 2.0, 0.3};
  const auto fix_around = [&](const model::Pose2& p) {
    return model::Pose2{p.x + standard_normal(random), p.y + standard_normal(random), p.theta + 0.1 * standard_normal(random)};
  };
  const Eigen::Matrix3d filter_covariance = diagonal(0.25, 0.25, 0.0025);
  Eigen::Vector3d correction;
  Eigen::Matrix3d typical;
  // Following its fixes: never lost in 5000 epochs.
  InnovationMonitor following(params);
  int false_alarms = 0;
  for (int t = 0; t < 5000; ++t) {
    following.add(truth, fix_around(truth), fix_covariance);
    false_alarms += following.lost(filter_covariance, correction, typical) ? 1 : 0;
  }
  EXPECT_EQ(false_alarms, 0);
  // 6 m off: lost as soon as there are enough fixes; the correction brings it back to the truth.
  InnovationMonitor far(params);
  const model::Pose2 far_off{truth.x + 6.0, truth.y, truth.theta};
  int epochs = 0;
  bool lost = false;
  while (!lost && epochs < 100) {
    ++epochs;
    // Every fifth fix with an outlier's huge covariance: the typical fix's covariance is used.
    far.add(far_off, fix_around(truth), epochs % 5 == 0 ? Eigen::Matrix3d(100.0 * fix_covariance) : fix_covariance);
    lost = far.lost(filter_covariance, correction, typical);
  }
  EXPECT_TRUE(lost);
  EXPECT_EQ(epochs, 10) << "the first test with a fifth of the window";
  EXPECT_NEAR(far_off.x + correction.x(), truth.x, 0.8);
  EXPECT_NEAR(far_off.y + correction.y(), truth.y, 0.8);
  EXPECT_TRUE(typical.isApprox(fix_covariance)) << typical;
  // Fixes whose covariance is mostly errors the filter shares (a common mode, node biases: the
  // same ranges reach both, they cancel in fix - estimate): tested against the fixes' own part.
  InnovationMonitor shared(params);
  InnovationMonitor whole(params);
  const Eigen::Matrix3d lasting = 25.0 * fix_covariance;  // 5 m sigmas the filter shares
  bool shared_lost = false;
  bool whole_lost = false;
  for (int t = 0; t < 10; ++t) {
    const model::Pose2 fix = fix_around(truth);
    shared.add(far_off, fix, lasting, fix_covariance);
    whole.add(far_off, fix, lasting);
    shared_lost = shared.lost(filter_covariance, correction, typical);
    whole_lost = whole.lost(filter_covariance, correction, typical);
  }
  EXPECT_TRUE(shared_lost) << "6 m off against 1 m own fix errors";
  EXPECT_FALSE(whole_lost) << "6 m off against 5 m whole fix errors: within them";
  // 2.7 m off (d^2 ~ 5.8 < 16.27 at each test, 3 sigma over all): lost only after it persists.
  InnovationMonitor moderate(params);
  const model::Pose2 moderately_off{truth.x + 2.7, truth.y, truth.theta};
  epochs = 0;
  lost = false;
  while (!lost && epochs < 1000) {
    ++epochs;
    moderate.add(moderately_off, fix_around(truth), fix_covariance);
    lost = moderate.lost(filter_covariance, correction, typical);
  }
  EXPECT_TRUE(lost);
  EXPECT_GE(epochs, 10 + 100 - 1) << "not before half the mean's window of tests";
  EXPECT_LE(epochs, 10 + 200);
  moderate.reset();
  EXPECT_FALSE(moderate.lost(filter_covariance, correction, typical)) << "no fixes since the restart";
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
