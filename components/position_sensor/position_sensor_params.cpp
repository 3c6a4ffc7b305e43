#include "components/position_sensor/position_sensor_params.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robodds::position_sensor {
namespace {

/// Shortest text that reads back as the same double ("-1", "0.5", "nan", "inf").
std::string format_value(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void reject(const char* key, const char* reason, double value) {
  throw std::invalid_argument(std::string(key) + ": " + reason + " (got " + format_value(value) +
                              ")");
}

void require_positive_finite(const char* key, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    reject(key, "must be > 0 and finite", value);
  }
}

void require_non_negative_finite(const char* key, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    reject(key, "must be >= 0 and finite", value);
  }
}

}  // namespace

void PositionSensorParams::validate() const {
  require_positive_finite("rate_hz", rate_hz);
  require_non_negative_finite("noise_var_x_m2", noise_var_x_m2);
  require_non_negative_finite("noise_var_y_m2", noise_var_y_m2);
}

}  // namespace robodds::position_sensor
