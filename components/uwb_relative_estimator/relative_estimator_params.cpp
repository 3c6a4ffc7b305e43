#include "components/uwb_relative_estimator/relative_estimator_params.hpp"

namespace robodds::uwb_relative_estimator {

SolverOptions paper_solver_options() {
  SolverOptions options;
  options.loss = RobustLoss::kNone;
  return options;
}

WindowWeights paper_window_weights() {
  WindowWeights weights;
  weights.odometry_xy_std_m = 0.005;
  weights.odometry_theta_std_rad = 0.005;
  weights.uwb_xy_std_m = 0.3;
  weights.uwb_theta_std_rad = 0.1;
  return weights;
}

const params::ParamTable<RelativeEstimatorParams>& relative_estimator_param_table() {
  using P = RelativeEstimatorParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Relative pose of each peer in a robot's body frame (paper 3): eq. (1), eq. (2), eq. (3)-(6), [22].")
          .add("window_epochs", &P::window_epochs, "epochs", params::at_least(2), "eq. (2): epochs in the sliding window (paper: w = 30)")
          .add("restart_after_gap_s", &P::restart_after_gap_s, "s", params::positive(),
               "a filter restarts around the next measurement of a peer after a gap longer than this")
          .add("threads", &P::threads, "", params::at_least(1),
               "threads of one estimator's epoch (per-peer stages and the window side by side; the estimates do not depend on it)")
          .include_as("window", &P::window, window_weights_param_table(), "eq. (2): constant information matrices")
          .include_as("solver", &P::solver, solver_param_table(), "eq. (1): single-epoch solve (the paper: loss none)")
          .include_as("tracker", &P::tracker, tracker_param_table(), "eq. (1) epoch after epoch: cold-start recovery")
          .include_as("pf", &P::pf, relative_pf_param_table(), "eq. (3)-(6) particle filter and the baseline [22]")
          .include_as("uncertainty", &P::uncertainty, uncertainty_param_table(),
                      "reported covariances of every stage (issue 27)")
          .include_as("tc", &P::tc, tight_window_param_table(),
                      "beyond the paper (issue 28): tightly coupled fixed-lag estimator on the raw ranges");
  return table;
}

void RelativeEstimatorParams::validate() const {
  relative_estimator_param_table().check_ranges(*this);
  window.validate();
  solver.validate();
  tracker.validate();
  pf.validate();
  uncertainty.validate();
  tc.validate();
}

}  // namespace robodds::uwb_relative_estimator
