#include "components/odometry_sensor/odometry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::odometry_sensor {
namespace {

constexpr int kSamples = 100000;
constexpr double kWheelBaseM = 0.5;  // m, the robot body of these readings

/// Sample moments of the reading error (reading - truth) over many readings of one twist.
struct ErrorMoments {
  double mean_v = 0.0;
  double mean_omega = 0.0;
  double var_v = 0.0;
  double var_omega = 0.0;
  double correlation = 0.0;
};

ErrorMoments error_moments(const model::Twist& truth, const OdometryParams& params,
                           RandomEngine& engine, int samples) {
  double sum_v = 0.0, sum_w = 0.0, sum_vv = 0.0, sum_ww = 0.0, sum_vw = 0.0;
  for (int i = 0; i < samples; ++i) {
    const OdometryReading reading = measure_odometry(truth, 0.02, kWheelBaseM, params, engine);
    const double ev = reading.v - truth.v;
    const double ew = reading.omega - truth.omega;
    sum_v += ev;
    sum_w += ew;
    sum_vv += ev * ev;
    sum_ww += ew * ew;
    sum_vw += ev * ew;
  }
  ErrorMoments m;
  m.mean_v = sum_v / samples;
  m.mean_omega = sum_w / samples;
  m.var_v = sum_vv / samples - m.mean_v * m.mean_v;
  m.var_omega = sum_ww / samples - m.mean_omega * m.mean_omega;
  m.correlation = (sum_vw / samples - m.mean_v * m.mean_omega) / std::sqrt(m.var_v * m.var_omega);
  return m;
}

OdometryParams noiseless() {
  OdometryParams params;
  params.wheel_speed_noise_std_mps = 0.0;
  return params;
}

TEST(OdometryModel, ClaimedVariancesFollowFromWheelNoise) {
  OdometryParams params;
  params.wheel_speed_noise_std_mps = 0.04;
  RandomEngine engine(1);
  const OdometryReading reading = measure_odometry(model::Twist{1.0, 0.5}, 0.02, 0.4, params, engine);
  EXPECT_DOUBLE_EQ(reading.var_v, 0.04 * 0.04 / 2.0);
  EXPECT_DOUBLE_EQ(reading.var_omega, 2.0 * 0.04 * 0.04 / (0.4 * 0.4));
  EXPECT_EQ(reading.dt_s, 0.02);
}

TEST(OdometryModel, EmpiricalNoiseMatchesClaimedVariancesWithZeroMean) {
  OdometryParams params;
  params.wheel_speed_noise_std_mps = 0.05;
  RandomEngine engine(derive_seed(1, "odometry_sensor/statistics"));
  const model::Twist truth{0.8, -0.6};
  const ErrorMoments m = error_moments(truth, params, engine, kSamples);

  RandomEngine claim_engine(0);
  const OdometryReading claim = measure_odometry(truth, 0.02, kWheelBaseM, params, claim_engine);
  // Tolerances: 5 standard errors. Mean: sigma/sqrt(n). Variance: var*sqrt(2/n).
  // Correlation: 1/sqrt(n) (the v and omega errors of independent wheels are uncorrelated).
  const double n = kSamples;
  EXPECT_NEAR(m.mean_v, 0.0, 5.0 * std::sqrt(claim.var_v / n));
  EXPECT_NEAR(m.mean_omega, 0.0, 5.0 * std::sqrt(claim.var_omega / n));
  EXPECT_NEAR(m.var_v, claim.var_v, 5.0 * claim.var_v * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.var_omega, claim.var_omega, 5.0 * claim.var_omega * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.correlation, 0.0, 5.0 / std::sqrt(n));
}

TEST(OdometryModel, ZeroNoiseAndSlipGiveTruth) {
  const OdometryParams params = noiseless();
  RandomEngine engine(derive_seed(2, "odometry_sensor/zero_noise"));
  for (const model::Twist truth : {model::Twist{0.0, 0.0}, model::Twist{1.0, 0.0},
                                   model::Twist{0.0, -1.0}, model::Twist{0.37, 0.91}}) {
    const OdometryReading reading = measure_odometry(truth, 0.02, kWheelBaseM, params, engine);
    // Exact up to the rounding of the wheel-speed round trip.
    EXPECT_NEAR(reading.v, truth.v, 1e-15);
    EXPECT_NEAR(reading.omega, truth.omega, 1e-14);
    EXPECT_EQ(reading.var_v, 0.0);
    EXPECT_EQ(reading.var_omega, 0.0);
  }
}

TEST(OdometryModel, SameSeedGivesIdenticalSequence) {
  const OdometryParams params;
  RandomEngine a(derive_seed(42, "odometry_sensor/robot1"));
  RandomEngine b(derive_seed(42, "odometry_sensor/robot1"));
  const model::Twist truth{0.5, 0.2};
  for (int i = 0; i < 1000; ++i) {
    const OdometryReading ra = measure_odometry(truth, 0.02, kWheelBaseM, params, a);
    const OdometryReading rb = measure_odometry(truth, 0.02, kWheelBaseM, params, b);
    ASSERT_EQ(ra.v, rb.v);
    ASSERT_EQ(ra.omega, rb.omega);
  }
}

TEST(OdometryModel, DifferentSeedGivesDifferentReadings) {
  const OdometryParams params;
  RandomEngine a(derive_seed(42, "odometry_sensor/robot1"));
  RandomEngine b(derive_seed(42, "odometry_sensor/robot2"));
  const OdometryReading ra = measure_odometry(model::Twist{}, 0.02, kWheelBaseM, params, a);
  const OdometryReading rb = measure_odometry(model::Twist{}, 0.02, kWheelBaseM, params, b);
  EXPECT_NE(ra.v, rb.v);
  EXPECT_NE(ra.omega, rb.omega);
}

TEST(OdometryModel, DrawsTwoNormalsPerReadingWhateverTheNoise) {
  RandomEngine a(9);
  RandomEngine b(9);
  measure_odometry(model::Twist{}, 0.02, kWheelBaseM, OdometryParams{}, a);
  measure_odometry(model::Twist{}, 0.02, kWheelBaseM, noiseless(), b);
  EXPECT_EQ(a, b);
}

// Slip, straight line at v = 1 m/s, D = 0.5 m: a wheel reading fast by s adds s/2 m/s to v and
// turns omega toward the other wheel's side by s * 1 / D rad/s.

TEST(OdometryModel, FastRightWheelReadsFasterAndTurningLeft) {
  OdometryParams params = noiseless();
  params.right_slip = 0.01;
  RandomEngine engine(3);
  const OdometryReading reading = measure_odometry(model::Twist{1.0, 0.0}, 0.02, kWheelBaseM, params, engine);
  EXPECT_NEAR(reading.v, 1.005, 1e-12);
  EXPECT_NEAR(reading.omega, 0.02, 1e-12);  // counter-clockwise
}

TEST(OdometryModel, FastLeftWheelReadsFasterAndTurningRight) {
  OdometryParams params = noiseless();
  params.left_slip = 0.01;
  RandomEngine engine(3);
  const OdometryReading reading = measure_odometry(model::Twist{1.0, 0.0}, 0.02, kWheelBaseM, params, engine);
  EXPECT_NEAR(reading.v, 1.005, 1e-12);
  EXPECT_NEAR(reading.omega, -0.02, 1e-12);  // clockwise
}

TEST(OdometryModel, EqualSlipScalesTheWholeTwist) {
  OdometryParams params = noiseless();
  params.left_slip = -0.03;
  params.right_slip = -0.03;
  RandomEngine engine(3);
  const OdometryReading reading = measure_odometry(model::Twist{0.8, -0.4}, 0.02, kWheelBaseM, params, engine);
  EXPECT_NEAR(reading.v, 0.97 * 0.8, 1e-12);
  EXPECT_NEAR(reading.omega, 0.97 * -0.4, 1e-12);
}

TEST(OdometryModel, SlipBiasMatchesPredictionUnderNoise) {
  // General prediction: v_m = v + (sl v_l + sr v_r)/2, omega_m = omega + (sr v_r - sl v_l)/D.
  OdometryParams params;
  params.left_slip = -0.02;
  params.right_slip = 0.015;
  const model::Twist truth{0.6, 0.8};
  const double v_left = truth.v - 0.5 * truth.omega * kWheelBaseM;
  const double v_right = truth.v + 0.5 * truth.omega * kWheelBaseM;
  const double predicted_v_bias = 0.5 * (params.left_slip * v_left + params.right_slip * v_right);
  const double predicted_omega_bias =
      (params.right_slip * v_right - params.left_slip * v_left) / kWheelBaseM;

  RandomEngine engine(derive_seed(4, "odometry_sensor/slip"));
  const ErrorMoments m = error_moments(truth, params, engine, kSamples);
  // The noise is added after the scale error, so it still has the white-noise variances.
  const double noise_std = params.wheel_speed_noise_std_mps;
  const double var_v = noise_std * noise_std / 2.0;
  const double var_omega =
      2.0 * noise_std * noise_std / (kWheelBaseM * kWheelBaseM);
  const double n = kSamples;
  EXPECT_NEAR(m.mean_v, predicted_v_bias, 5.0 * std::sqrt(var_v / n));
  EXPECT_NEAR(m.mean_omega, predicted_omega_bias, 5.0 * std::sqrt(var_omega / n));
  EXPECT_NEAR(m.var_v, var_v, 5.0 * var_v * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.var_omega, var_omega, 5.0 * var_omega * std::sqrt(2.0 / n));
  // Sanity of the prediction's direction: left slow and right fast both turn left and the
  // faster-moving right wheel dominates v.
  EXPECT_GT(predicted_omega_bias, 0.0);
  EXPECT_GT(predicted_v_bias, 0.0);
}

TEST(OdometryModel, TurnRateBiasShiftsOmegaOnlyWhateverTheMotion) {
  OdometryParams params = noiseless();
  params.turn_rate_bias_radps = 0.0175;  // 1 deg/s
  RandomEngine engine(6);
  for (const model::Twist truth : {model::Twist{0.0, 0.0}, model::Twist{1.0, 0.0}, model::Twist{0.4, -0.7}}) {
    const OdometryReading reading = measure_odometry(truth, 0.02, kWheelBaseM, params, engine);
    EXPECT_NEAR(reading.v, truth.v, 1e-15);
    EXPECT_NEAR(reading.omega, truth.omega + 0.0175, 1e-14);  // also at standstill, like a gyro
    EXPECT_EQ(reading.var_omega, 0.0);                         // the bias is not claimed
  }
}

TEST(OdometryModel, TurnRateBiasDrawsNothingExtra) {
  OdometryParams biased;
  biased.turn_rate_bias_radps = -0.1;
  RandomEngine a(9);
  RandomEngine b(9);
  measure_odometry(model::Twist{}, 0.02, kWheelBaseM, OdometryParams{}, a);
  measure_odometry(model::Twist{}, 0.02, kWheelBaseM, biased, b);
  EXPECT_EQ(a, b);
}

// The wander off (the default) spends no draws: every scenario without it keeps its streams.
TEST(SlipWander, OffDrawsNothingAndStaysZero) {
  RandomEngine engine(11);
  const RandomEngine before = engine;
  SlipWander wander;
  advance_slip_wander(wander, 0.05, OdometryParams{}, engine);
  EXPECT_EQ(engine, before);
  EXPECT_EQ(wander.left, 0.0);
  EXPECT_EQ(wander.right, 0.0);
}

// On: starts stationary, keeps its sigma, and its lag correlation is exp(-dt / tau) (so it is
// neither white nor frozen); the two wheels wander independently.
TEST(SlipWander, IsAStationaryGaussMarkovProcessPerWheel) {
  OdometryParams params;
  params.slip_wander_sigma = 0.004;
  params.slip_wander_tau_s = 10.0;
  const double dt_s = 0.05;
  const int kSteps = 400000;  // 20,000 s: 2,000 correlation times
  RandomEngine engine(derive_seed(5, "odometry_sensor/wander"));
  SlipWander wander;
  double sum_l = 0.0, sum_ll = 0.0, sum_lag = 0.0, sum_lr = 0.0, previous = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    advance_slip_wander(wander, dt_s, params, engine);
    ASSERT_TRUE(wander.started);
    sum_l += wander.left;
    sum_ll += wander.left * wander.left;
    sum_lr += wander.left * wander.right;
    if (i > 0) sum_lag += wander.left * previous;
    previous = wander.left;
  }
  const double var = sum_ll / kSteps;
  EXPECT_NEAR(std::sqrt(var), 0.004, 0.004 * 0.1);
  EXPECT_NEAR(sum_l / kSteps, 0.0, 0.0008);
  EXPECT_NEAR(sum_lag / (kSteps - 1) / var, std::exp(-dt_s / 10.0), 0.002);
  EXPECT_NEAR(sum_lr / kSteps / var, 0.0, 0.1) << "left and right wander independently";
}

TEST(SlipWander, ScalesTheWheelSpeedsLikeTheSlip) {
  OdometryParams params = noiseless();
  params.left_slip = 0.001;
  RandomEngine engine(3);
  const OdometryReading reading =
      measure_odometry(model::Twist{1.0, 0.0}, 0.02, kWheelBaseM, params, engine, SlipWander{0.002, -0.003, true});
  // Left reads 1.003, right 0.997: v = 1.0, omega = (0.997 - 1.003) / 0.5.
  EXPECT_NEAR(reading.v, 1.0, 1e-12);
  EXPECT_NEAR(reading.omega, -0.006 / kWheelBaseM, 1e-12);
}

}  // namespace
}  // namespace robodds::odometry_sensor
