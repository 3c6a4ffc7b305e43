#include "components/range_sensor/range_sensor_params.hpp"

namespace robodds::range_sensor {

const params::ParamTable<RangeSensorParams>& range_sensor_param_table() {
  using P = RangeSensorParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "Range sensor (paper 2): the distance from each robot to its assigned target (mission/target)\n"
          "plus seeded Gaussian noise, clamped at 0; optional independent dropouts.")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "sampling rate; must divide the simulation rate")
          .add("noise_sigma_m", &P::noise_sigma_m, "m", params::non_negative(), "standard deviation of the range noise")
          .add("dropout_probability", &P::dropout_probability, "", params::in_half_open_interval(0.0, 1.0),
               "probability that a sample is lost (0 = never)");
  return table;
}

void RangeSensorParams::validate() const { range_sensor_param_table().check_ranges(*this); }

}  // namespace robodds::range_sensor
