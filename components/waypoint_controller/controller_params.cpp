#include "components/waypoint_controller/controller_params.hpp"

#include <cmath>
#include <string>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::waypoint {
namespace {

std::string format_gains(const GainSet& gains) {
  return "kd=" + shortest_text(gains.kd) + ", ka=" + shortest_text(gains.ka) + ", ksigma=" + shortest_text(gains.ksigma);
}

void require_finite_gains(const std::string& key, const GainSet& gains) {
  param_checks::require_finite(key + ".kd", gains.kd);
  param_checks::require_finite(key + ".ka", gains.ka);
  param_checks::require_finite(key + ".ksigma", gains.ksigma);
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

void ControllerParams::validate() const {
  require_finite_gains("forward_gains", forward_gains);
  check_forward_gains(forward_gains);
  require_finite_gains("backward_gains", backward_gains);
  check_backward_gains(backward_gains);
  param_checks::require_positive("epsilon_m", epsilon_m);
  param_checks::require_non_negative("max_speed_mps", max_speed_mps, "0 = no limit");
  param_checks::require_non_negative("max_turn_rate_radps", max_turn_rate_radps, "0 = no limit");
  param_checks::require_non_negative("confidence_switch_sigmas", confidence_switch_sigmas, "0 = off");
}

}  // namespace robodds::waypoint
