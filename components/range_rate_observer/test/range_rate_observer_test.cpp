#include "components/range_rate_observer/range_rate_observer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/random.hpp"

namespace robodds::range_rate_observer {
namespace {

/// A range with bounded acceleration (|s''| <= 0.75 m/s^2 < b = 2.2): s = 50 + 2 t + 3 sin(t / 2).
double smooth_range(double t) { return 50.0 + 2.0 * t + 3.0 * std::sin(0.5 * t); }
double smooth_rate(double t) { return 2.0 + 1.5 * std::cos(0.5 * t); }

struct Track {
  double settle_time_s = std::numeric_limits<double>::infinity();  // |rate error| < tol from here on
  double rms_after_mps = 0.0;                                      // over t >= rms_from_s
  double mean_after_mps = 0.0;                                     // signed, over t >= rms_from_s
  double max_abs_after_mps = 0.0;
};

/// Runs `observer` on range(t) sampled at rate_hz for duration_s (plus optional noise, m).
template <class Observer>
Track track(Observer observer, double rate_hz, double duration_s, const std::function<double(double)>& range,
            const std::function<double(double)>& rate, double tol_mps, double rms_from_s, double noise_m = 0.0,
            std::uint64_t seed = 7) {
  RandomEngine engine(seed);
  Track result;
  double sum_sq = 0.0;
  double sum = 0.0;
  int count = 0;
  bool settled = false;
  const int samples = static_cast<int>(std::lround(duration_s * rate_hz));
  for (int k = 0; k <= samples; ++k) {
    const double t = k / rate_hz;
    const RangeRateEstimate est = observer.update(t, range(t) + noise_m * standard_normal(engine));
    const double error = est.rate_mps - rate(t);
    if (std::abs(error) < tol_mps) {
      if (!settled) {
        result.settle_time_s = t;
        settled = true;
      }
    } else {
      settled = false;
      result.settle_time_s = std::numeric_limits<double>::infinity();
    }
    if (t >= rms_from_s) {
      sum_sq += error * error;
      sum += error;
      ++count;
      result.max_abs_after_mps = std::max(result.max_abs_after_mps, std::abs(error));
    }
  }
  result.rms_after_mps = std::sqrt(sum_sq / count);
  result.mean_after_mps = sum / count;
  return result;
}

TEST(SuperTwistingObserver, ConvergesWithinSecondsFromAnUnknownRate) {
  // Starts at rate 0 against a true rate of 3.5 m/s; NOTES.md: ~3 s with these gains.
  const Track t = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 30.0, smooth_range, smooth_rate, 0.1, 10.0);
  EXPECT_LT(t.settle_time_s, 6.0);
  EXPECT_LT(t.max_abs_after_mps, 0.1);
}

TEST(SuperTwistingObserver, ChatteringScalesWithTheSamplePeriod) {
  // Noise-free, the remaining error is discretisation chattering of about 0.8 b T (NOTES.md:
  // 0.17 / 0.035 / 0.018 m/s RMS at 10 / 50 / 100 Hz with b = 2.2).
  double rms[3];
  const double rates_hz[3] = {10.0, 50.0, 100.0};
  for (int i = 0; i < 3; ++i) {
    rms[i] = track(SuperTwistingObserver(SuperTwistingParams{}), rates_hz[i], 60.0, smooth_range, smooth_rate, 1.0, 20.0)
                 .rms_after_mps;
    const double expected = 0.8 * 2.2 / rates_hz[i];
    std::printf("%5.0f Hz: rate error RMS %.4f m/s (0.8 b T = %.4f)\n", rates_hz[i], rms[i], expected);
    EXPECT_GT(rms[i], 0.3 * expected) << rates_hz[i] << " Hz";
    EXPECT_LT(rms[i], 2.0 * expected) << rates_hz[i] << " Hz";
  }
  EXPECT_GT(rms[0] / rms[2], 5.0);
}

TEST(SuperTwistingObserver, LinearTermDSpeedsUpConvergence) {
  // The d e term matters when the initial error is large: from rate 0 against ~21 m/s, d = 1
  // settles in ~4 s and d = 0 in ~7 s (the gap grows with the error: ~2x at 50 m/s).
  const auto range = [](double t) { return 50.0 + 20.0 * t + 3.0 * std::sin(0.5 * t); };
  const auto rate = [](double t) { return 20.0 + 1.5 * std::cos(0.5 * t); };
  SuperTwistingParams plain;
  plain.d = 0.0;
  const double with_d = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 40.0, range, rate, 0.1, 30.0).settle_time_s;
  const double without_d = track(SuperTwistingObserver(plain), 100.0, 40.0, range, rate, 0.1, 30.0).settle_time_s;
  ASSERT_TRUE(std::isfinite(without_d));
  EXPECT_GT(without_d, 1.3 * with_d);
}

TEST(Observers, SlidingModeIsExactUnderConstantAccelerationWhereTheLinearOneLags) {
  // s = t^2 / 2: the linear observer settles at a rate error of -k1 a / k2 (-1.33 m/s with the
  // defaults); the super-twisting observer follows exactly (b > |a|), up to chattering.
  const auto range = [](double t) { return 10.0 + 0.5 * t * t; };
  const auto rate = [](double t) { return t; };
  const Track sliding = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 30.0, range, rate, 0.1, 20.0);
  const Track linear = track(LinearRangeRateObserver(LinearObserverParams{}), 100.0, 30.0, range, rate, 0.1, 20.0);
  std::printf("constant acceleration 1 m/s^2, rate error RMS: sliding mode %.3f, linear %.3f m/s\n",
              sliding.rms_after_mps, linear.rms_after_mps);
  EXPECT_LT(sliding.max_abs_after_mps, 0.1);
  EXPECT_NEAR(linear.rms_after_mps, 3.0 * 1.0 / 2.25, 0.1);
}

