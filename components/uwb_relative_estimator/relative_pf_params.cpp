#include "components/uwb_relative_estimator/relative_pf_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::uwb_relative_estimator {

const params::ParamTable<RelativePfParams>& relative_pf_param_table() {
  using P = RelativePfParams;
  using params::positive;
  using params::shown_as;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Relative-pose particle filter of paper 3, eq. (3)-(6), and its range-weighted baseline [22].")
          .add("num_particles", &P::num_particles, "", params::at_least(1), "S, the number of particles")
          .add("odometry_xy_std_m", &P::odometry_xy_std_m, "m", params::non_negative(),
               "eq. (4): noise on each robot's odometry increment x and y, per particle and epoch")
          .add("odometry_theta_std_rad", &P::odometry_theta_std_rad, "rad", params::non_negative(),
               "eq. (4): noise on each robot's odometry increment heading, per particle and epoch")
          .add("lambda_d_m", &P::lambda_d_m, "m", positive(),
               "eq. (5)-(6): std of the measured relative position; also the initial spread")
          .add("lambda_theta_rad", &P::lambda_theta_rad, "rad", positive(),
               "eq. (5)-(6): std of the measured relative heading; also the initial spread")
          .add("range_std_m", &P::range_std_m, "m", positive(), "baseline [22]: std of each UWB range")
          .add("resample_ess_fraction", &P::resample_ess_fraction, "", shown_as(positive(), "(0, 1]"),
               "resample when N_eff < fraction x num_particles; 1 = after every update (the paper)");
  return table;
}

void RelativePfParams::validate() const {
  relative_pf_param_table().check_ranges(*this);
  if (resample_ess_fraction > 1.0) {
    param_checks::reject("resample_ess_fraction", "must be in (0, 1]", resample_ess_fraction);
  }
}

}  // namespace robodds::uwb_relative_estimator
