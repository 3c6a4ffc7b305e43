#include "sim/mission_source/node/mission_source_params.hpp"

#include <stdexcept>

#include "sim/mission_source/node/mission_source_node.hpp"

namespace robodds::mission_source {
namespace {

/// A WaypointMission holds 1 to 256 way-points.
params::Check<std::vector<params::Point2>> one_to_256_points() {
  return {"1 to 256 points", [](std::string_view key, const std::vector<params::Point2>& points) {
            if (points.empty()) {
              throw std::invalid_argument(std::string(key) + ": the mission needs at least one way-point");
            }
            if (points.size() > 256) {
              throw std::invalid_argument(std::string(key) + ": at most 256 way-points fit in a WaypointMission");
            }
          }};
}

}  // namespace

const params::ParamTable<MissionParams>& mission_source_param_table() {
  static const params::ParamTable<MissionParams> table =
      params::ParamTable<MissionParams>(
          "Publishes each served robot's way-point mission once, on the transient-local mission topic\n"
          "(a controller that starts late still receives it).")
          .add("waypoints", &MissionParams::waypoints, "m", one_to_256_points(), "world [x, y] of each way-point, in order");
  return table;
}

}  // namespace robodds::mission_source
