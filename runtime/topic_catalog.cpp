#include "runtime/topic_catalog.hpp"

#include "runtime/error.hpp"

namespace robodds {

const std::vector<TopicInfo>& topic_catalog() {
  static const std::vector<TopicInfo> topics = {
      {"sim/clock", "robodds::idl::SimTick", QosClass::kLockstep, "-", "coordinator (`robodds run`)", "every host"},
      {"sim/step_done", "robodds::idl::StepDone", QosClass::kLockstep, "member", "every host", "coordinator"},
      {"plant/state", "robodds::idl::RobotState", QosClass::kState, "robot_id", "plant", "sensors, truth_estimator, evaluator"},
      {"plant/cmd", "robodds::idl::VelocityCommand", QosClass::kCommand, "robot_id", "waypoint_controller, open_loop_commander", "plant, evaluator"},
      {"sensor/position", "robodds::idl::PositionMeasurement", QosClass::kSensor, "robot_id", "position_sensor", "pf_estimator, evaluator"},
      {"sensor/odometry", "robodds::idl::Odometry", QosClass::kSensor, "robot_id", "odometry_sensor", "pf_estimator, evaluator"},
      {"sensor/range", "robodds::idl::RangeMeasurement", QosClass::kSensor, "robot_id, target_id", "range sensor", "range-rate observer"},
      {"sensor/uwb", "robodds::idl::UwbRanges", QosClass::kSensor, "robot_id, peer_id", "UWB sensor", "relative estimator"},
      {"estimate/pose", "robodds::idl::PoseEstimate", QosClass::kState, "robot_id", "pf_estimator, truth_estimator", "waypoint_controller, evaluator"},
      {"estimate/relative_pose", "robodds::idl::RelativePoseEstimate", QosClass::kState, "robot_id, peer_id", "UWB estimator", "evaluator"},
      {"observer/range_rate", "robodds::idl::RangeRateEstimate", QosClass::kState, "robot_id, target_id", "range-rate observer", "guidance controller"},
      {"mission/waypoints", "robodds::idl::WaypointMission", QosClass::kMission, "robot_id", "mission_source", "waypoint_controller, evaluator"},
      {"mission/target", "robodds::idl::TargetAssignment", QosClass::kMission, "robot_id", "mission source", "guidance controller"},
      {"control/status", "robodds::idl::ControllerStatus", QosClass::kState, "robot_id", "controllers", "evaluator, CLI"},
  };
  return topics;
}

const TopicInfo* find_topic(const std::string& name) {
  for (const TopicInfo& topic : topic_catalog()) {
    if (topic.name == name) {
      return &topic;
    }
  }
  return nullptr;
}

const TopicInfo& topic_info(const std::string& name) {
  if (const TopicInfo* topic = find_topic(name)) {
    return *topic;
  }
  std::string known;
  for (const TopicInfo& topic : topic_catalog()) {
    known += (known.empty() ? "" : ", ") + topic.name;
  }
  throw ConfigError("unknown topic '" + name + "' (known: " + known + ")");
}

std::string qos_profile_for(const TopicInfo& topic, TimeMode mode, bool single_process) {
  if (mode == TimeMode::kLockstep && topic.qos_class != QosClass::kMission) {
    return single_process ? kLockstepLocalProfile : kLockstepProfile;
  }
  return to_string(topic.qos_class);
}

std::string monitor_profile_for(const TopicInfo& topic) {
  return topic.qos_class == QosClass::kMission ? kMissionProfile : kMonitorProfile;
}

}  // namespace robodds