TEST(Observers, LagUnderConstantRangeAccelerationNoiseFree) {
  // LAG alone: no noise, s = 10 + t^2 / 2 (1 m/s^2 < b). The linear observer's steady rate error
  // is -k1 a / k2 = -1.333 m/s with the defaults; the super-twisting one has no lag, only its
  // chattering (~0.8 b T). Signed mean and RMS of the rate error over 20-60 s, 100 Hz.
  const auto range = [](double t) { return 10.0 + 0.5 * t * t; };
  const auto rate = [](double t) { return t; };
  const Track sliding = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 60.0, range, rate, 0.1, 20.0);
  const Track linear = track(LinearRangeRateObserver(LinearObserverParams{}), 100.0, 60.0, range, rate, 0.1, 20.0);
  std::printf("lag, noise-free, 1 m/s^2 at 100 Hz, rate error mean / RMS: sliding mode %.4f / %.4f, linear %.4f / %.4f m/s\n",
              sliding.mean_after_mps, sliding.rms_after_mps, linear.mean_after_mps, linear.rms_after_mps);
  // Measured 2026-12-02: sliding mode -0.0078 / 0.0177, linear -1.3283 / 1.3283 m/s.
  EXPECT_NEAR(linear.mean_after_mps, -3.0 * 1.0 / 2.25, 0.02);
  EXPECT_NEAR(linear.rms_after_mps, 3.0 * 1.0 / 2.25, 0.02);
  EXPECT_LT(std::abs(sliding.mean_after_mps), 0.02);
  EXPECT_LT(sliding.rms_after_mps, 0.03);
}

TEST(Observers, NoiseFloorOnAConstantRangeWithHalfAMetreOfNoise) {
  // NOISE alone: a constant range (no lag to measure) with seeded white Gaussian noise of 0.5 m
  // at 100 Hz; RMS of the rate estimate over 20-200 s. The linear defaults (w = 1.5 rad/s) pass
  // less noise than the super-twisting defaults, whose sgn(e) term reacts to every noisy sign.
  const auto range = [](double) { return 100.0; };
  const auto rate = [](double) { return 0.0; };
  const Track sliding = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 200.0, range, rate, 1.0, 20.0, 0.5);
  const Track linear = track(LinearRangeRateObserver(LinearObserverParams{}), 100.0, 200.0, range, rate, 1.0, 20.0, 0.5);
  std::printf("noise floor, constant range, 0.5 m noise at 100 Hz, rate RMS: sliding mode %.4f, linear %.4f m/s\n",
              sliding.rms_after_mps, linear.rms_after_mps);
  // Measured 2026-12-02 (seed 7): sliding mode 0.1135, linear 0.0470 m/s; seeds 1-10 give
  // 0.108-0.117 and 0.044-0.048. Noise-free the sliding mode would show only its chattering
  // (~0.018) and the linear one 0; the lag case above gives 1.33: both outside these bands.
  EXPECT_GT(sliding.rms_after_mps, 0.09);
  EXPECT_LT(sliding.rms_after_mps, 0.14);
  EXPECT_GT(linear.rms_after_mps, 0.038);
  EXPECT_LT(linear.rms_after_mps, 0.058);
  EXPECT_LT(linear.rms_after_mps, 0.6 * sliding.rms_after_mps);
  EXPECT_LT(std::abs(sliding.mean_after_mps), 0.05);
  EXPECT_LT(std::abs(linear.mean_after_mps), 0.05);
}

// Issue 28: the Kalman filter (kalman_law.hpp) against paper 2's two observers. Its key idea is
// the range-acceleration state: without it (a constant-velocity model) it would lag under a
// constant acceleration like the linear observer (KalmanObserver.ConstantAccelerationWithoutLag
// fails then); its small jerk density gives a noise floor near the linear observer's.
TEST(KalmanObserver, ConstantAccelerationWithoutLag) {
  const auto range = [](double t) { return 10.0 + 0.5 * t * t; };
  const auto rate = [](double t) { return t; };
  const Track kalman = track(KalmanRangeRateObserver(KalmanObserverParams{}), 100.0, 60.0, range, rate, 0.1, 20.0);
  const Track linear = track(LinearRangeRateObserver(LinearObserverParams{}), 100.0, 60.0, range, rate, 0.1, 20.0);
  std::printf("lag, noise-free, 1 m/s^2 at 100 Hz, rate error mean / RMS: Kalman %.5f / %.5f, linear %.4f / %.4f m/s\n",
              kalman.mean_after_mps, kalman.rms_after_mps, linear.mean_after_mps, linear.rms_after_mps);
  EXPECT_LT(kalman.max_abs_after_mps, 0.01);
  EXPECT_GT(linear.rms_after_mps, 1.0);
}

