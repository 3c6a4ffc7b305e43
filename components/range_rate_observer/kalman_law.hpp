#pragma once
// Issue 28, beyond the paper: a Kalman filter as the Law of a RangeRateObserver
// (range_rate_observer.hpp): state x = (range s, range rate v, range acceleration a), the range
// modelled as driven by white jerk of spectral density q (the constant-acceleration model):
//   x_k = F x_k-1 + w,  F = [1 dt dt^2/2; 0 1 dt; 0 0 1],
//   Q = q [dt^5/20 dt^4/8 dt^3/6; dt^4/8 dt^3/3 dt^2/2; dt^3/6 dt^2/2 dt],
// corrected by each range with variance sigma^2, sigma the observer's online noise estimate
// (the configured noise_floor_m until that estimate is trained, never below min_range_sigma_m): a
// sensor quieter than configured (the noise-free scenario) is trusted as it is. The acceleration state follows a manoeuvre without the lag of a
// two-state observer (the linear observer lags by k1 a / k2), while a small q keeps the steady
// noise floor low. Its own covariance is not what the observer reports: with one q for steady
// flight and manoeuvres it is too small in the manoeuvres (README.md "Kalman filter"); the
// observer's measured rate std (rate_uncertainty.hpp) is reported as for the other two.
// Pure: Eigen and std; ranges in m, times in s.

#include <algorithm>

#include <Eigen/Core>

#include "components/range_rate_observer/observer_laws.hpp"
#include "components/range_rate_observer/observer_params.hpp"

namespace robodds::range_rate_observer {

class KalmanLaw {
 public:
  using Params = KalmanObserverParams;
  /// A gap of lost samples is one longer prediction: the filter needs no made-up ranges.
  static constexpr bool kBridgesGaps = false;

  explicit KalmanLaw(const Params& params) : params_(params) {}

  /// (Re)starts at range_m and rate_mps (std rate_std_mps), acceleration 0 (std
  /// initial_accel_std_mps2), the range known to noise_floor_m.
  void start(double range_m, double rate_mps, double rate_std_mps, double /*range_error_m*/) {
    x_ << range_m, rate_mps, 0.0;
    P_.setZero();
    P_(0, 0) = params_.noise_floor_m * params_.noise_floor_m;
    P_(1, 1) = rate_std_mps * rate_std_mps;
    P_(2, 2) = params_.initial_accel_std_mps2 * params_.initial_accel_std_mps2;
  }

  /// Predicts dt_s ahead and corrects with measured_range_m of std range_sigma_m (never taken
  /// below min_range_sigma_m).
  void advance(double dt_s, double measured_range_m, double range_sigma_m) {
    const double sigma_m = std::max(range_sigma_m, params_.min_range_sigma_m);
    const double dt2 = dt_s * dt_s;
    const double dt3 = dt2 * dt_s;
    Eigen::Matrix3d F;
    F << 1.0, dt_s, 0.5 * dt2, 0.0, 1.0, dt_s, 0.0, 0.0, 1.0;
    Eigen::Matrix3d Q;
    Q << dt3 * dt2 / 20.0, dt2 * dt2 / 8.0, dt3 / 6.0,  //
        dt2 * dt2 / 8.0, dt3 / 3.0, dt2 / 2.0,          //
        dt3 / 6.0, dt2 / 2.0, dt_s;
    x_ = F * x_;
    P_ = F * P_ * F.transpose() + params_.jerk_psd_m2ps5 * Q;
    const double innovation_var = P_(0, 0) + sigma_m * sigma_m;
    const Eigen::Vector3d gain = P_.col(0) / innovation_var;
    x_ += gain * (measured_range_m - x_(0));
    P_ -= gain * gain.transpose() * innovation_var;  // (I - K H) P, kept symmetric
  }

  double range_m() const { return x_(0); }
  double rate_mps() const { return x_(1); }
  /// The range acceleration state (m/s^2).
  double accel_mps2() const { return x_(2); }
  /// The constant-acceleration model dt_s ahead (F x), no correction: a lost sample.
  LawPrediction predict(double dt_s) const {
    return {x_(0) + dt_s * x_(1) + 0.5 * dt_s * dt_s * x_(2), x_(1) + dt_s * x_(2)};
  }

 private:
  Params params_;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Zero();
};

}  // namespace robodds::range_rate_observer
