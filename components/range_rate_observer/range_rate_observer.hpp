#pragma once
// A range-rate observer fed by sampled ranges: one class for paper 2's two observers and the
// Kalman filter of issue 28. What they share is here (restarts on range jumps and target changes,
// the restart window, the online noise estimate, lost samples, the reported rate std); how the
// state moves from one sample to the next is the `Law`:
//   EulerLaw (below): the state (s_hat, v_hat) integrated with explicit Euler between samples, the
//     correction computed from the error at the previous sample; the right-hand side is paper 2's
//     super-twisting or linear observer (observer_laws.hpp);
//   KalmanLaw (kalman_law.hpp): range, rate and range acceleration, predicted and corrected.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include "common/number_text.hpp"
#include "components/range_rate_observer/kalman_law.hpp"
#include "components/range_rate_observer/observer_laws.hpp"
#include "components/range_rate_observer/rate_uncertainty.hpp"
#include "components/range_rate_observer/running_abs_median.hpp"

namespace robodds::range_rate_observer {

/// How an observer's state moves from one range sample to the next (see the file comment): a
/// class with `using Params` (validate(), restart_sigmas, noise_floor_m, restart_window_s),
/// `static constexpr bool kBridgesGaps` (whether lost samples are integrated period by period
/// against the curve between the ranges on either side, bent by the law's accel_mps2), and
///   explicit Law(const Params&);
///   void start(double range_m, double rate_mps, double rate_std_mps, double range_error_m);
///   void advance(double dt_s, double measured_range_m, double range_sigma_m);
///     (range_sigma_m: the online noise estimate, or the configured floor until it is trained)
///   double range_m() const;  double rate_mps() const;
///   double accel_mps2() const;            (the range acceleration the law's model carries)
///   LawPrediction predict(double dt_s) const;  (the state dt_s ahead without a range)
/// Paper 2's observers: eq. (1) and eq. (9) integrated with explicit Euler.
///
/// Their model of the range acceleration is v_hat' itself (b sgn(e) + c e; k2 e): in the sliding
/// mode the mean of b sgn(e) + c e is the true s'' (the "equivalent output injection" of sliding-mode
/// observers), so its low-pass over kAccelFilterS is the law's s'' estimate. It only serves to carry
/// the estimate across lost samples (predict); the observer itself is eq. (1) / (9) unchanged.
template <class P, ObserverDerivative (*Derivative)(const P&, double, double)>
class EulerLaw {
 public:
  using Params = P;
  static constexpr bool kBridgesGaps = true;

  /// s: time constant of the low-pass of v_hat' (accel_mps2): ~12 periods at 50 Hz, where the
  /// sliding mode's b sgn(e) alternates every period or two, and short against the seconds over
  /// which a robot's range acceleration changes (a turn at 0.15 rad/s).
  static constexpr double kAccelFilterS = 0.25;

  explicit EulerLaw(const Params& params) : params_(params) {}
  /// The state (s_hat, v_hat) and the range error e the next step corrects with; s'' unknown (0).
  void start(double range_m, double rate_mps, double /*rate_std_mps*/, double range_error_m) {
    range_m_ = range_m;
    rate_mps_ = rate_mps;
    error_m_ = range_error_m;
    accel_mps2_ = 0.0;
  }
  /// One Euler step of dt_s with the error at the previous sample, then the error against
  /// measured_range_m for the next step.
  void advance(double dt_s, double measured_range_m, double /*range_sigma_m*/) {
    const ObserverDerivative derivative = Derivative(params_, rate_mps_, error_m_);
    range_m_ += dt_s * derivative.range_mps;
    rate_mps_ += dt_s * derivative.rate_mps2;
    error_m_ = measured_range_m - range_m_;
    accel_mps2_ += (derivative.rate_mps2 - accel_mps2_) * (1.0 - std::exp(-dt_s / kAccelFilterS));
  }
  double range_m() const { return range_m_; }
  double rate_mps() const { return rate_mps_; }
  double accel_mps2() const { return accel_mps2_; }
  /// s_hat' = v_hat, v_hat' = accel_mps2() over dt_s: the state without a range to correct with.
  LawPrediction predict(double dt_s) const {
    return {range_m_ + dt_s * rate_mps_ + 0.5 * dt_s * dt_s * accel_mps2_, rate_mps_ + dt_s * accel_mps2_};
  }

