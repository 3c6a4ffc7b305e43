#pragma once
// Every parameter of the waypoint_controller component: the controller's (ControllerParams) plus
// the node's own. config/waypoint_controller.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/model/estimate_gap_hold.hpp"
#include "common/param_table.hpp"
#include "components/waypoint_controller/controller_params.hpp"

namespace robodds::waypoint_controller {

// Units, ranges and one-line descriptions of these fields: waypoint_controller_param_table() in
// waypoint_controller_params.cpp (the one source; `robodds components --params waypoint_controller`
// prints it). Defaults: the member initialisers.
struct WaypointControllerNodeParams {
  double rate_hz = 100.0;
  ControllerParams controller;
  bool require_valid_estimate = true;
  double invalid_estimate_speed_mps = 0.0;
  double invalid_estimate_creep_max_m = 12.0;
  double invalid_estimate_creep_limit_s = 40.0;
  int invalid_estimate_creep_restarts = 3;
  int invalid_estimate_creep_extensions = 2;
  double invalid_estimate_creep_progress = 0.1;
  int invalid_estimate_creep_relearns = 3;
  double invalid_estimate_relearn_max_position_std_m = 1.0;
  double estimate_timeout_s = 0.5;
  model::HoldParams gap_hold;  // issue 27: through a brief invalid estimate while driving
};

const params::ParamTable<WaypointControllerNodeParams>& waypoint_controller_param_table();

}  // namespace robodds::waypoint_controller
