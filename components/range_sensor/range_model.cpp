#include "components/range_sensor/range_model.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::range_sensor {

double true_range(double x, double y, double target_x, double target_y) { return std::hypot(x - target_x, y - target_y); }

double measure_range(double truth_m, const RangeSensorParams& params, RandomEngine& engine) {
  return std::max(0.0, truth_m + params.noise_sigma_m * standard_normal(engine));
}

bool sample_lost(const RangeSensorParams& params, RandomEngine& engine) { return uniform01(engine) < params.dropout_probability; }

}  // namespace robodds::range_sensor
