#include "components/waypoint_controller/node/waypoint_controller_params.hpp"

#include "components/waypoint_controller/node/waypoint_controller_node.hpp"

namespace robodds::waypoint_controller {

const params::ParamTable<WaypointControllerNodeParams>& waypoint_controller_param_table() {
  static const params::ParamTable<WaypointControllerNodeParams> table =
      params::ParamTable<WaypointControllerNodeParams>(
          "Way-point controller of paper 1 (eq. 8-19). Gains are checked against eq. (11) and (16) at\n"
          "start-up. Defaults are the paper's, except stop_when_done.")
          .add("rate_hz", &WaypointControllerNodeParams::rate_hz, "Hz", params::positive(),
               "control rate; must divide the simulation rate")
          .include(&WaypointControllerNodeParams::controller, controller_param_table())
          .add("require_valid_estimate", &WaypointControllerNodeParams::require_valid_estimate, "", params::any<bool>(),
               "command zero while the pose estimate says it is not valid yet")
          .add("invalid_estimate_speed_mps", &WaypointControllerNodeParams::invalid_estimate_speed_mps, "m/s",
               params::non_negative("0 = stand still"),
               "with require_valid_estimate: drive straight ahead at this speed while the estimate is not valid "
               "(motion makes the heading observable from position fixes), within the acceleration limits; only "
               "before the first valid estimate of the run (or of an estimator restart, or of a relearn) and never once "
               "the mission is done: else zero")
          .add("invalid_estimate_creep_max_m", &WaypointControllerNodeParams::invalid_estimate_creep_max_m, "m",
               params::positive(),
               "with invalid_estimate_speed_mps: stop creeping once this distance was commanded (|v| integrated over "
               "the control steps: there is no pose to measure it with)")
          .add("invalid_estimate_creep_limit_s", &WaypointControllerNodeParams::invalid_estimate_creep_limit_s, "s",
               params::positive(),
               "with invalid_estimate_speed_mps: stop creeping this long after the first creeping step (a filter that "
               "never converges must not drive the robot on)")
          .add("invalid_estimate_creep_restarts", &WaypointControllerNodeParams::invalid_estimate_creep_restarts, "",
               params::at_least(0),
               "with invalid_estimate_speed_mps: how many estimator restarts (PoseEstimate.restarts rising: a lost filter "
               "redrawn from the fixes, its heading unknown) may each grant a new creep budget in a run; 0 = none")
          .add("invalid_estimate_creep_extensions", &WaypointControllerNodeParams::invalid_estimate_creep_extensions, "",
               params::at_least(0),
               "with invalid_estimate_speed_mps: a creep budget that runs out while the estimate's heading std is still "
               "falling (by invalid_estimate_creep_progress since the budget started) is extended by one more, at most "
               "this many times per budget (noisier fixes need more creeping: issue 27); 0 = none")
          .add("invalid_estimate_creep_progress", &WaypointControllerNodeParams::invalid_estimate_creep_progress, "",
               params::in_half_open_interval(0.0, 1.0),
               "the fraction by which the heading std must have fallen since a creep budget started for it to be extended")
          .add("invalid_estimate_creep_relearns", &WaypointControllerNodeParams::invalid_estimate_creep_relearns, "",
               params::at_least(0),
               "with invalid_estimate_speed_mps: an estimate that turns invalid after it was valid, its position std "
               "still below invalid_estimate_relearn_max_position_std_m (only the heading spread grew), grants a new creep "
               "budget once the gap hold ran out, at most this many times in a row without a way-point reached in "
               "between (issue 27: a standing robot cannot learn its heading again); 0 = none (zero command after a "
               "valid estimate)")
          .add("invalid_estimate_relearn_max_position_std_m",
               &WaypointControllerNodeParams::invalid_estimate_relearn_max_position_std_m, "m", params::positive(),
               "the invalid estimate's position std (sqrt(var x + var y)) must be below this for a relearn creep: the "
               "position fixes still hold the estimate")
          .add("estimate_timeout_s", &WaypointControllerNodeParams::estimate_timeout_s, "s", params::positive(),
               "real time only: an estimate received longer ago than this stops the robot (state ESTIMATE_STALE); > the control period. "
               "One older than two of its producer's periods (next_step - step) already holds the last command")
          .include_as("gap_hold", &WaypointControllerNodeParams::gap_hold, model::hold_param_table(),
                      "with require_valid_estimate: a robot that was tracking and is moving, whose estimate arrives but "
                      "says it is not valid, keeps the curvature of its last command at a reduced speed (braked within "
                      "max_accel_mps2) for at most hold_s, then the rules above (stop, or creep after an estimator "
                      "restart or as a relearn); never before the first valid estimate, never once the mission is done, never on a missing or "
                      "stale estimate nor on one marked inputs_stale (issue 27)");
  return table;
}

}  // namespace robodds::waypoint_controller
