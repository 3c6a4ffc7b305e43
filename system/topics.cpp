#include "system/topics.hpp"

#include <mutex>

#include "system/mission_plan.hpp"
#include "system/sample_checks.hpp"

namespace robodds::system {

std::vector<TopicInfo> robot_topics() {
  return {
      make_topic<idl::RobotState>("plant/state", QosClass::kState, "plant", "sensors, truth_estimator, evaluator"),
      make_topic<idl::VelocityCommand>("plant/cmd", QosClass::kCommand, "waypoint_controller, circumnavigation_controller, route_follower, open_loop_commander", "plant, evaluator"),
      make_topic<idl::PositionMeasurement>("sensor/position", QosClass::kSensor, "position_sensor", "pf_estimator, evaluator"),
      make_topic<idl::Odometry>("sensor/odometry", QosClass::kSensor, "odometry_sensor", "pf_estimator, uwb_relative_estimator, evaluator"),
      make_topic<idl::RangeMeasurement>("sensor/range", QosClass::kSensor, "range_sensor", "range_rate_observer, evaluator"),
      make_topic<idl::UwbRanges>("sensor/uwb", QosClass::kSensor, "uwb_sensor", "uwb_relative_estimator"),
      make_topic<idl::PoseEstimate>("estimate/pose", QosClass::kState, "pf_estimator, truth_estimator", "waypoint_controller, circumnavigation_controller, route_follower, evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose", QosClass::kState,
                                            "uwb_relative_estimator (particle filter, eq. 3-6: the estimator's answer)", "evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose_uwb", QosClass::kState,
                                            "uwb_relative_estimator (single epoch, eq. 1)", "evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose_window", QosClass::kState,
                                            "uwb_relative_estimator (sliding window, eq. 2)", "evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose_pf_baseline", QosClass::kState,
                                            "uwb_relative_estimator (range-weighted filter, the paper's [22])", "evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose_odometry", QosClass::kState,
                                            "uwb_relative_estimator (odometry dead reckoning)", "evaluator"),
      make_topic<idl::RelativePoseEstimate>("estimate/relative_pose_tc", QosClass::kState,
                                            "uwb_relative_estimator (tightly coupled fixed-lag estimator, issue 28)", "evaluator"),
      make_topic<idl::RangeRateEstimate>("observer/range_rate", QosClass::kState, "range_rate_observer (super-twisting, eq. 1)",
                                         "circumnavigation_controller, evaluator"),
      make_topic<idl::RangeRateEstimate>("observer/range_rate_linear", QosClass::kState, "range_rate_observer (linear baseline, eq. 9)",
                                         "circumnavigation_controller (observer_topic), evaluator"),
      make_topic<idl::RangeRateEstimate>("observer/range_rate_kf", QosClass::kState,
                                         "range_rate_observer (Kalman filter on range, rate, acceleration; issue 28)",
                                         "circumnavigation_controller (observer_topic), evaluator"),
      make_topic<idl::WaypointMission>("mission/waypoints", QosClass::kMission, "mission_source", "waypoint_controller, evaluator"),
      make_topic<idl::TargetAssignment>("mission/target", QosClass::kMission, "target_mission",
                                        "range_sensor, circumnavigation_controller, evaluator"),
      make_topic<idl::ControllerStatus>("control/status", QosClass::kState, "controllers", "evaluator, CLI"),
  };
}

void install_robot_system() {
  static std::once_flag once;
  std::call_once(once, [] {
    add_topics(robot_topics());
    install_sample_checks();
    register_mission_sections();
  });
}

}  // namespace robodds::system