 private:
  Params params_;
  double range_m_ = 0.0;  // s_hat
  double rate_mps_ = 0.0;  // v_hat
  double error_m_ = 0.0;   // s - s_hat at the last sample, m
  double accel_mps2_ = 0.0;  // low-passed v_hat', m/s^2
};

struct RangeRateEstimate {
  double time_s = 0.0;
  double range_m = 0.0;    // s_hat
  double rate_mps = 0.0;   // v_hat, the range-rate estimate (positive: the range grows)
  /// false while a restart window fills (see RangeRateObserver::update): do not use the
  /// estimate then.
  bool valid = true;
  /// m/s, the std of rate_mps's error (rate_uncertainty.hpp): measured while valid; inside a
  /// restart window the std of the window line's slope (the initial rate std with one sample).
  double rate_std_mps = 0.0;
};

template <class Law>
class RangeRateObserver {
 public:
  using Params = typename Law::Params;

  /// Throws std::invalid_argument (from Params::validate) for bad gains or uncertainty
  /// parameters, or a negative or non-finite sample_period_s.
  ///
  /// sample_period_s: the period the ranges are sampled at (s), for lost samples; 0: every step is
  /// one Euler step however long. A step longer than kGapRatio periods spans lost samples: it is
  /// integrated in steps of about one period (at most kMaxGapSteps), each correcting with the
  /// error against the curve between the last range and this one that bends with the law's range
  /// acceleration estimate (update()), as if the lost ranges had lain on it. One Euler step over
  /// the gap applied the last error's b sgn(e) for k periods and widened the sliding mode's
  /// chattering k-fold (issue 27, finding 6: 0.20-0.44 m/s instead of 0.10 at
  /// 10-30 % losses); correcting over one period and predicting the rest would leave it b (1 -
  /// losses) of rate correction per second, below the range accelerations it must follow.
  explicit RangeRateObserver(Params params, RateUncertaintyParams uncertainty = {}, double sample_period_s = 0.0)
      : params_(std::move(params)), law_(params_), uncertainty_(uncertainty), sample_period_s_(sample_period_s) {
    params_.validate();
    if (!(std::isfinite(sample_period_s) && sample_period_s >= 0.0)) {
      throw std::invalid_argument("range-rate observer: sample_period_s must be finite and >= 0 (got " +
                                  shortest_text(sample_period_s) + ")");
    }
  }

