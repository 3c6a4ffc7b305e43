#include "components/position_sensor/position_model.hpp"

#include <cmath>

namespace robodds::position_sensor {

PositionFix measure_position(const model::Pose2& truth, const PositionSensorParams& params,
                             RandomEngine& engine) {
  // Draw into named locals: the order of evaluation of function arguments is unspecified,
  // and a fixed x-then-y order keeps the output reproducible across compilers.
  const double unit_noise_x = standard_normal(engine);
  const double unit_noise_y = standard_normal(engine);
  PositionFix fix;
  fix.x = truth.x + std::sqrt(params.noise_var_x_m2) * unit_noise_x;
  fix.y = truth.y + std::sqrt(params.noise_var_y_m2) * unit_noise_y;
  // The outlier draw comes after the noise and only when outliers are on, so a configuration
  // without them keeps the stream (and every output) of the sensor without the feature.
  if (params.outlier_probability > 0.0 && uniform01(engine) < params.outlier_probability) {
    fix.x += params.outlier_offset_m;
  }
  fix.var_x = params.noise_var_x_m2;
  fix.var_y = params.noise_var_y_m2;
  return fix;
}

}  // namespace robodds::position_sensor
