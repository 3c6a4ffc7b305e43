#include "components/uwb_relative_estimator/node/uwb_relative_estimator_params.hpp"

#include <cmath>
#include <string>

#include "common/param_checks.hpp"

namespace robodds::uwb_relative_estimator {

const params::ParamTable<RelativeEstimatorNodeParams>& relative_estimator_node_param_table() {
  using P = RelativeEstimatorNodeParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "Relative pose of each peer in each served robot's body frame (paper 3, issue 11), one topic per stage:\n"
          "estimate/relative_pose_uwb (eq. 1), _window (eq. 2), estimate/relative_pose (particle filter, eq. 3-6),\n"
          "_pf_baseline ([22]), _odometry (dead reckoning), _tc (beyond the paper: tightly coupled, issue 28); inputs\n"
          "sensor/uwb (newest frame of each epoch) and\n"
          "sensor/odometry of the robot and its peers.")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "epoch rate (paper: 10); must divide the simulation rate")
          .add("peers", &P::peers, "robot ids", params::shown_as(params::any<std::vector<double>>(), "[] or scenario robot ids"),
               "peers each served robot estimates (a served robot in the list is skipped for itself); [] = every other robot")
          .add("odometry_known_start", &P::odometry_known_start, "", params::any<bool>(),
               "odometry stage: start from the scenario's initial poses (true) or from the first valid eq. (1) solve")
          .add("peer_links", &P::peer_links, "", params::any<bool>(),
               "the window also uses the ranges between each two peers (sensor/uwb of the lower id to the higher)")
          .add("uwb_timeout_s", &P::uwb_timeout_s, "s", params::positive(),
               "window, pf, pf_baseline, tc: not valid while the peer's last accepted UWB frame is older than this; > the period")
          .add("odometry_timeout_s", &P::odometry_timeout_s, "s", params::positive(),
               "real time only: not valid while the robot's or the peer's odometry is older than this; > the period")
          .include(&P::estimator, relative_estimator_param_table());
  return table;
}

void RelativeEstimatorNodeParams::validate() const {
  relative_estimator_node_param_table().check_ranges(*this);
  for (const double id : peers) {
    if (!(id >= 0.0 && id <= 4294967295.0 && std::floor(id) == id)) {
      param_checks::reject("peers", "each entry must be a robot id (a whole number >= 0)", id);
    }
  }
  estimator.validate();
}

}  // namespace robodds::uwb_relative_estimator
