#pragma once
// The circumnavigation guidance law of issue 10 (paper 2 gives none; README.md has the law, its
// derivation and how we chose it). Inputs: the observed range r_hat and range rate v_hat to the
// target, the orbit radius R of the mission, the angular gaps to the team mates. Output: a
// unicycle command (v, omega) for a counter-clockwise orbit. Pure: std only, time in seconds.

#include <string_view>

#include "common/model/twist.hpp"
#include "components/circumnavigation_controller/formation_gaps.hpp"
#include "components/circumnavigation_controller/guidance_params.hpp"

namespace robodds::circumnavigation_controller {

/// value clamped to [-limit, limit] (limit >= 0).
double saturate(double value, double limit);

/// rdot_des = -approach_gain V sat_1((r_hat - R) / approach_width): approach (< 0) when too far,
/// recede when too close, 0 on the orbit.
double desired_range_rate(double range_m, double radius_m, double speed_mps, const GuidanceParams& params);

/// omega = sat_{max_turn}(V / R + heading_gain (v_hat - rdot_des)): the orbit's turn rate V / R
/// plus a correction that turns towards the target (left) while the range grows faster than
/// desired.
double turn_rate(double range_rate_mps, double desired_range_rate_mps, double speed_mps, double radius_m,
                 const GuidanceParams& params);

/// The speed the spacing asks for: V0 (1 + sat_{spacing_saturation}(spacing_gain (g+ - g-) / (2 pi / n)));
/// V0 for a robot alone (n = 1).
double spacing_speed(const Gaps& gaps, const GuidanceParams& params);

/// `target` moved towards from `previous` by at most max_change (>= 0).
double rate_limited(double previous, double target, double max_change);

/// Throws std::invalid_argument("desired_radius: must be > 0 and finite (got ...)") unless it is;
/// the radius comes with the mission, so its check is not part of GuidanceParams::validate().
void check_radius(double radius_m);

/// The observer bound of issue 10: v_max omega_max <= b, where b is the super-twisting gain that
/// must exceed the largest range acceleration and v omega is its dominant term (README.md,
/// "Observer bound"; the "1.3 V omega_max" is this with v_max = (1 + 0.3) V0). Throws
/// std::invalid_argument naming the keys (max_turn_rate_radps, cruise_speed_mps,
/// spacing_saturation and b_key), the numbers, and what to change, if it fails.
void check_observer_bound(double v_max_mps, double omega_max_radps, double b_mps2, std::string_view b_key = "sta.b");

/// The same for the law's own limits: v_max = max_commanded_speed(params),
/// omega_max = params.max_turn_rate_radps.
void check_observer_bound(const GuidanceParams& params, double b_mps2, std::string_view b_key = "sta.b");

/// The law with its one state, the rate-limited speed of one robot.
class GuidanceLaw {
 public:
  /// Validates params (throws std::invalid_argument "key: ...").
  explicit GuidanceLaw(const GuidanceParams& params);

  /// One control step of dt_s seconds (> 0): the speed moves towards spacing_speed(gaps) by at
  /// most max_accel dt (from V0 after construction with start_cruising, else and after reset() from 0), then omega follows
  /// from the range, the range rate and that speed. Throws std::invalid_argument for a bad radius
  /// or dt, or non-finite range / range rate (state unchanged).
  model::Twist step(double range_m, double range_rate_mps, double radius_m, const Gaps& gaps, double dt_s);

  /// Back to speed 0: the robot was stopped (zero commands) and starts from rest again.
  void reset();
  /// The robot moves at speed_mps without the law (held through a gap of the estimate,
  /// common/model/estimate_gap_hold.hpp): the next step rate-limits from it.
  void continue_from(double speed_mps) { speed_mps_ = speed_mps; }

  double speed_mps() const { return speed_mps_; }
  const GuidanceParams& params() const { return params_; }

 private:
  GuidanceParams params_;
  double speed_mps_;
};

}  // namespace robodds::circumnavigation_controller
