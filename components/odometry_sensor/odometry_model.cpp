#include "components/odometry_sensor/odometry_model.hpp"

#include "common/model/actuator.hpp"
#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::odometry_sensor {

void advance_slip_wander(SlipWander& wander, double dt_s, const OdometryParams& params, RandomEngine& engine) {
  const double sigma = params.slip_wander_sigma;
  if (sigma == 0.0) {
    return;
  }
  // Named locals fix the draw order (left, then right).
  const double unit_left = standard_normal(engine);
  const double unit_right = standard_normal(engine);
  if (!wander.started) {
    wander = SlipWander{sigma * unit_left, sigma * unit_right, true};
    return;
  }
  wander.left = gauss_markov_step(wander.left, dt_s, params.slip_wander_tau_s, sigma, unit_left);
  wander.right = gauss_markov_step(wander.right, dt_s, params.slip_wander_tau_s, sigma, unit_right);
}

OdometryReading measure_odometry(const model::Twist& true_twist, double dt_s, double wheel_base_m,
                                 const OdometryParams& params, RandomEngine& engine,
                                 const SlipWander& wander) {
  const model::WheelSpeeds truth = model::wheel_speeds_from_twist(true_twist, wheel_base_m);
  // Named locals fix the draw order (left, then right) regardless of argument evaluation order.
  const double unit_noise_left = standard_normal(engine);
  const double unit_noise_right = standard_normal(engine);
  const double std_mps = params.wheel_speed_noise_std_mps;
  const double measured_left = (1.0 + params.left_slip + wander.left) * truth.left + std_mps * unit_noise_left;
  const double measured_right =
      (1.0 + params.right_slip + wander.right) * truth.right + std_mps * unit_noise_right;

  const model::Twist measured =
      model::twist_from_wheel_speeds(measured_left, measured_right, wheel_base_m);
  // v = (l + r)/2 and omega = (r - l)/D of two independent wheel errors of variance std^2.
  const double wheel_var = std_mps * std_mps;
  OdometryReading reading;
  reading.v = measured.v;
  reading.omega = measured.omega + params.turn_rate_bias_radps;
  reading.dt_s = dt_s;
  reading.var_v = 0.5 * wheel_var;
  reading.var_omega = 2.0 * wheel_var / (wheel_base_m * wheel_base_m);
  return reading;
}

}  // namespace robodds::odometry_sensor