TEST(KalmanObserver, NoiseFloorNearTheLinearObserversAndBelowTheSlidingModes) {
  // The same constant range and noise as NoiseFloorOnAConstantRangeWithHalfAMetreOfNoise, 50 Hz
  // (the papers' range rate), seeds 1-5 pooled.
  const auto range = [](double) { return 100.0; };
  const auto rate = [](double) { return 0.0; };
  double kalman_sq = 0.0;
  double linear_sq = 0.0;
  double sliding_sq = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto rms = [&](auto observer) {
      return track(observer, 50.0, 200.0, range, rate, 1.0, 20.0, 0.5, seed).rms_after_mps;
    };
    kalman_sq += std::pow(rms(KalmanRangeRateObserver(KalmanObserverParams{})), 2);
    linear_sq += std::pow(rms(LinearRangeRateObserver(LinearObserverParams{})), 2);
    sliding_sq += std::pow(rms(SuperTwistingObserver(SuperTwistingParams{})), 2);
  }
  const double kalman = std::sqrt(kalman_sq / 5.0);
  const double linear = std::sqrt(linear_sq / 5.0);
  const double sliding = std::sqrt(sliding_sq / 5.0);
  std::printf("noise floor, constant range, 0.5 m at 50 Hz, rate RMS: Kalman %.4f, linear %.4f, sliding mode %.4f m/s\n",
              kalman, linear, sliding);
  EXPECT_LT(kalman, 0.5 * sliding);
  EXPECT_LT(kalman, 1.5 * linear);
}

TEST(KalmanObserver, OnAnOrbitUnderNoiseItBeatsBothPaperObservers) {
  // The observer study's orbit (a robot at ~9 m/s turning at 0.15 rad/s around a point off the
  // target): s = 300 + 60 sin(0.15 t), |s''| <= 1.35 m/s^2, 0.5 m of noise at 50 Hz, RMS over
  // 20-200 s, seeds 1-5 pooled. Its bandwidth, (q / (sigma^2 dt))^(1/6) ~ 0.76 rad/s, is tuned for
  // such slow range dynamics: on faster ones it loses to the linear observer (smooth_range, 0.5
  // rad/s: 0.94 against 0.64 m/s RMS over 5-60 s; README.md "Kalman filter").
  const auto range = [](double t) { return 300.0 + 60.0 * std::sin(0.15 * t); };
  const auto rate = [](double t) { return 9.0 * std::cos(0.15 * t); };
  double kalman_sq = 0.0;
  double linear_sq = 0.0;
  double sliding_sq = 0.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto rms = [&](auto observer) { return track(observer, 50.0, 200.0, range, rate, 1.0, 20.0, 0.5, seed).rms_after_mps; };
    kalman_sq += std::pow(rms(KalmanRangeRateObserver(KalmanObserverParams{})), 2);
    linear_sq += std::pow(rms(LinearRangeRateObserver(LinearObserverParams{})), 2);
    sliding_sq += std::pow(rms(SuperTwistingObserver(SuperTwistingParams{})), 2);
  }
  const double kalman = std::sqrt(kalman_sq / 5.0);
  const double linear = std::sqrt(linear_sq / 5.0);
  const double sliding = std::sqrt(sliding_sq / 5.0);
  std::printf("orbit, 0.5 m at 50 Hz, rate RMS 20-200 s: Kalman %.4f, linear %.4f, sliding mode %.4f m/s\n", kalman, linear,
              sliding);
  EXPECT_LT(kalman, linear);
  EXPECT_LT(kalman, sliding);
}

TEST(KalmanObserver, RestartsOnARangeJumpAndBridgesLostSamplesByPrediction) {
  KalmanRangeRateObserver observer{KalmanObserverParams{}};
  // 10 s at 50 Hz on s = 10 + t^2 / 2, then 20 samples lost, then on: no restart, error small.
  for (int k = 0; k <= 500; ++k) {
    observer.update(k / 50.0, 10.0 + 0.5 * std::pow(k / 50.0, 2));
  }
  const double t = 10.4;
  const RangeRateEstimate after_gap = observer.update(t, 10.0 + 0.5 * t * t);
  EXPECT_EQ(observer.restarts(), 0u);
  EXPECT_NEAR(after_gap.rate_mps, t, 0.01);
  // A 500 m jump (a new target): one restart, a window, then valid again.
  observer.update(t + 0.02, 510.0 + 0.5 * t * t);
  EXPECT_EQ(observer.restarts(), 1u);
  EXPECT_FALSE(observer.valid());
}

TEST(KalmanObserver, RejectsBadParametersByKey) {
  KalmanObserverParams p;
  p.jerk_psd_m2ps5 = 0.0;
  try {
    KalmanRangeRateObserver observer{p};
    FAIL() << "accepted jerk_psd_m2ps5 = 0";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("jerk_psd_m2ps5"), std::string::npos) << e.what();
  }
}

TEST(RangeRateObserver, RestartsOnARangeJumpInsteadOfSpiking) {
  // A new target 500 m further at t = 10 s (paper 2 switches targets at 1000 s).
  const auto range = [](double t) { return smooth_range(t) + (t >= 10.0 ? 500.0 : 0.0); };
  const Track restarted = track(SuperTwistingObserver(SuperTwistingParams{}), 100.0, 20.0, range, smooth_rate, 0.1, 9.0);
  EXPECT_LT(restarted.max_abs_after_mps, 0.5);
  SuperTwistingParams never;
  never.restart_sigmas = 0.0;
  const Track spiked = track(SuperTwistingObserver(never), 100.0, 20.0, range, smooth_rate, 0.1, 9.0);
  EXPECT_GT(spiked.max_abs_after_mps, 20.0);

  SuperTwistingObserver observer{SuperTwistingParams{}};
  observer.update(0.0, 10.0);
  observer.update(0.01, 10.0);
  EXPECT_EQ(observer.restarts(), 0u);
  const RangeRateEstimate after = observer.update(0.02, 510.0);
  EXPECT_EQ(observer.restarts(), 1u);
  EXPECT_EQ(after.range_m, 510.0);
}