  /// Feeds the range measured at time_s (s, strictly increasing) and returns the estimate at
  /// time_s. The first sample starts the observer at (range, rate 0), valid at once: the
  /// convergence from an unknown rate is the observer's own transient (the paper's figures). A
  /// non-finite input or a time that does not advance throws std::invalid_argument and leaves the
  /// state unchanged.
  ///
  /// Restart: when the range moved between two samples by more than restart_threshold_m() beyond
  /// what the rate estimate explains, |(s_k - s_k-1) - v_hat dt| (a new target or range source),
  /// or after restart(), the observer opens a window at that sample. Measured differences, not
  /// s_hat, are compared, so the range error of a converging observer never triggers it, and a
  /// fast target at a coarse sample rate restarts once at most (while v_hat is still far off).
  /// The threshold is statistical: restart_sigmas times the step's spread, sqrt(2) range sigmas
  /// (two independent noisy ranges), the range sigma estimated online (noise_sigma_m()) and never
  /// below noise_floor_m. A fixed threshold in metres was crossed by noise alone (issue 27: 5 m
  /// restarted the observers ~30,000 times a run at 2 m of noise).
  ///
  /// Window: for restart_window_s the samples are collected; the estimate is `valid == false` and
  /// must not be used. Meanwhile it reports the least-squares line through the window's samples
  /// (range: the line at time_s; rate: its slope), and with one sample only that range and the
  /// rate held from before the restart. At the first sample at least restart_window_s after the
  /// window opened the observer restarts from that line (s_hat = the line at time_s, v_hat = its
  /// slope) and is valid again. One noisy difference would set v_hat off by sqrt(2) sigma / T
  /// (0.5 m at 50 Hz: ~35 m/s); the slope over N samples spanning W is off by about
  /// sigma sqrt(12 / N) / W (0.5 m, 26 samples over 0.5 s: ~0.7 m/s). A jump inside the window
  /// opens a new one.
  RangeRateEstimate update(double time_s, double range_m) {
    if (!std::isfinite(time_s) || !std::isfinite(range_m)) {
      throw std::invalid_argument("range-rate observer: non-finite input (time_s " + shortest_text(time_s) +
                                  ", range_m " + shortest_text(range_m) + ")");
    }
    if (!started_) {
      start_at(time_s, range_m, 0.0, uncertainty_.params().initial_rate_std_mps);
      restart_requested_ = false;
      return estimate_;
    }
    if (!(time_s > estimate_.time_s)) {
      throw std::invalid_argument("range-rate observer: time must advance (got " + shortest_text(time_s) + " s after " +
                                  shortest_text(estimate_.time_s) + " s)");
    }
    const double dt = time_s - estimate_.time_s;
    // One sample into a window there is no rate to predict with: the second one is not checked.
    const bool can_predict = !window_open_ || window_.count >= 2;
    const double unexplained_m = range_m - predicted_range(dt);
    const bool jumped = can_predict && params_.restart_sigmas > 0.0 && std::abs(unexplained_m) > restart_threshold_m();
    if (!window_open_) {
      // Every step predicted from v_hat feeds the noise estimate, a jump too (the median ignores
      // a minority of them; leaving out the steps above the threshold would let a threshold too
      // low for a sensor that became noisier never learn). Inside a window the prediction rests
      // on a line through a few samples and misses by more than the sensor's noise: left out.
      unexplained_steps_.add(unexplained_m);
    }
    if (restart_requested_ || jumped) {
      ++restarts_;
      restart_requested_ = false;
      open_window(time_s, range_m);
      return estimate_;
    }
    if (window_open_) {
      add_to_window(time_s, range_m);
      return estimate_;
    }
    // Lost samples: a step longer than kGapRatio sample periods spans them (see the constructor).
    const int substeps = Law::kBridgesGaps && sample_period_s_ > 0.0 && dt > kGapRatio * sample_period_s_
                             ? static_cast<int>(std::min(std::round(dt / sample_period_s_), static_cast<double>(kMaxGapSteps)))
                             : 1;
    const double h = dt / substeps;
    // The range noise a law may weigh samples by (the Kalman filter): the online estimate once it
    // rests on enough steps, before that never below the configured floor.
    const double range_sigma_m =
        noise_samples() < kMinNoiseSamples ? std::max(noise_sigma_m(), params_.noise_floor_m) : noise_sigma_m();
    // The lost ranges: the curve between the last range and this one that bends with the law's
    // range acceleration a (the law's prediction from the last range, corrected linearly to end at
    // this one): the line plus a tau (tau - dt) / 2, tau the time since the last range. The line
    // alone lies r'' tau (dt - tau) / 2 inside the true range (2.6 mm over 5 periods at 2.1 m/s^2),
    // several times the sliding mode's range error (~b T^2), and knocked it out of the sliding
    // mode where r'' is near b: v_hat fell b T per period behind and recovered at b - |r''| per s.
    const double accel_mps2 = law_.accel_mps2();
    for (int i = 1; i <= substeps; ++i) {
      const double tau = h * i;
      const double measured_m = i == substeps ? range_m
                                              : last_range_m_ + (range_m - last_range_m_) * i / substeps +
                                                    0.5 * accel_mps2 * tau * (tau - dt);
      law_.advance(h, measured_m, range_sigma_m);
    }
    estimate_.range_m = law_.range_m();
    estimate_.rate_mps = law_.rate_mps();
    estimate_.time_s = time_s;
    last_range_m_ = range_m;
    uncertainty_.add(time_s, range_m, estimate_.rate_mps);
    estimate_.rate_std_mps = uncertainty_.std_mps();
    return estimate_;
  }

