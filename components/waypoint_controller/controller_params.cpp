#include "components/waypoint_controller/controller_params.hpp"

#include <cmath>
#include <string>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::waypoint_controller {
namespace {

std::string format_gains(const GainSet& gains) {
  return "kd=" + shortest_text(gains.kd) + ", ka=" + shortest_text(gains.ka) + ", ksigma=" + shortest_text(gains.ksigma);
}

/// Throws "key: violates <inequality> (got <gains>)" unless holds.
void require_inequality(bool holds, const char* key, const char* inequality, const GainSet& gains) {
  if (!holds) {
    param_checks::reject(key, std::string("violates ") + inequality, format_gains(gains));
  }
}

/// Forward set, sgn* = +1: eq. (11) and the first line of eq. (16) as printed (with the OCR'd
/// second "ksigma" read as ka, as the derivation of eq. (17) requires).
void check_forward_gains(const GainSet& g) {
  constexpr const char* kKey = "forward_gains";
  constexpr double sgn = 1.0;
  require_inequality(g.kd > 0.0, kKey, "eq. (11) kd > 0 (the forward set must drive towards the way-point)", g);
  require_inequality(sgn * g.ksigma < 0.0, kKey, "eq. (11) sgn*·ksigma < 0 (sgn* = +1)", g);
  require_inequality(sgn * g.ksigma + g.ka - g.kd > 0.0, kKey, "eq. (11) sgn*·ksigma + ka - kd > 0 (sgn* = +1)", g);
  require_inequality(2.0 * sgn * g.ksigma + g.ka - (2.0 / kPi) * g.kd > 0.0, kKey,
                     "eq. (16) 2·sgn*·ksigma + ka - (2/pi)·kd > 0 (sgn* = +1; keeps |alpha| <= pi/2, eq. 17)", g);
}

/// Backward set, sgn* = -1, read as explained in README.md: the sign conditions of eq. (11)
/// are applied to the products the proof uses, the bracket of dV1/dt must stay positive for
/// every sin(alpha)/alpha in [0, 1], and eq. (16) is replaced by what eq. (18) needs.
void check_backward_gains(const GainSet& g) {
  constexpr const char* kKey = "backward_gains";
  constexpr double sgn = -1.0;
  require_inequality(g.kd < 0.0, kKey,
                     "eq. (11) read for the backward set: kd < 0 (the robot backs up, v = kd·d)", g);
  require_inequality(sgn * g.ksigma * g.kd < 0.0, kKey,
                     "eq. (11) read for the backward set: sgn*·ksigma·kd < 0 (sgn* = -1; V1 >= 0 and "
                     "lambda2·lambda3 > 0)",
                     g);
  require_inequality(sgn * g.ksigma + g.ka - g.kd > 0.0, kKey, "eq. (11) sgn*·ksigma + ka - kd > 0 (sgn* = -1)", g);
  require_inequality(sgn * g.ksigma + g.ka > 0.0, kKey,
                     "eq. (11) read for the backward set: sgn*·ksigma + ka > 0 (sgn* = -1; with kd < 0 the "
                     "bracket of dV1/dt is smallest at sin(alpha)/alpha -> 0)",
                     g);
  require_inequality(g.ka - 2.0 * std::abs(g.ksigma) - (2.0 / kPi) * g.kd > 0.0, kKey,
                     "eq. (16) read for the backward set: ka - 2·|ksigma| - (2/pi)·kd > 0 (dalpha/dt < 0 just "
                     "beyond alpha = pi/2 for every sigma, eq. 18)",
                     g);
  require_inequality(g.ka - std::abs(g.ksigma) > 0.0, kKey,
                     "eq. (18) at alpha = pi: ka - |ksigma| > 0 (dalpha/dt < 0 there for every sigma)", g);
}

}  // namespace

const params::ParamTable<ControllerParams>& controller_param_table() {
  using C = ControllerParams;
  const auto gains = params::shown_as(params::finite(), "eq. (11), (16)");
  static const params::ParamTable<ControllerParams> table =
      params::ParamTable<ControllerParams>()
          .group("forward_gains", "used while |alpha| <= pi/2")
          .add("forward_gains.kd", &C::forward_gains, &GainSet::kd, "1/s", gains, "v = kd * d")
          .add("forward_gains.ka", &C::forward_gains, &GainSet::ka, "1/s", gains, "omega gain on alpha")
          .add("forward_gains.ksigma", &C::forward_gains, &GainSet::ksigma, "1/s", gains,
               "omega gain on sigma (times sgn*)")
          .group("backward_gains", "used while |alpha| > pi/2: the robot backs up (kd < 0)")
          .add("backward_gains.kd", &C::backward_gains, &GainSet::kd, "1/s", gains, "v = kd * d")
          .add("backward_gains.ka", &C::backward_gains, &GainSet::ka, "1/s", gains, "omega gain on alpha")
          .add("backward_gains.ksigma", &C::backward_gains, &GainSet::ksigma, "1/s", gains,
               "omega gain on sigma (times sgn*)")
          .add("epsilon_m", &C::epsilon_m, "m", params::positive(),
               "switch to the next way-point when the distance is <= epsilon (eq. 19)")
          .add("max_speed_mps", &C::max_speed_mps, "m/s", params::non_negative("0 = no limit"),
               "optional |v| limit (the paper: 0)")
          .add("max_turn_rate_radps", &C::max_turn_rate_radps, "rad/s", params::non_negative("0 = no limit"),
               "optional |omega| limit (the paper: 0)")
          .add("confidence_switch_sigmas", &C::confidence_switch_sigmas, "", params::non_negative("0 = off"),
               "kappa: also switch once the way-point is inside the kappa-sigma ellipse of the estimate")
          .add("stop_when_done", &C::stop_when_done, "", params::any<bool>(),
               "command zero once the last way-point is reached (false = the paper: the law stays active)")
          .add("path_lookahead_m", &C::path_lookahead_m, "m", params::non_negative("0 = the paper's law"),
               "> 0: keep each leg straight (issue 28): steer to the point this far ahead on the segment from the "
               "previous way-point");
  return table;
}

void ControllerParams::validate() const {
  controller_param_table().check_ranges(*this);
  body.validate();
  check_forward_gains(forward_gains);
  check_backward_gains(backward_gains);
}

}  // namespace robodds::waypoint_controller
