#pragma once
// Every parameter of the uwb_relative_estimator component (config/uwb_relative_estimator.params.yaml
// is generated from the table): rate, peers, the node's freshness rules and the estimator's stages
// (relative_estimator_params.hpp). The array every robot carries is not among them: it is the
// scenario's shared fact `facts: uwb_array:` (system/robot_facts.hpp), which the sensor reads too.
#include <vector>

#include "common/param_table.hpp"
#include "components/uwb_relative_estimator/relative_estimator_params.hpp"

namespace robodds::uwb_relative_estimator {

// Units, ranges and descriptions: relative_estimator_node_param_table() (the one source).
// Defaults: the member initialisers here and in the included structs.
struct RelativeEstimatorNodeParams {
  double rate_hz = 10.0;
  /// Robot ids of the peers each served robot estimates; [] = every other robot of the scenario.
  std::vector<double> peers;
  /// The odometry stage starts from the scenario's initial poses (the paper's robots start at known
  /// places); false: from the first valid eq. (1) solve.
  bool odometry_known_start = true;
  /// The window also takes the ranges between pairs of peers (each measured by the lower id: its
  /// sensor/uwb (lower, higher) stream), as the paper's server, which has every robot's data;
  /// false: only this robot's own ranges.
  bool peer_links = true;
  /// The window, pf and pf_baseline estimates of a peer are not valid while its last accepted
  /// frame is older than this (sim time in lockstep, receive time in real time).
  double uwb_timeout_s = 2.0;
  /// Real time only: every stage of a peer that uses odometry (all but uwb) is not valid while
  /// this robot's or the peer's odometry was last received longer ago than this. Samples lost in
  /// between are motion the dead reckoning never sees: the odometry stage keeps that offset.
  double odometry_timeout_s = 0.5;
  RelativeEstimatorParams estimator;  // keys window_epochs, window.*, solver.*, tracker.*, pf.*

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<RelativeEstimatorNodeParams>& relative_estimator_node_param_table();

}  // namespace robodds::uwb_relative_estimator