  /// The estimate at time_s without a new range (a lost sample; issue 27, finding 6): the law's
  /// state carried from the last sample on its own model (LawPrediction: range and rate moved by
  /// the rate and the law's range acceleration; inside a restart window the window line), its std
  /// widened for the hold by the largest range acceleration times the time since the last sample,
  /// sqrt(std^2 + (range_accel_mps2 dt)^2): the rate error a hold of dt can add when the model's
  /// s'' is off by up to the bound. Republishing the last estimate instead held the range and rate
  /// while the truth moved (0.26 m per lost step at 13 m/s; 0.22 m/s of rate after 7 lost samples
  /// at r'' 1.6 m/s^2) and claimed the std of a fresh one. time_s at or before the last sample, or
  /// before the first: estimate(). Changes nothing.
  RangeRateEstimate predict(double time_s) const {
    if (!started_ || !(time_s > estimate_.time_s)) {
      return estimate_;
    }
    const double dt = time_s - estimate_.time_s;
    RangeRateEstimate held = estimate_;
    held.time_s = time_s;
    if (window_open_) {
      held.range_m = estimate_.range_m + dt * estimate_.rate_mps;
    } else {
      const LawPrediction moved = law_.predict(dt);
      held.range_m = moved.range_m;
      held.rate_mps = moved.rate_mps;
    }
    const double widening = uncertainty_.params().range_accel_mps2 * dt;
    held.rate_std_mps = std::sqrt(estimate_.rate_std_mps * estimate_.rate_std_mps + widening * widening);
    return held;
  }

  /// A new target or range source: the next sample opens a restart window (counted in
  /// restarts()), whatever its range. Before the first sample it does nothing.
  void restart() { restart_requested_ = started_; }

  bool started() const { return started_; }
  /// The estimate after the last sample (what update() returned).
  const RangeRateEstimate& estimate() const { return estimate_; }
  /// false while a restart window fills: the estimate must not be used.
  bool valid() const { return estimate_.valid; }
  /// How many times the observer restarted (a range jump above restart_threshold_m(), or restart()).
  std::size_t restarts() const { return restarts_; }
  /// The range noise (sigma, m) estimated online: the robust spread (running median of |step|,
  /// MAD scale) of the last kNoiseWindow range steps the rate estimate does not explain, divided by
  /// sqrt(2). Steps inside a restart window are left out; a minority of wild ones (jumps) cannot
  /// move it. 0 before the second sample. May be below noise_floor_m (the threshold uses the floor).
  double noise_sigma_m() const { return unexplained_steps_.sigma() / std::sqrt(2.0); }
  /// How many steps noise_sigma_m() rests on (at most kNoiseWindow).
  std::size_t noise_samples() const { return unexplained_steps_.count(); }
  /// A step the rate misses by more than this (m) restarts the observer (restart_sigmas > 0).
  double restart_threshold_m() const {
    const double sigma_m = std::max(noise_sigma_m(), params_.noise_floor_m);
    // Until the estimate rests on kMinNoiseSamples steps its median is too uncertain (+-30 % at
    // 16 steps) to set a restart threshold: the threshold is kUntrainedWidening times wider. A
    // sensor 4x noisier than its floor then does not restart the observer at start (2 m on a 0.5 m
    // floor: 14.8 m = 5.2 step sigmas), while a target switch (hundreds of m) still does.
    const double widening = noise_samples() < kMinNoiseSamples ? kUntrainedWidening : 1.0;
    return params_.restart_sigmas * std::sqrt(2.0) * sigma_m * widening;
  }
  const Params& params() const { return params_; }

 private:
  /// Starts (valid) from rate_mps, whose error has std rate_std_mps; range_error_m: the measured
  /// range minus range_m.
  void start_at(double time_s, double range_m, double rate_mps, double rate_std_mps, double range_error_m = 0.0) {
    uncertainty_.restart(rate_std_mps);
    uncertainty_.add(time_s, range_m, rate_mps);
    estimate_ = {time_s, range_m, rate_mps, true, uncertainty_.std_mps()};
    law_.start(range_m, rate_mps, rate_std_mps, range_error_m);
    last_range_m_ = range_m;
    window_open_ = false;
    started_ = true;
  }

  /// The range expected dt after the last sample: from the last measured range and v_hat, or
  /// inside a window (two samples or more) from its least-squares line.
  double predicted_range(double dt) const {
    if (window_open_) {
      return estimate_.range_m + estimate_.rate_mps * dt;
    }
    return last_range_m_ + estimate_.rate_mps * dt;
  }

  void open_window(double time_s, double range_m) {
    window_ = Window{};
    window_.t0_s = time_s;
    window_.r0_m = range_m;
    window_open_ = true;
    add_to_window(time_s, range_m);
  }

