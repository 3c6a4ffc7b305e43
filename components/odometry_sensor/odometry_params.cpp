#include "components/odometry_sensor/odometry_params.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace robodds::odometry_sensor {
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

// Comparisons are written so that NaN fails them.

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

void require_slip_range(const char* key, double value) {
  if (!(value > -0.5 && value < 0.5)) {
    reject(key, "must be in (-0.5, 0.5)", value);
  }
}

}  // namespace

void OdometryParams::validate() const {
  require_positive_finite("rate_hz", rate_hz);
  require_positive_finite("wheel_base_m", wheel_base_m);
  require_non_negative_finite("wheel_speed_noise_std_mps", wheel_speed_noise_std_mps);
  require_slip_range("left_slip", left_slip);
  require_slip_range("right_slip", right_slip);
}

}  // namespace robodds::odometry_sensor
