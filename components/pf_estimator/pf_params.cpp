#include "components/pf_estimator/pf_params.hpp"

#include <stdexcept>
#include <string>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::pf {
namespace {

using param_checks::reject;
using param_checks::require_finite;
using param_checks::require_non_negative;
using param_checks::require_positive;

void require_ordered(std::string_view min_key, double min_value, std::string_view max_key,
                     double max_value) {
  require_finite(min_key, min_value);
  require_finite(max_key, max_value);
  if (!(max_value > min_value)) {
    reject(max_key, "must be > " + std::string(min_key) + " = " + shortest_text(min_value), max_value);
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
  param_checks::require_at_least("num_particles", num_particles, 1);
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
