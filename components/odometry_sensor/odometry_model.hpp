#pragma once
// Measurement model of wheel odometry: the true body twist is split into wheel rim speeds, each
// wheel's speed gets its scale error (slip: a constant plus an optional Gauss-Markov wander) and
// independent white Gaussian noise, and the result is turned back into a body twist; a constant
// turn-rate bias (gyro-like) is added last.

#include "common/model/twist.hpp"
#include "common/random.hpp"
#include "components/odometry_sensor/odometry_params.hpp"

namespace robodds::odometry_sensor {

/// One odometry reading: the measured body twist over the last dt_s seconds.
struct OdometryReading {
  double v = 0.0;          // m/s, measured forward speed
  double omega = 0.0;      // rad/s, measured turn rate (counter-clockwise positive)
  double dt_s = 0.0;       // s, interval the reading covers (passed through)
  double var_v = 0.0;      // (m/s)^2, claimed variance of v from the white noise: std^2 / 2
  double var_omega = 0.0;  // (rad/s)^2, claimed variance of omega: 2 std^2 / D^2
};

/// The wandering part of each wheel's slip (dimensionless), carried from reading to reading.
struct SlipWander {
  double left = 0.0;
  double right = 0.0;
  bool started = false;  // false until the first advance draws the stationary start
};

/// Moves `wander` over the dt_s seconds a reading covers. Off (slip_wander_sigma = 0): leaves it at
/// zero and draws nothing. On: the first call draws the stationary start (two normals, left then
/// right), every later call one exact Gauss-Markov step (two normals, left then right).
void advance_slip_wander(SlipWander& wander, double dt_s, const OdometryParams& params, RandomEngine& engine);

/// Samples one reading of `true_twist` of a robot whose wheels are wheel_base_m (m, > 0) apart (its
/// body, a shared fact of the scenario); each wheel reads (1 + slip + wander) x its true speed. The claimed variances describe the white wheel noise
/// only (v and omega errors from it are uncorrelated); the slip and turn-rate biases are deliberately
/// not included, as a real odometry does not know its own calibration error. Always draws exactly
/// two standard normals from `engine` (left wheel first, then right). `params` must have
/// passed validate().
OdometryReading measure_odometry(const model::Twist& true_twist, double dt_s, double wheel_base_m,
                                 const OdometryParams& params, RandomEngine& engine,
                                 const SlipWander& wander = {});

}  // namespace robodds::odometry_sensor