/// Restarts of `observer` on smooth_range sampled at 50 Hz for duration_s with Gaussian noise
/// sigma_m, plus jump_m added from jump_at_s on; the noise estimate at the end.
template <class Observer>
std::pair<std::size_t, double> restarts_under_noise(Observer observer, double sigma_m, std::uint64_t seed, double duration_s,
                                                    double jump_at_s = 1e9, double jump_m = 0.0) {
  RandomEngine engine(seed);
  const int samples = static_cast<int>(std::lround(duration_s * 50.0));
  for (int k = 0; k <= samples; ++k) {
    const double t = k / 50.0;
    observer.update(t, smooth_range(t) + (t >= jump_at_s ? jump_m : 0.0) + sigma_m * standard_normal(engine));
  }
  return {observer.restarts(), observer.noise_sigma_m()};
}

TEST(RangeRateObserver, RangeNoiseAboveItsFloorDoesNotRestartIt) {
  // Issue 27: the sensor 2x and 4x noisier than the configured 0.5 m. A fixed 5 m threshold on
  // the step (sqrt(2) sigma spread: 2.83 m at 2 m) restarted the observers ~30,000 times a
  // 2000 s run; the threshold now follows the estimated noise (7 x 2.83 = 19.8 m at 2 m), so
  // 300 s (15,000 steps) on 5 seeds give none, and the estimate (a median of 256 steps, ~7 %
  // relative error) is within 20 % of the truth.
  for (const double sigma_m : {1.0, 2.0}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const auto [sta_restarts, sta_sigma] =
          restarts_under_noise(SuperTwistingObserver(SuperTwistingParams{}), sigma_m, seed, 300.0);
      const auto [linear_restarts, linear_sigma] =
          restarts_under_noise(LinearRangeRateObserver(LinearObserverParams{}), sigma_m, seed, 300.0);
      EXPECT_EQ(sta_restarts, 0u) << sigma_m << " m, seed " << seed;
      EXPECT_EQ(linear_restarts, 0u) << sigma_m << " m, seed " << seed;
      EXPECT_NEAR(sta_sigma, sigma_m, 0.2 * sigma_m) << seed;
      EXPECT_NEAR(linear_sigma, sigma_m, 0.2 * sigma_m) << seed;
    }
  }
}

TEST(RangeRateObserver, AJumpWellAboveTheEstimatedNoiseStillRestartsItOnce) {
  // At 2 m of noise a 50 m jump (17.7 step sigmas; the threshold is ~19.8 m) is a new range
  // source: exactly one restart, and the jump does not move the noise estimate.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto [restarts, sigma] =
        restarts_under_noise(SuperTwistingObserver(SuperTwistingParams{}), 2.0, seed, 120.0, 60.0, 50.0);
    EXPECT_EQ(restarts, 1u) << seed;
    EXPECT_NEAR(sigma, 2.0, 0.4) << seed;
  }
}

TEST(RangeRateObserver, ThresholdRestsOnTheFloorWithoutNoiseAndIsWiderUntilTrained) {
  // Noise-free the steps the rate misses are millimetres: the configured floor (0.5 m) sets the
  // threshold, 7 sqrt(2) 0.5 = 4.95 m (the fixed 5 m of before); over the first 32 steps it is
  // 3x wider, so a sensor noisier than its floor does not restart the observer at start.
  SuperTwistingObserver observer{SuperTwistingParams{}};
  observer.update(0.0, smooth_range(0.0));
  observer.update(0.02, smooth_range(0.02));
  EXPECT_NEAR(observer.restart_threshold_m(), 3.0 * 7.0 * std::sqrt(2.0) * 0.5, 1e-9);
  for (int k = 2; k <= 600; ++k) {
    observer.update(k * 0.02, smooth_range(k * 0.02));
  }
  EXPECT_LT(observer.noise_sigma_m(), 0.01);
  EXPECT_NEAR(observer.restart_threshold_m(), 7.0 * std::sqrt(2.0) * 0.5, 1e-9);
  EXPECT_EQ(observer.noise_samples(), 256u);
  EXPECT_EQ(observer.restarts(), 0u);
}

/// A target switch under range noise: the range to target 1 until switch_s, then to target 2
/// (a jump of ~700 m, so the jump rule restarts the observer), seeded Gaussian noise.
struct AfterRestart {
  double max_error_valid_mps = 0.0;  // max |rate error| over valid samples from the switch to +20 s
  double settle_s = 0.0;             // from the switch until |rate error| < 1 m/s for good
  int invalid_samples = 0;
  std::size_t restarts = 0;
};

double target2_range(double t) { return 800.0 - 3.0 * t + 2.0 * std::sin(t / 3.0); }
double target2_rate(double t) { return -3.0 + (2.0 / 3.0) * std::cos(t / 3.0); }

template <class Observer>
AfterRestart restart_under_noise(Observer observer, double rate_hz, double noise_m, std::uint64_t seed,
                                 bool by_call = false) {
  RandomEngine engine(seed);
  const double switch_s = 30.0;
  AfterRestart result;
  double last_bad_s = switch_s;
  const int samples = static_cast<int>(std::lround((switch_s + 20.0) * rate_hz));
  for (int k = 0; k <= samples; ++k) {
    const double t = k / rate_hz;
    const bool after = t >= switch_s;
    if (by_call && k == static_cast<int>(std::lround(switch_s * rate_hz))) {
      observer.restart();
    }
    const double truth = after ? target2_range(t) : smooth_range(t);
    const double truth_rate = after ? target2_rate(t) : smooth_rate(t);
    const RangeRateEstimate est = observer.update(t, truth + noise_m * standard_normal(engine));
    EXPECT_EQ(est.valid, observer.valid());
    if (!after) {
      continue;
    }
    if (!est.valid) {
      ++result.invalid_samples;
      last_bad_s = t;
      continue;
    }
    const double error = std::abs(est.rate_mps - truth_rate);
    result.max_error_valid_mps = std::max(result.max_error_valid_mps, error);
    if (error >= 1.0) {
      last_bad_s = t;
    }
  }
  result.settle_s = last_bad_s - switch_s;
  result.restarts = observer.restarts();
  return result;
}