  /// Adds a sample to the window; updates the (invalid) estimate from the least-squares line,
  /// and restarts the observer from it once the window spans restart_window_s.
  void add_to_window(double time_s, double range_m) {
    Window& w = window_;
    const double t = time_s - w.t0_s;  // relative to the window's first sample, for conditioning
    const double r = range_m - w.r0_m;
    ++w.count;
    w.sum_t += t;
    w.sum_r += r;
    w.sum_tt += t * t;
    w.sum_tr += t * r;
    last_range_m_ = range_m;
    double line_range_m = range_m;
    double slope_mps = estimate_.rate_mps;  // one sample: the rate held from before the restart
    double slope_std_mps = uncertainty_.params().initial_rate_std_mps;
    if (w.count >= 2) {
      const double n = static_cast<double>(w.count);
      const double spread_s2 = w.sum_tt - w.sum_t * w.sum_t / n;  // sum (t - t_mean)^2
      slope_mps = (n * w.sum_tr - w.sum_t * w.sum_r) / (n * w.sum_tt - w.sum_t * w.sum_t);
      line_range_m = w.r0_m + (w.sum_r - slope_mps * w.sum_t) / n + slope_mps * t;
      // The slope's noise (range sigma: the estimate, never below the configured floor) and its
      // lag: it is the rate at the window's centre, t - mean t before the newest sample.
      const double sigma_m = std::max(noise_sigma_m(), params_.noise_floor_m);
      const double lag_s = t - w.sum_t / n;
      const double accel_term = uncertainty_.params().range_accel_mps2 * lag_s;
      slope_std_mps = std::sqrt(sigma_m * sigma_m / spread_s2 + accel_term * accel_term);
    }
    // 1e-9 s: a window of 0.5 s at 50 Hz must close at the 26th sample whatever the rounding.
    if (w.count >= 2 && t >= params_.restart_window_s - 1e-9) {
      start_at(time_s, line_range_m, slope_mps, slope_std_mps, range_m - line_range_m);
      last_range_m_ = range_m;
      return;
    }
    estimate_ = {time_s, line_range_m, slope_mps, false, slope_std_mps};
  }

  /// Least-squares sums of a restart window, times and ranges relative to its first sample.
  struct Window {
    double t0_s = 0.0;
    double r0_m = 0.0;
    std::size_t count = 0;
    double sum_t = 0.0;
    double sum_r = 0.0;
    double sum_tt = 0.0;
    double sum_tr = 0.0;
  };

  /// Steps in the noise estimate: 256 (5.1 s at 50 Hz). Its median's relative error would be ~7 %
  /// (1 sigma) for independent steps; adjacent steps share a range sample, and end-of-run snapshots
  /// in paper 2 scatter -16/+27 % (0.84-1.27 m at 1 m, 40 of them): 7 step sigmas stay above 5.9,
  /// a false restart per ~3e8 Gaussian steps.
  static constexpr std::size_t kNoiseWindow = 256;
  static constexpr std::size_t kMinNoiseSamples = 32;
  static constexpr double kUntrainedWidening = 3.0;
  /// A step longer than this many sample periods spans lost samples.
  static constexpr double kGapRatio = 1.5;
  /// Steps a gap is integrated in, at most (a longer gap: longer steps).
  static constexpr int kMaxGapSteps = 64;

  Params params_;
  Law law_;  // the state between samples (after params_: built from it)
  RateUncertainty uncertainty_;
  RunningAbsMedian unexplained_steps_{kNoiseWindow};
  RangeRateEstimate estimate_;
  double last_range_m_ = 0.0;  // the last measured range, m
  double sample_period_s_ = 0.0;  // s, 0: no gap handling
  Window window_;
  bool window_open_ = false;       // restarted: collecting the window, estimate not valid
  bool restart_requested_ = false;  // restart(): the next sample opens a window
  bool started_ = false;
  std::size_t restarts_ = 0;
};

using SuperTwistingObserver = RangeRateObserver<EulerLaw<SuperTwistingParams, &super_twisting_derivative>>;
using LinearRangeRateObserver = RangeRateObserver<EulerLaw<LinearObserverParams, &linear_derivative>>;
using KalmanRangeRateObserver = RangeRateObserver<KalmanLaw>;

}  // namespace robodds::range_rate_observer
