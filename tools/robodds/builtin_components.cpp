#include "tools/robodds/builtin_components.hpp"

#include "components/odometry_sensor/node/odometry_sensor_node.hpp"
#include "components/pf_estimator/node/pf_estimator_node.hpp"
#include "components/position_sensor/node/position_sensor_node.hpp"
#include "components/waypoint_controller/node/waypoint_controller_node.hpp"
#include "sim/evaluator/node/evaluator_node.hpp"
#include "sim/mission/node/mission_node.hpp"
#include "sim/open_loop/node/open_loop_node.hpp"
#include "sim/plant/node/plant_node.hpp"
#include "sim/truth_estimator/node/truth_estimator_node.hpp"

namespace robodds {

void register_builtin_components(ComponentRegistry& registry) {
  registry.add({"plant", "differential-drive plant (paper 1 eq. 1): plant/cmd -> plant/state",
                "sim/plant/config/plant.params.yaml", plant::make_plant_node, plant::plant_params_doc});
  registry.add({"position_sensor", "noisy absolute position: plant/state -> sensor/position",
                "components/position_sensor/config/position_sensor.params.yaml", position_sensor::make_position_sensor_node, position_sensor::position_sensor_params_doc});
  registry.add({"odometry_sensor", "wheel odometry with noise and slip: plant/state -> sensor/odometry",
                "components/odometry_sensor/config/odometry_sensor.params.yaml", odometry_sensor::make_odometry_sensor_node, odometry_sensor::odometry_sensor_params_doc});
  registry.add({"open_loop_commander", "open-loop velocity commands -> plant/cmd",
                "sim/open_loop/config/open_loop_commander.params.yaml", open_loop::make_open_loop_node, open_loop::open_loop_commander_params_doc});
  registry.add({"mission_source", "publishes the way-point mission (transient local) -> mission/waypoints",
                "sim/mission/config/mission_source.params.yaml", mission::make_mission_node, mission::mission_source_params_doc});
  registry.add({"waypoint_controller", "paper 1 way-point tracking: estimate/pose + mission/waypoints -> plant/cmd, control/status",
                "components/waypoint_controller/config/waypoint_controller.params.yaml", waypoint::make_waypoint_controller_node, waypoint::waypoint_controller_params_doc});
  registry.add({"pf_estimator", "paper 1 particle filter, full pose: sensor/odometry + sensor/position -> estimate/pose",
                "components/pf_estimator/config/pf_estimator.params.yaml", pf::make_pf_estimator_node, pf::pf_estimator_params_doc});
  registry.add({"truth_estimator", "ideal estimator: plant/state -> estimate/pose (true pose)",
                "sim/truth_estimator/config/truth_estimator.params.yaml", truth_estimator::make_truth_estimator_node, truth_estimator::truth_estimator_params_doc});
  registry.add({"evaluator", "records topics to CSV and writes summary.json",
                "sim/evaluator/config/evaluator.params.yaml", evaluator::make_evaluator_node, evaluator::evaluator_params_doc});
}

}  // namespace robodds