TEST(RangeRateObserver, RestartUnderNoiseStartsFromAWindowSlopeAndIsInvalidMeanwhile) {
  // sigma 0.5 m at 50 Hz, a target switch at 30 s, 20 seeds. Re-initialised from the 0.5 s
  // least-squares slope, the worst rate error once valid is 0.48-1.60 m/s (seed 7: 0.68) for the
  // sliding mode and 0.39-1.56 for the linear observer, settled (< 1 m/s) when the window closes
  // (0.48 s) on 17 of 20 seeds, within 1.3 s on all. Set from one difference (a window of one
  // sample period, the old rule) the same seeds give up to 90 m/s (seed 7: 8.1) and up to 5.5 s to
  // settle. The system bound: max error after a restart <= 3 m/s.
  const double rate_hz = 50.0;
  SuperTwistingParams sliding_one_difference;
  sliding_one_difference.restart_window_s = 1.0 / rate_hz;
  LinearObserverParams linear_one_difference;
  linear_one_difference.restart_window_s = 1.0 / rate_hz;
  double worst_sliding = 0.0;
  double worst_linear = 0.0;
  double worst_settle = 0.0;
  int one_difference_over_3 = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const AfterRestart sliding = restart_under_noise(SuperTwistingObserver(SuperTwistingParams{}), rate_hz, 0.5, seed);
    const AfterRestart linear = restart_under_noise(LinearRangeRateObserver(LinearObserverParams{}), rate_hz, 0.5, seed);
    EXPECT_EQ(sliding.restarts, 1u) << seed;
    EXPECT_EQ(linear.restarts, 1u) << seed;
    EXPECT_EQ(sliding.invalid_samples, 25) << seed;  // 0.5 s: valid again at the 26th sample
    worst_sliding = std::max(worst_sliding, sliding.max_error_valid_mps);
    worst_linear = std::max(worst_linear, linear.max_error_valid_mps);
    worst_settle = std::max({worst_settle, sliding.settle_s, linear.settle_s});
    const AfterRestart old = restart_under_noise(SuperTwistingObserver(sliding_one_difference), rate_hz, 0.5, seed);
    one_difference_over_3 += old.max_error_valid_mps > 3.0 ? 1 : 0;
  }
  std::printf("restart, 0.5 m noise at 50 Hz, seeds 1-20: worst rate error once valid sliding mode %.3f, linear %.3f m/s, "
              "worst settle %.2f s; one-difference start over 3 m/s on %d of 20 seeds\n",
              worst_sliding, worst_linear, worst_settle, one_difference_over_3);
  EXPECT_LT(worst_sliding, 2.0);
  EXPECT_LT(worst_linear, 2.0);
  EXPECT_LT(worst_settle, 1.5);
  EXPECT_GE(one_difference_over_3, 10);
}

TEST(RangeRateObserver, RestartCallOpensAWindowWithoutARangeJump) {
  // A new target at the same range (the node calls restart() on a target change): no jump, yet
  // the next sample opens the window; noise-free, the estimate is exact again once valid.
  SuperTwistingObserver observer{SuperTwistingParams{}};
  observer.restart();  // before the first sample: nothing to restart
  int invalid = 0;
  double worst_valid_error = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = k / 100.0;
    if (k == 1000) {
      observer.restart();
    }
    const RangeRateEstimate est = observer.update(t, smooth_range(t));
    if (!est.valid) {
      ++invalid;
    } else if (t >= 10.0) {
      worst_valid_error = std::max(worst_valid_error, std::abs(est.rate_mps - smooth_rate(t)));
    }
  }
  EXPECT_EQ(observer.restarts(), 1u);
  EXPECT_EQ(invalid, 50);  // 0.5 s at 100 Hz
  EXPECT_LT(worst_valid_error, 0.3);
}

TEST(RangeRateObserver, AFastTargetAtACoarseRateRestartsAtMostOnce) {
  // 10 m/s sampled at 1 Hz moves 10 m per sample, twice the default threshold at the 0.5 m floor
  // (4.95 m): the restart rule compares with the prediction s_hat + v_hat dt, so once the rate is
  // known it stops firing. Over the first 32 steps the threshold is 3x wider (14.8 m), so the
  // 10 m steps no longer restart it at start; the gains tuned for 50 Hz then converge from rate 0
  // into the sliding mode's 1 Hz limit cycle, 6.6-13.4 m/s (before issue 27 a restart at the
  // first step happened to start it from the exact slope: 1.8 m/s). A 1 Hz sensor feeding an
  // observer tuned for 50 Hz is issue 27's rate-mismatch finding, not handled here.
  SuperTwistingObserver observer{SuperTwistingParams{}};
  double worst_late_error = 0.0;
  for (int k = 0; k <= 60; ++k) {
    const double t = k;
    const RangeRateEstimate est = observer.update(t, 50.0 + 10.0 * t);
    if (t >= 30.0) {
      worst_late_error = std::max(worst_late_error, std::abs(est.rate_mps - 10.0));
    }
  }
  EXPECT_LE(observer.restarts(), 1u);
  EXPECT_LT(worst_late_error, 4.0);  // the 1 Hz limit cycle: 3.44 m/s
}

