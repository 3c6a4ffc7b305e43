#pragma once
// The observer study of issue 10 ("Beyond the paper"): lag against noise floor of the
// super-twisting observer (eq. 1), of the linear baseline (eq. 9) over a range of linear gains and
// of issue 28's Kalman filter (kalman_law.hpp) over a range of jerk densities q, at several sample
// rates and range-noise levels, over seeds. Pure, std only; main.cpp prints the
// CSV and scripts/paper2_observer_study.sh draws it.
//
// For each (signal, sample rate, noise sigma, observer) and each seed, three RMS rate errors over
// the steady state (t >= steady_from_s):
//   LAG   the signal without noise (the observer's tracking error: linear lag, sliding-mode
//         chattering);
//   NOISE a constant range with noise sigma (the pure noise response, the "noise floor");
//   TOTAL the signal with noise sigma.
// For the linear observer TOTAL^2 = LAG^2 + NOISE^2 (superposition). The super-twisting one is
// not linear: under noise it loses the sliding mode and lags (TOTAL_BIAS on the accel signal).

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "components/range_rate_observer/observer_params.hpp"
#include "common/sample_stats.hpp"

namespace robodds::range_rate_observer::study {

enum class SignalKind {
  /// s = 300 + 60 sin(0.15 t + phase) m: a robot at ~9 m/s turning at the plant's 0.15 rad/s
  /// limit around a point off the target; peak rate 9 m/s, peak |s''| 1.35 m/s^2 (< b = 2.2).
  kOrbit,
  /// s = 300 - 8 t + t^2 / 2 m: an approach at 8 m/s under a constant 1 m/s^2 range acceleration
  /// (the linear observer's lag is then k1 a / k2 = 2 a / w).
  kConstantAcceleration,
  /// s = 300 m: the noise response alone.
  kConstant,
};

/// "orbit", "accel", "constant".
const char* signal_name(SignalKind kind);

/// A range signal s(t) (m) and its exact rate s'(t) (m/s).
struct RangeSignal {
  SignalKind kind = SignalKind::kConstant;
  double phase_rad = 0.0;  // kOrbit only

  double range_m(double t_s) const;
  double rate_mps(double t_s) const;
};

enum class ObserverKind {
  kSuperTwisting,  // eq. (1), SuperTwistingObserver
  kLinear,         // eq. (9), LinearRangeRateObserver
  kKalman,         // issue 28, KalmanRangeRateObserver
};

/// "sta", "linear", "kf" (the CSV's observer column).
const char* observer_name(ObserverKind kind);

/// One observer of the study, restarts disabled (restart_sigmas = 0: noise must not restart it).
/// Only the params of `kind` are used.
struct ObserverConfig {
  ObserverKind kind = ObserverKind::kSuperTwisting;
  /// Linear only: k1 = 2 w, k2 = w^2 (critically damped, both poles at -w).
  double w_radps = 0.0;
  SuperTwistingParams sta;
  LinearObserverParams linear;
  /// Kalman only: its gain is the jerk density kalman.jerk_psd_m2ps5 (q); the rest the defaults.
  KalmanObserverParams kalman;
};

/// The super-twisting defaults (a 2.12, b 2.2, c 1, d 1).
ObserverConfig super_twisting_config();
/// The linear observer with k1 = 2 w, k2 = w^2.
ObserverConfig linear_config(double w_radps);
/// The Kalman filter with jerk density q (m^2/s^5), its other parameters the defaults.
ObserverConfig kalman_config(double q_m2ps5);

struct RunSpec {
  double rate_hz = 50.0;
  double duration_s = 200.0;
  double steady_from_s = 20.0;
  double sigma_m = 0.0;
  std::uint64_t noise_seed = 0;
};

struct RunResult {
  double rms_error_mps = 0.0;   // RMS of the rate error over t >= steady_from_s
  double mean_error_mps = 0.0;  // signed mean of the rate error over t >= steady_from_s
  /// Restarts of a copy of the observer with the default restart rule (restart_sigmas 7, floor 0.5 m) fed the same
  /// samples: how often noise alone would restart it.
  std::size_t restarts_at_default_jump = 0;
};

/// Samples signal + sigma N(0, 1) (RandomEngine(noise_seed)) at rate_hz from t = 0 to duration_s
/// and feeds the observer, which starts at (first range, rate 0).
RunResult run_observer(const ObserverConfig& observer, const RangeSignal& signal, const RunSpec& spec);

struct StudyOptions {
  std::size_t seeds = 20;
  double duration_s = 200.0;
  double steady_from_s = 20.0;
  std::vector<SignalKind> signals = {SignalKind::kOrbit, SignalKind::kConstantAcceleration};
  std::vector<double> rates_hz = {10.0, 50.0, 100.0};
  std::vector<double> sigmas_m = {0.0, 0.1, 0.5, 1.0};
  std::vector<double> linear_w_radps = {0.5, 1.0, 1.5, 2.6, 4.0, 6.0, 9.0};
  /// The Kalman filter's jerk densities q (m^2/s^5); 0.001 is the library default.
  std::vector<double> kalman_q_m2ps5 = {1e-4, 1e-3, 1e-2, 1e-1};
};

/// One row of the table: mean and 95 % CI over seeds.
struct StudyRow {
  SignalKind signal = SignalKind::kOrbit;
  double rate_hz = 0.0;
  double sigma_m = 0.0;
  ObserverConfig observer;
  std::size_t seeds = 0;
  stats::SampleSummary lag_mps;    // noise-free signal (the orbit's phase is drawn per seed)
  stats::SampleSummary noise_mps;  // constant range, noise sigma
  stats::SampleSummary total_mps;  // signal, noise sigma
  /// Signed mean rate error of the TOTAL runs, mean over seeds: a bias (lag) under noise; ~0 on
  /// the orbit, whose acceleration changes sign.
  double total_bias_mps = 0.0;
  double restarts_per_run = 0.0;  // of the TOTAL runs, at the default restart rule
};

/// Rows ordered signal, rate, sigma, observer (super-twisting first, then the linear gains, then
/// the Kalman filter's q).
/// Seed i (1..seeds) draws the orbit phase and the noise from derive_seed(i, name): every
/// observer sees the same samples (common random numbers). Throws std::invalid_argument for
/// seeds < 1 or steady_from_s >= duration_s.
std::vector<StudyRow> run_study(const StudyOptions& options);

/// Header + one line per row; numbers with 5 significant digits, w/k1/k2 empty but for the
/// linear observer, q_m2ps5 empty but for the Kalman filter.
void write_csv(std::ostream& out, const std::vector<StudyRow>& rows);

}  // namespace robodds::range_rate_observer::study
