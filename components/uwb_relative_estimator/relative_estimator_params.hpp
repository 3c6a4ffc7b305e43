#pragma once
// Parameters of one robot's relative-pose estimator of paper 3 (issue 11): every stage from the
// single-epoch solve of eq. (1) to the particle filter of eq. (3)-(6), and the baseline [22].
// relative_estimator_param_table() is the one source of keys, units, ranges and descriptions;
// the defaults are the values (member initialisers here and in the included structs,
// except where this struct overrides a library default, as noted).
#include "common/param_table.hpp"
#include "components/uwb_relative_estimator/relative_pf_params.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "components/uwb_relative_estimator/relative_pose_tracker.hpp"
#include "components/uwb_relative_estimator/sliding_window.hpp"
#include "components/uwb_relative_estimator/tightly_coupled_window.hpp"

namespace robodds::uwb_relative_estimator {

/// Eq. (1) as the paper solves it: plain least squares (the library's default is Huber 0.15 m).
SolverOptions paper_solver_options();
/// Eq. (2) weights of issue 11: odometry 0.005 m / 0.005 rad, UWB 0.3 m / 0.1 rad per epoch.
WindowWeights paper_window_weights();

struct RelativeEstimatorParams {
  /// Eq. (2): epochs in the sliding window (the paper's w; >= 2).
  int window_epochs = 30;
  /// After a gap longer than this without a measurement of a peer (no valid window estimate for
  /// the filter, no frame for the baseline), its filter restarts around the next measurement
  /// instead of weighting a cloud that drifted on odometry alone.
  double restart_after_gap_s = 2.0;
  WindowWeights window = paper_window_weights();  // keys window.*
  SolverOptions solver = paper_solver_options();  // keys solver.* (eq. 1)
  TrackerParams tracker;                          // keys tracker.* (cold-start recovery)
  RelativePfParams pf;                            // keys pf.* (eq. 3-6 and the baseline [22])
  UncertaintyParams uncertainty;                  // keys uncertainty.* (reported covariances, issue 27)
  TightWindowParams tc;                           // keys tc.* (the tc stage, issue 28)
  /// Threads of one estimator's epoch (issue 29): the per-peer stages (eq. 1 solves, tc, the
  /// filters) and the window run on a pool of this many (the caller's included); 1: all on the
  /// caller. The estimates do not depend on it (bit for bit), only the time an epoch takes.
  int threads = 2;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field (the included
  /// structs' keys carry their prefix).
  void validate() const;
};

const params::ParamTable<RelativeEstimatorParams>& relative_estimator_param_table();

}  // namespace robodds::uwb_relative_estimator