/// Max and RMS rate error over 20-120 s of `observer` on smooth_range at 50 Hz, each sample lost
/// with probability `loss` (seeded), and how often it restarted.
template <class Observer>
std::pair<Track, std::size_t> track_with_losses(Observer observer, double loss, std::uint64_t seed,
                                               const std::function<double(double)>& range = smooth_range,
                                               const std::function<double(double)>& rate = smooth_rate) {
  RandomEngine engine(seed);
  Track result;
  double sum_sq = 0.0;
  int count = 0;
  for (int k = 0; k <= 6000; ++k) {
    const double t = k / 50.0;
    if (k > 0 && uniform01(engine) < loss) {
      continue;  // lost: the observer sees the next sample after a longer step
    }
    const double error = observer.update(t, range(t)).rate_mps - rate(t);
    if (t >= 20.0) {
      sum_sq += error * error;
      ++count;
      result.max_abs_after_mps = std::max(result.max_abs_after_mps, std::abs(error));
    }
  }
  result.rms_after_mps = std::sqrt(sum_sq / count);
  return {result, observer.restarts()};
}

TEST(RangeRateObserver, LostSamplesNeitherRestartItNorWidenItsChattering) {
  // Issue 27, finding 6: with 10 % of the ranges lost, paper 2's convergence (0.2 m/s held for
  // 200 s) took 367-1,528 s. A lost sample makes one step 2T (or kT) long; one Euler step over it
  // applied the last error's correction, the sliding mode's b sgn(e), for 2T and its chattering
  // grew. Now the gap is integrated period by period against the line between the ranges on
  // either side (the constructor's comment). Noise-free 50 Hz, max / RMS over 20-120 s: no losses
  // 0.103 / 0.038 m/s; one Euler step per gap 0.20-0.22 / 0.046-0.047 (10 %), 0.33-0.44 /
  // 0.069-0.074 (30 %); now 0.100-0.124 / 0.038-0.039. The linear observer lags 0.91 m/s on this
  // range's 0.75 m/s^2 either way (correcting over one period and predicting the rest: up to
  // 1.05, 16 % more at 30 % losses).
  const Track clean = track_with_losses(SuperTwistingObserver(SuperTwistingParams{}, {}, 0.02), 0.0, 1).first;
  const Track clean_linear = track_with_losses(LinearRangeRateObserver(LinearObserverParams{}, {}, 0.02), 0.0, 1).first;
  for (const double loss : {0.1, 0.3}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const auto [lossy, restarts] = track_with_losses(SuperTwistingObserver(SuperTwistingParams{}, {}, 0.02), loss, seed);
      const auto [lossy_linear, linear_restarts] = track_with_losses(LinearRangeRateObserver(LinearObserverParams{}, {}, 0.02), loss, seed);
      std::printf("loss %.0f %% seed %d: sta max %.4f RMS %.4f m/s (no loss: max %.4f RMS %.4f), linear max %.4f m/s\n",
                  100.0 * loss, static_cast<int>(seed), lossy.max_abs_after_mps, lossy.rms_after_mps,
                  clean.max_abs_after_mps, clean.rms_after_mps, lossy_linear.max_abs_after_mps);
      EXPECT_EQ(restarts, 0u);
      EXPECT_EQ(linear_restarts, 0u);
      EXPECT_LT(lossy.max_abs_after_mps, 0.15) << "loss " << loss << " seed " << seed;
      EXPECT_LT(lossy.rms_after_mps, 1.1 * clean.rms_after_mps) << "loss " << loss << " seed " << seed;
      EXPECT_LT(lossy_linear.max_abs_after_mps, 1.05 * clean_linear.max_abs_after_mps) << "loss " << loss << " seed " << seed;
    }
  }
}

TEST(RangeRateObserver, LostSamplesDoNotLowerItsBoundOnTheRangeAcceleration) {
  // The sliding mode follows |s''| up to b = 2.2 m/s^2. Correcting over one period per received
  // sample and predicting over the rest of a gap would leave it b (1 - losses) of rate correction
  // per second (1.54 m/s^2 at 30 % losses). Range 50 + 2 t + 8 sin(t / 2), |s''| up to 2 m/s^2, max
  // error over 20-120 s: no losses 0.144 m/s; now 0.144-0.157 (10 %), 0.171-0.208 (30 %); correcting
  // over one period and predicting 0.22-0.29 (10 %), 1.04-1.32 (30 %); one Euler step per gap
  // 0.31-0.49 (30 %). Lost ranges on the straight line between the received ones (the chord lies
  // r'' tau (dt - tau) / 2 inside the range, a few mm, above the sliding mode's range error):
  // 0.171-0.208, RMS 0.051-0.054 (30 %); on the curve bent by the law's s'' estimate: 0.120-0.141
  // (30 %), 0.138-0.144 (10 %), RMS 0.036-0.038 (no losses 0.036).
  const auto range = [](double t) { return 50.0 + 2.0 * t + 8.0 * std::sin(0.5 * t); };
  const auto rate = [](double t) { return 2.0 + 4.0 * std::cos(0.5 * t); };
  const Track clean = track_with_losses(SuperTwistingObserver(SuperTwistingParams{}, {}, 0.02), 0.0, 1, range, rate).first;
  for (const double loss : {0.1, 0.3}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const Track lossy = track_with_losses(SuperTwistingObserver(SuperTwistingParams{}, {}, 0.02), loss, seed, range, rate).first;
      std::printf("|s''| 2 m/s^2, loss %.0f %% seed %d: max %.4f RMS %.4f m/s (no loss: max %.4f RMS %.4f)\n", 100.0 * loss,
                  static_cast<int>(seed), lossy.max_abs_after_mps, lossy.rms_after_mps, clean.max_abs_after_mps,
                  clean.rms_after_mps);
      EXPECT_LT(lossy.max_abs_after_mps, 1.1 * clean.max_abs_after_mps) << "loss " << loss << " seed " << seed;
      EXPECT_LT(lossy.rms_after_mps, 1.1 * clean.rms_after_mps) << "loss " << loss << " seed " << seed;
    }
  }
}

