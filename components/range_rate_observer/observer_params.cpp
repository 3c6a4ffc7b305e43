#include "components/range_rate_observer/observer_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::range_rate {

void SuperTwistingParams::validate() const {
  param_checks::require_in_open_interval("a", a, 0.0, 2.5);  // paper 2, section 1.2
  param_checks::require_positive("b", b);
  param_checks::require_positive("c", c);
  param_checks::require_non_negative("d", d, "0 = plain super-twisting");
  param_checks::require_non_negative("restart_jump_m", restart_jump_m, "0 = never restart");
}

void LinearObserverParams::validate() const {
  param_checks::require_positive("k1", k1);
  param_checks::require_positive("k2", k2);
  param_checks::require_non_negative("restart_jump_m", restart_jump_m, "0 = never restart");
}

}  // namespace robodds::range_rate
