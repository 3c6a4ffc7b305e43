#include "common/model/estimate_gap_hold.hpp"

#include <algorithm>
#include <limits>

#include "common/param_checks.hpp"

namespace robodds::model {

const params::ParamTable<HoldParams>& hold_param_table() {
  using P = HoldParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Hold through a brief gap of the estimate (issue 27): keep the last curvature, slow down, then stop.")
          .add("hold_s", &P::hold_s, "s", params::non_negative("0 = stop at once"),
               "longest gap of a usable estimate (it arrives but says it is not valid: a restart window, a target "
               "switch, a filter unsure of its pose; never a stale one) a moving robot rides through on its last "
               "curvature; longer: it stops")
          .add("speed_fraction", &P::speed_fraction, "", params::shown_as(params::positive(), "(0, 1]"),
               "while held, the speed tends to this fraction of the last command's, within the controller's "
               "acceleration limit");
  return table;
}

void HoldParams::validate() const {
  hold_param_table().check_ranges(*this);
  if (!(speed_fraction <= 1.0)) {
    param_checks::reject("speed_fraction", "must be in (0, 1] (a fraction of the last speed)", speed_fraction);
  }
}

EstimateGapHold::EstimateGapHold(const HoldParams& params) : params_(params) { params_.validate(); }

void EstimateGapHold::steered(const Twist& command) {
  armed_ = true;
  holding_ = false;
  last_ = command;
  speed_mps_ = command.v;
  gap_s_ = 0.0;
}

void EstimateGapHold::stopped() {
  armed_ = false;
  holding_ = false;
  gap_s_ = 0.0;
}

std::optional<Twist> EstimateGapHold::gap(double dt_s, double max_decel_mps2) {
  param_checks::require_positive("dt", dt_s);
  gap_s_ += dt_s;
  // 1e-9 s: a hold of 1 s at 50 Hz holds exactly 50 steps whatever the rounding of the sum.
  if (!armed_ || last_.v == 0.0 || gap_s_ > params_.hold_s + 1e-9) {
    armed_ = false;
    holding_ = false;
    return std::nullopt;
  }
  holding_ = true;
  const double curvature = last_.omega / last_.v;
  const double max_change = max_decel_mps2 > 0.0 ? max_decel_mps2 * dt_s : std::numeric_limits<double>::infinity();
  const double target = params_.speed_fraction * last_.v;
  speed_mps_ += std::clamp(target - speed_mps_, -max_change, max_change);
  return Twist{speed_mps_, curvature * speed_mps_};
}

}  // namespace robodds::model