/// Worst |error| of predict(t + k T) (k = 1..7 lost periods) over every sample of 40-120 s, and of
/// the estimate held instead (what the node republished before), against the truth, for rate and
/// range; the worst |rate error| of the estimates themselves; and whether every prediction's std
/// was the fresh one widened by 2.2 m/s^2 x k T.
struct PredictionErrors {
  double fresh_rate_mps = 0.0;
  double predicted_rate_mps = 0.0;
  double held_rate_mps = 0.0;
  double predicted_range_m = 0.0;
  double held_range_m = 0.0;
  bool std_widened = true;
};

template <class Observer>
PredictionErrors prediction_errors(Observer observer) {
  // The observer study's orbit: a robot at ~9 m/s turning at the plant's 0.15 rad/s limit,
  // |s''| up to 1.35 m/s^2 (< b = 2.2).
  const auto range = [](double t) { return 300.0 + 60.0 * std::sin(0.15 * t); };
  const auto rate = [](double t) { return 9.0 * std::cos(0.15 * t); };
  constexpr double kPeriodS = 0.02;
  PredictionErrors out;
  for (int i = 0; i <= 6000; ++i) {
    const double t = i * kPeriodS;
    const RangeRateEstimate fresh = observer.update(t, range(t));
    if (t < 40.0) {
      continue;
    }
    out.fresh_rate_mps = std::max(out.fresh_rate_mps, std::abs(fresh.rate_mps - rate(t)));
    for (int k = 1; k <= 7; ++k) {
      const double later = t + k * kPeriodS;
      const RangeRateEstimate predicted = observer.predict(later);
      out.predicted_rate_mps = std::max(out.predicted_rate_mps, std::abs(predicted.rate_mps - rate(later)));
      out.held_rate_mps = std::max(out.held_rate_mps, std::abs(fresh.rate_mps - rate(later)));
      out.predicted_range_m = std::max(out.predicted_range_m, std::abs(predicted.range_m - range(later)));
      out.held_range_m = std::max(out.held_range_m, std::abs(fresh.range_m - range(later)));
      const double widening = 2.2 * k * kPeriodS;
      out.std_widened &= std::abs(predicted.rate_std_mps -
                                  std::sqrt(fresh.rate_std_mps * fresh.rate_std_mps + widening * widening)) < 1e-12 &&
                         predicted.time_s == later && predicted.valid == fresh.valid;
    }
    // Before and at the last sample: the estimate itself.
    out.std_widened &= observer.predict(t).rate_mps == fresh.rate_mps && observer.predict(t - 1.0).range_m == fresh.range_m;
  }
  return out;
}

TEST(RangeRateObserver, ALostSampleIsPredictedOnTheLawsModelWithAWiderStd) {
  // Issue 27, finding 6: while ranges are lost the node republished the last estimate, so a
  // burst of k lost samples held the rate for k T while the truth moved by s'' k T (0.28 m/s at
  // 2 m/s^2 over 7 periods) and the range by the rate times k T, claiming the std of a fresh
  // estimate. predict() carries each law's state on its own model of s'' (the Kalman filter's
  // acceleration state; the low-passed v_hat' of paper 2's laws, their equivalent output
  // injection) and widens the std by the bound times the hold. Noise-free orbit, 50 Hz, worst over
  // 40-120 s and 1-7 lost periods, rate m/s: sta 0.118 fresh (its chattering), 0.172 predicted,
  // 0.306 held; Kalman 0.050 / 0.072 / 0.200; linear (its lag) 1.771 / 1.772 / 1.958; range m,
  // predicted / held: sta 0.022 / 1.26, Kalman 0.017 / 1.25, linear 0.84 / 1.50 (its own range lag).
  // Predicting the rate as held (no s'' model) is the held figure.
  RateUncertaintyParams uncertainty;
  uncertainty.range_accel_mps2 = 2.2;
  const PredictionErrors sta = prediction_errors(SuperTwistingObserver(SuperTwistingParams{}, uncertainty, 0.02));
  const PredictionErrors linear = prediction_errors(LinearRangeRateObserver(LinearObserverParams{}, uncertainty, 0.02));
  const PredictionErrors kalman = prediction_errors(KalmanRangeRateObserver(KalmanObserverParams{}, uncertainty, 0.02));
  for (const auto& [name, e] : {std::pair<const char*, PredictionErrors>{"sta", sta}, {"linear", linear}, {"kalman", kalman}}) {
    std::printf("%s: rate fresh %.4f predicted %.4f held %.4f m/s, range predicted %.4f held %.4f m\n", name,
                e.fresh_rate_mps, e.predicted_rate_mps, e.held_rate_mps, e.predicted_range_m, e.held_range_m);
    EXPECT_TRUE(e.std_widened) << name;
    EXPECT_LT(e.predicted_range_m, 0.6 * e.held_range_m) << name;
    // What 7 lost periods add to the rate error: held, |s''| 7 T = 0.19 m/s; predicted, a third of it.
    EXPECT_GT(e.held_rate_mps - e.fresh_rate_mps, 0.15) << name;
    EXPECT_LT(e.predicted_rate_mps - e.fresh_rate_mps, 0.06) << name;
  }
  EXPECT_LT(sta.predicted_range_m, 0.05);
  EXPECT_LT(kalman.predicted_range_m, 0.05);
}

