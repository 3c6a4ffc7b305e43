#include "components/pf_estimator/node/pf_estimator_params.hpp"

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::pf_estimator {

const params::ParamTable<PfEstimatorNodeParams>& pf_estimator_param_table() {
  static const params::ParamTable<PfEstimatorNodeParams> table =
      params::ParamTable<PfEstimatorNodeParams>(
          "Particle-filter pose estimator (paper 1 eq. 4-7, extended to the full pose [x, y, theta]).\n"
          "Prediction: the constant-v/omega arc driven by odometry (with a per-particle turn slip); update: Gaussian\n"
          "position likelihood behind a chi-square gate; a lost filter is redrawn around the last fixes (issue 12).")
          .add("rate_hz", &PfEstimatorNodeParams::rate_hz, "Hz", params::positive(),
               "estimate publication rate; must divide the simulation rate")
          .include(&PfEstimatorNodeParams::filter, pf_param_table())
          .add("valid_max_position_std_m", &PfEstimatorNodeParams::valid_max_position_std_m, "m", params::positive(),
               "the estimate is valid once sqrt(trace of its xy covariance) is below this ...")
          .add("valid_max_heading_std_rad", &PfEstimatorNodeParams::valid_max_heading_std_rad, "rad",
               params::non_negative("0 = heading not checked, nor against the fixes' track"), "... and the heading's standard deviation too")
          .add("valid_keep_max_heading_std_rad", &PfEstimatorNodeParams::valid_keep_max_heading_std_rad, "rad",
               params::shown_as(params::non_negative(), ">= valid_max_heading_std_rad"),
               "once valid, the estimate stays valid while the heading's std is below this (a band against flicker)")
          .add("input_timeout_s", &PfEstimatorNodeParams::input_timeout_s, "s", params::positive(),
               "real time only: valid = false while odometry or position was last received longer ago than this; > the period")
          .add("extrapolate_to_step", &PfEstimatorNodeParams::extrapolate_to_step, "", params::any<bool>(),
               "true: an estimate published after the last odometry sample is moved on along that sample's arc to the publication time (at most one sample interval)");
  return table;
}

void PfEstimatorNodeParams::validate() const {
  pf_estimator_param_table().check_ranges(*this);
  filter.validate();
  if (!(valid_keep_max_heading_std_rad >= valid_max_heading_std_rad)) {
    param_checks::reject("valid_keep_max_heading_std_rad", "must be >= valid_max_heading_std_rad (" +
                         shortest_text(valid_max_heading_std_rad) + ")", valid_keep_max_heading_std_rad);
  }
}

}  // namespace robodds::pf_estimator
