#include "runtime/topics/topic_catalog.hpp"

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"

namespace robodds {

namespace {

/// One catalog entry of IDL type Msg: its type name and key come from the IDL (the generated
/// idl::type_name<Msg>() and idl::key_names<Msg>()), so they cannot disagree with it.
template <class Msg>
TopicInfo topic(std::string name, QosClass qos_class, std::string producers, std::string consumers) {
  return TopicInfo{std::move(name), idl::type_name<Msg>(), qos_class, idl::key_names<Msg>(), std::move(producers),
                   std::move(consumers)};
}

}  // namespace

const std::vector<TopicInfo>& topic_catalog() {
  static const std::vector<TopicInfo> topics = {
      topic<idl::SimTick>("sim/clock", QosClass::kLockstep, "coordinator (`robodds run`)", "every host"),
      topic<idl::StepDone>("sim/step_done", QosClass::kLockstep, "every host", "coordinator"),
      topic<idl::RobotState>("plant/state", QosClass::kState, "plant", "sensors, truth_estimator, evaluator"),
      topic<idl::VelocityCommand>("plant/cmd", QosClass::kCommand, "waypoint_controller, circumnavigation_controller, route_follower, open_loop_commander", "plant, evaluator"),
      topic<idl::PositionMeasurement>("sensor/position", QosClass::kSensor, "position_sensor", "pf_estimator, evaluator"),
      topic<idl::Odometry>("sensor/odometry", QosClass::kSensor, "odometry_sensor", "pf_estimator, uwb_relative_estimator, evaluator"),
      topic<idl::RangeMeasurement>("sensor/range", QosClass::kSensor, "range_sensor", "range_rate_observer, evaluator"),
      topic<idl::UwbRanges>("sensor/uwb", QosClass::kSensor, "uwb_sensor", "uwb_relative_estimator"),
      topic<idl::PoseEstimate>("estimate/pose", QosClass::kState, "pf_estimator, truth_estimator", "waypoint_controller, circumnavigation_controller, route_follower, evaluator"),
      topic<idl::RelativePoseEstimate>("estimate/relative_pose", QosClass::kState,
                                        "uwb_relative_estimator (particle filter, eq. 3-6: the estimator's answer)", "evaluator"),
      topic<idl::RelativePoseEstimate>("estimate/relative_pose_uwb", QosClass::kState,
                                        "uwb_relative_estimator (single epoch, eq. 1)", "evaluator"),
      topic<idl::RelativePoseEstimate>("estimate/relative_pose_window", QosClass::kState,
                                        "uwb_relative_estimator (sliding window, eq. 2)", "evaluator"),
      topic<idl::RelativePoseEstimate>("estimate/relative_pose_pf_baseline", QosClass::kState,
                                        "uwb_relative_estimator (range-weighted filter, the paper's [22])", "evaluator"),
      topic<idl::RelativePoseEstimate>("estimate/relative_pose_odometry", QosClass::kState,
                                        "uwb_relative_estimator (odometry dead reckoning)", "evaluator"),
      topic<idl::RangeRateEstimate>("observer/range_rate", QosClass::kState, "range_rate_observer (super-twisting, eq. 1)",
                                     "circumnavigation_controller, evaluator"),
      topic<idl::RangeRateEstimate>("observer/range_rate_linear", QosClass::kState, "range_rate_observer (linear baseline, eq. 9)",
                                     "circumnavigation_controller (observer_topic), evaluator"),
      topic<idl::WaypointMission>("mission/waypoints", QosClass::kMission, "mission_source", "waypoint_controller, evaluator"),
      topic<idl::TargetAssignment>("mission/target", QosClass::kMission, "target_mission",
                                    "range_sensor, circumnavigation_controller, evaluator"),
      topic<idl::ControllerStatus>("control/status", QosClass::kState, "controllers", "evaluator, CLI"),
      topic<idl::HostReport>("run/health", QosClass::kMission, "every host across processes (once, at its end)",
                             "the evaluator's host (summary.json `hosts`, `inputs`, `run.timing`)"),
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
