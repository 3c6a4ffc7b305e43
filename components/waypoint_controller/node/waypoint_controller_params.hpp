#pragma once
// Every parameter of the waypoint_controller component: the controller's (ControllerParams) plus the node's own. The table is the one source of the keys,
// defaults (the member initialisers), units, ranges and descriptions;
// config/waypoint_controller.params.yaml is generated from it.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"
#include "components/waypoint_controller/controller_params.hpp"

namespace robodds::waypoint {

struct WaypointControllerNodeParams {
  double rate_hz = 100.0;
  ControllerParams controller;
  bool require_valid_estimate = true;
};

const params::ParamTable<WaypointControllerNodeParams>& waypoint_controller_param_table();

}  // namespace robodds::waypoint
