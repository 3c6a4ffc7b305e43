#include "components/odometry_sensor/odometry_params.hpp"


namespace robodds::odometry_sensor {

const params::ParamTable<OdometryParams>& odometry_sensor_param_table() {
  static const params::ParamTable<OdometryParams> table =
      params::ParamTable<OdometryParams>(
          "Wheel odometry: mean wheel rim speeds over each interval (what encoders count), with a\n"
          "per-wheel scale error (slip, constant plus an optional Gauss-Markov wander) and white noise, converted to v and omega, plus an optional turn-rate bias.")
          .add("rate_hz", &OdometryParams::rate_hz, "Hz", params::positive(), "readings per second; must divide the simulation rate")
          .add("wheel_speed_noise_std_mps", &OdometryParams::wheel_speed_noise_std_mps, "m/s", params::non_negative(),
               "white noise on each wheel's measured speed")
          .add("left_slip", &OdometryParams::left_slip, "fraction", params::in_open_interval(-0.5, 0.5),
               "the left wheel reads (1 + slip) x its true speed")
          .add("right_slip", &OdometryParams::right_slip, "fraction", params::in_open_interval(-0.5, 0.5),
               "the right wheel reads (1 + slip) x its true speed")
          .add("slip_wander_sigma", &OdometryParams::slip_wander_sigma, "fraction", params::in_half_open_interval(0.0, 0.5),
               "stationary std of a Gauss-Markov part of each wheel's slip (uneven floor); 0 = off")
          .add("slip_wander_tau_s", &OdometryParams::slip_wander_tau_s, "s", params::positive(),
               "correlation time of the wandering slip")
          .add("turn_rate_bias_radps", &OdometryParams::turn_rate_bias_radps, "rad/s", params::finite(),
               "constant error added to the measured turn rate (gyro-like bias; counter-clockwise positive)");
  return table;
}

void OdometryParams::validate() const { odometry_sensor_param_table().check_ranges(*this); }

}  // namespace robodds::odometry_sensor
