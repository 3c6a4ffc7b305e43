#include "components/circumnavigation_controller/guidance_law.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::circumnavigation_controller {

double saturate(double value, double limit) { return std::clamp(value, -limit, limit); }

double desired_range_rate(double range_m, double radius_m, double speed_mps, const GuidanceParams& params) {
  return -params.approach_gain * speed_mps * saturate((range_m - radius_m) / params.approach_width_m, 1.0);
}

double turn_rate(double range_rate_mps, double desired_range_rate_mps, double speed_mps, double radius_m,
                 const GuidanceParams& params) {
  return saturate(speed_mps / radius_m + params.heading_gain * (range_rate_mps - desired_range_rate_mps),
                  params.max_turn_rate_radps);
}

double spacing_speed(const Gaps& gaps, const GuidanceParams& params) {
  if (gaps.team_count <= 1) {
    return params.cruise_speed_mps;
  }
  const double even_gap = 2.0 * kPi / gaps.team_count;
  const double imbalance = params.spacing_gain * (gaps.ahead_rad - gaps.behind_rad) / even_gap;
  return params.cruise_speed_mps * (1.0 + saturate(imbalance, params.spacing_saturation));
}

double rate_limited(double previous, double target, double max_change) {
  return previous + saturate(target - previous, max_change);
}

void check_radius(double radius_m) { param_checks::require_positive("desired_radius", radius_m); }

void check_observer_bound(double v_max_mps, double omega_max_radps, double b_mps2, std::string_view b_key) {
  const double demand = v_max_mps * omega_max_radps;
  if (demand <= b_mps2) {
    return;
  }
  std::string message = "max_turn_rate_radps, cruise_speed_mps, spacing_saturation: the observer bound"
                        " V_max omega_max <= " + std::string(b_key) + " fails: " +
                        shortest_text(v_max_mps) + " m/s x " + shortest_text(omega_max_radps) +
                        " rad/s = " + shortest_text(demand) + " m/s^2 > " + std::string(b_key) + " = " +
                        shortest_text(b_mps2) +
                        " m/s^2 (V_max = cruise_speed_mps (1 + spacing_saturation); the observer is no longer exact "
                        "when the range acceleration exceeds its b). Lower max_turn_rate_radps to <= " +
                        shortest_text(b_mps2 / v_max_mps) + " or V_max to <= " +
                        shortest_text(b_mps2 / omega_max_radps) + " m/s, or raise " +
                        std::string(b_key) + " to >= " + shortest_text(demand);
  throw std::invalid_argument(message);
}

void check_observer_bound(const GuidanceParams& params, double b_mps2, std::string_view b_key) {
  check_observer_bound(max_commanded_speed(params), params.max_turn_rate_radps, b_mps2, b_key);
}

GuidanceLaw::GuidanceLaw(const GuidanceParams& params) : params_(params), speed_mps_(params.start_cruising ? params.cruise_speed_mps : 0.0) {
  params_.validate();
}

model::Twist GuidanceLaw::step(double range_m, double range_rate_mps, double radius_m, const Gaps& gaps,
                               double dt_s) {
  check_radius(radius_m);
  param_checks::require_positive("dt", dt_s);
  param_checks::require_finite("range", range_m);
  param_checks::require_finite("range_rate", range_rate_mps);
  speed_mps_ = rate_limited(speed_mps_, spacing_speed(gaps, params_), params_.max_accel_mps2 * dt_s);
  const double rdot_des = desired_range_rate(range_m, radius_m, speed_mps_, params_);
  return model::Twist{speed_mps_, turn_rate(range_rate_mps, rdot_des, speed_mps_, radius_m, params_)};
}

void GuidanceLaw::reset() { speed_mps_ = 0.0; }

}  // namespace robodds::circumnavigation_controller