TEST(RangeRateObserver, BadInputThrowsAndChangesNothing) {
  SuperTwistingObserver a{SuperTwistingParams{}};
  SuperTwistingObserver b{SuperTwistingParams{}};
  EXPECT_THROW(a.update(0.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_FALSE(a.started());
  for (int k = 0; k < 50; ++k) {
    const double t = 0.01 * k;
    a.update(t, smooth_range(t));
    b.update(t, smooth_range(t));
  }
  EXPECT_THROW(a.update(0.49, 60.0), std::invalid_argument);  // time does not advance
  EXPECT_THROW(a.update(std::numeric_limits<double>::quiet_NaN(), 60.0), std::invalid_argument);
  try {
    a.update(0.49, 60.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "range-rate observer: time must advance (got 0.49 s after 0.49 s)");
  }
  EXPECT_THROW(a.update(0.5, std::numeric_limits<double>::infinity()), std::invalid_argument);
  const RangeRateEstimate ea = a.update(0.5, smooth_range(0.5));
  const RangeRateEstimate eb = b.update(0.5, smooth_range(0.5));
  EXPECT_EQ(ea.range_m, eb.range_m);
  EXPECT_EQ(ea.rate_mps, eb.rate_mps);
}

/// Issue 27: the rate std each estimate carries covers its error. Both observers on a range with
/// a bounded acceleration, 0.5 m of noise at 50 Hz, and a range jump (a new source) at 150 s.
template <class Observer>
void expect_reported_std_covers_the_error(Observer observer, const char* name) {
  RandomEngine engine(11);
  int valid = 0, outside = 0;
  double sum_sq_error = 0.0, sum_std = 0.0;
  for (int k = 0; k <= 300 * 50; ++k) {
    const double t = k / 50.0;
    const double jump_m = t >= 150.0 ? 40.0 : 0.0;
    const RangeRateEstimate est = observer.update(t, smooth_range(t) + jump_m + 0.5 * standard_normal(engine));
    if (k == 0) {
      EXPECT_DOUBLE_EQ(est.rate_std_mps, RateUncertaintyParams{}.initial_rate_std_mps) << name;
    }
    if (!est.valid) {
      continue;
    }
    const double error = est.rate_mps - smooth_rate(t);
    ++valid;
    outside += std::abs(error) > 3.0 * est.rate_std_mps ? 1 : 0;
    sum_sq_error += error * error;
    sum_std += est.rate_std_mps;
  }
  EXPECT_EQ(observer.restarts(), 1u) << name;
  EXPECT_LT(static_cast<double>(outside) / valid, 0.01) << name << ": " << outside << " of " << valid;
  // Not uselessly wide: the mean reported std within 3x the RMS error (the start's 2 m/s prior and
  // the check line's own spread make it larger than the error, by design).
  const double rms_error = std::sqrt(sum_sq_error / valid);
  EXPECT_LT(sum_std / valid, 3.0 * rms_error) << name << ": mean std " << sum_std / valid << ", rms error " << rms_error;
}

TEST(RangeRateObserver, TheReportedRateStdCoversTheError) {
  expect_reported_std_covers_the_error(SuperTwistingObserver{SuperTwistingParams{}}, "super-twisting");
  expect_reported_std_covers_the_error(LinearRangeRateObserver{LinearObserverParams{}}, "linear");
}

TEST(RangeRateObserver, InsideARestartWindowTheStdIsTheWindowSlopes) {
  // Noise-free ranges, the configured 0.5 m floor as the range sigma: the slope of n samples at
  // 50 Hz has std 0.5 / sqrt(sum (t - tm)^2); with a range acceleration bound its lag adds
  // bound x (t - tm).
  RateUncertaintyParams u;
  u.range_accel_mps2 = 1.0;
  SuperTwistingObserver observer{SuperTwistingParams{}, u};
  for (int k = 0; k < 100; ++k) {
    observer.update(k / 50.0, smooth_range(k / 50.0));
  }
  observer.restart();
  RangeRateEstimate est;
  for (int k = 100; k < 110; ++k) {
    est = observer.update(k / 50.0, smooth_range(k / 50.0));
  }
  ASSERT_FALSE(est.valid);
  double tm = 0.0, stt = 0.0;
  for (int i = 0; i < 10; ++i) {
    tm += i / 50.0 / 10.0;
  }
  for (int i = 0; i < 10; ++i) {
    stt += (i / 50.0 - tm) * (i / 50.0 - tm);
  }
  const double lag_term = 1.0 * (9 / 50.0 - tm);
  EXPECT_NEAR(est.rate_std_mps, std::sqrt(0.25 / stt + lag_term * lag_term), 1e-9);
}

TEST(RangeRateObserver, RejectsBadGainsAtConstruction) {
  SuperTwistingParams p;
  p.c = -1.0;
  EXPECT_THROW(SuperTwistingObserver{p}, std::invalid_argument);
  for (const double period_s : {-0.02, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(SuperTwistingObserver(SuperTwistingParams{}, {}, period_s), std::invalid_argument) << period_s;
  }
  EXPECT_NO_THROW(SuperTwistingObserver(SuperTwistingParams{}, {}, 0.0));
}

}  // namespace
}  // namespace robodds::range_rate_observer
