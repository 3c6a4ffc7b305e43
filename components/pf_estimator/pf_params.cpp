#include "components/pf_estimator/pf_params.hpp"

#include <sstream>
#include <stdexcept>

namespace robodds::pf {
namespace {

// Formats "key: requirement (got value)"; the key comes first so callers can map the error
// back to the YAML line.
[[noreturn]] void reject(std::string_view key, std::string_view requirement, double got) {
  std::ostringstream message;
  message << key << ": " << requirement << " (got " << got << ")";
  throw std::invalid_argument(message.str());
}

void require_finite(std::string_view key, double value) {
  if (!std::isfinite(value)) {
    reject(key, "must be finite", value);
  }
}

void require_positive(std::string_view key, double value) {
  require_finite(key, value);
  if (!(value > 0.0)) {
    reject(key, "must be > 0", value);
  }
}

void require_non_negative(std::string_view key, double value) {
  require_finite(key, value);
  if (!(value >= 0.0)) {
    reject(key, "must be >= 0", value);
  }
}

void require_ordered(std::string_view min_key, double min_value, std::string_view max_key,
                     double max_value) {
  require_finite(min_key, min_value);
  require_finite(max_key, max_value);
  if (!(max_value > min_value)) {
    std::ostringstream requirement;
    requirement << "must be > " << min_key << " = " << min_value;
    reject(max_key, requirement.str(), max_value);
  }
}

}  // namespace

ResamplingScheme resampling_scheme_from_string(std::string_view text) {
  if (text == "systematic") {
    return ResamplingScheme::kSystematic;
  }
  if (text == "residual") {
    return ResamplingScheme::kResidual;
  }
  throw std::invalid_argument("resampling: must be \"systematic\" or \"residual\" (got \"" +
                              std::string(text) + "\")");
}

std::string to_string(ResamplingScheme scheme) {
  return scheme == ResamplingScheme::kResidual ? "residual" : "systematic";
}

InitMode init_mode_from_string(std::string_view text) {
  if (text == "uniform_area") {
    return InitMode::kUniformArea;
  }
  if (text == "first_fix") {
    return InitMode::kFirstFix;
  }
  throw std::invalid_argument("init_mode: must be \"uniform_area\" or \"first_fix\" (got \"" +
                              std::string(text) + "\")");
}

std::string to_string(InitMode mode) {
  return mode == InitMode::kFirstFix ? "first_fix" : "uniform_area";
}

void PfParams::validate() const {
  if (num_particles < 1) {
    reject("num_particles", "must be >= 1", num_particles);
  }
  require_finite("resample_threshold", resample_threshold);
  if (!(resample_threshold > 0.0) || resample_threshold > num_particles) {
    reject("resample_threshold", "must be in (0, num_particles]", resample_threshold);
  }
  if (resampling != ResamplingScheme::kSystematic && resampling != ResamplingScheme::kResidual) {
    reject("resampling", "must be systematic or residual", static_cast<int>(resampling));
  }
  require_positive("measurement_std_m", measurement_std_m);
  require_non_negative("odom_v_std_mps", odom_v_std_mps);
  require_non_negative("odom_omega_std_radps", odom_omega_std_radps);
  require_non_negative("process_pos_std_m", process_pos_std_m);
  require_non_negative("process_theta_std_rad", process_theta_std_rad);
  require_non_negative("regularization_scale", regularization_scale);
  if (init_mode != InitMode::kUniformArea && init_mode != InitMode::kFirstFix) {
    reject("init_mode", "must be uniform_area or first_fix", static_cast<int>(init_mode));
  }
  // The area and the fix spread are checked whatever the mode, so a config stays valid when
  // only init_mode is switched.
  require_ordered("init_area_min_x", init_area_min_x, "init_area_max_x", init_area_max_x);
  require_ordered("init_area_min_y", init_area_min_y, "init_area_max_y", init_area_max_y);
  require_finite("init_theta_rad", init_theta_rad);
  require_positive("init_fix_std_m", init_fix_std_m);
}

}  // namespace robodds::pf
