#include "components/circumnavigation_controller/guidance_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::circumnavigation_controller {

const params::ParamTable<GuidanceParams>& guidance_param_table() {
  using P = GuidanceParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Circumnavigation guidance law (issue 10), see components/circumnavigation_controller/README.md.")
          .add("cruise_speed_mps", &P::cruise_speed_mps, "m/s", params::positive(), "V0: the nominal orbit speed")
          .add("approach_gain", &P::approach_gain, "", params::shown_as(params::positive(), "(0, 1]"),
               "desired range rate far from the orbit, as a fraction of V")
          .add("approach_width_m", &P::approach_width_m, "m", params::positive(),
               "range error at which the desired range rate saturates")
          .add("heading_gain", &P::heading_gain, "rad/m", params::positive(),
               "turn rate per m/s of range-rate error (rdot - rdot_des)")
          .add("max_turn_rate_radps", &P::max_turn_rate_radps, "rad/s", params::positive(),
               "|omega| limit of the command; enters the observer bound")
          .add("spacing_gain", &P::spacing_gain, "", params::non_negative("0 = no spacing"),
               "speed change per normalised gap difference (g+ - g-) / (2 pi / n)")
          .add("spacing_saturation", &P::spacing_saturation, "", params::shown_as(params::non_negative(), "[0, 1)"),
               "|V / V0 - 1| limit; V_max = V0 (1 + this) enters the observer bound")
          .add("max_accel_mps2", &P::max_accel_mps2, "m/s^2", params::positive(),
               "|dV/dt| limit of the speed command (rate limiter per robot)")
          .add("start_cruising", &P::start_cruising, "", params::any<bool>(),
               "the first command cruises at V0 (moving at the start, as in the paper); false: from rest. After a stop, from rest");
  return table;
}

void GuidanceParams::validate() const {
  guidance_param_table().check_ranges(*this);
  if (!(approach_gain <= 1.0)) {
    param_checks::reject("approach_gain", "must be in (0, 1] (a fraction of the speed)", approach_gain);
  }
  if (!(spacing_saturation < 1.0)) {
    param_checks::reject("spacing_saturation", "must be in [0, 1) (the speed must stay > 0)", spacing_saturation);
  }
}

double max_commanded_speed(const GuidanceParams& params) {
  return params.cruise_speed_mps * (1.0 + params.spacing_saturation);
}

}  // namespace robodds::circumnavigation_controller
