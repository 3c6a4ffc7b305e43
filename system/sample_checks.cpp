#include "system/sample_checks.hpp"

#include <array>
#include <cmath>
#include <string>

#include "common/number_text.hpp"

namespace robodds::system {
namespace {

using field_check::fail;
using field_check::first;
using field_check::variance;
using field_check::duration;
using field_check::within;

constexpr double kPos = robot_bounds::kPositionM;
constexpr double kSpeed = robot_bounds::kSpeedMps;
constexpr double kTurn = robot_bounds::kTurnRateRadps;
constexpr double kAngle = robot_bounds::kAngleRad;

/// Row-major 3x3 covariance: diagonal >= 0, every entry bounded.
CheckResult covariance(const std::array<double, 9>& cov) {
  static const char* const kNames[9] = {"cov[0]", "cov[1]", "cov[2]", "cov[3]", "cov[4]",
                                        "cov[5]", "cov[6]", "cov[7]", "cov[8]"};
  for (std::size_t i = 0; i < 9; ++i) {
    if (auto f = i % 4 == 0 ? variance(kNames[i], cov[i]) : within(kNames[i], cov[i], sample_bounds::kVariance)) {
      return f;
    }
  }
  return std::nullopt;
}

}  // namespace

CheckResult check_robot_state(const idl::RobotState& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle),
                within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn)});
}

CheckResult check_velocity_command(const idl::VelocityCommand& s) {
  const auto mode = static_cast<std::uint32_t>(s.mode());
  if (mode != idl::VELOCITY && mode != idl::WHEEL_SPEEDS) {
    return fail(check_reason::kBadEnum, "mode", "is " + std::to_string(mode) + ", CommandMode has 0 (VELOCITY) and 1 (WHEEL_SPEEDS)");
  }
  return first({within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn), within("v_left", s.v_left(), kSpeed),
                within("v_right", s.v_right(), kSpeed)});
}

CheckResult check_position_measurement(const idl::PositionMeasurement& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), variance("var_x", s.var_x()), variance("var_y", s.var_y())});
}

CheckResult check_odometry(const idl::Odometry& s) {
  return first({within("v", s.v(), kSpeed), within("omega", s.omega(), kTurn), duration("dt_s", s.dt_s()),
                variance("var_v", s.var_v()), variance("var_omega", s.var_omega())});
}

CheckResult check_range_measurement(const idl::RangeMeasurement& s) {
  // A range sensor reports distances: the simulated one clamps its noisy value at 0, so a
  // negative range is a broken or hostile writer, not noise.
  if (s.range() < 0.0) {
    return fail(check_reason::kAbsurdMagnitude, "range", "is " + shortest_text(s.range()) + " (a range is >= 0)");
  }
  return first({within("range", s.range(), kPos), variance("var", s.var())});
}

CheckResult check_uwb_ranges(const idl::UwbRanges& s) {
  const std::uint64_t rows = s.rows();
  const std::uint64_t cols = s.cols();
  constexpr std::uint64_t kMaxRanges = 64;  // sequence<double, 64>
  if (rows > kMaxRanges || cols > kMaxRanges || rows * cols != s.ranges().size()) {
    return fail(check_reason::kBadSize, "ranges",
                "has " + std::to_string(s.ranges().size()) + " entries for rows " + std::to_string(rows) + " x cols " +
                    std::to_string(cols) + " (rows * cols entries expected, at most 64)");
  }
  for (std::size_t i = 0; i < s.ranges().size(); ++i) {
    // The simulated sensor clamps its noisy ranges at 0 (as RangeMeasurement); rows = cols = 0
    // with no ranges is the sensor's empty sample (out of range, lost frame).
    if (s.ranges()[i] < 0.0) {
      return fail(check_reason::kAbsurdMagnitude, "ranges[" + std::to_string(i) + "]",
                  "is " + shortest_text(s.ranges()[i]) + " (a range is >= 0)");
    }
    if (std::fabs(s.ranges()[i]) > kPos) {
      return fail(check_reason::kAbsurdMagnitude, "ranges[" + std::to_string(i) + "]",
                  "is " + shortest_text(s.ranges()[i]) + ", beyond the bound " + shortest_text(kPos));
    }
  }
  return std::nullopt;
}

CheckResult check_pose_estimate(const idl::PoseEstimate& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle), covariance(s.cov()),
                variance("fix_noise_std_m", s.fix_noise_std_m())});
}

CheckResult check_relative_pose_estimate(const idl::RelativePoseEstimate& s) {
  return first({within("x", s.x(), kPos), within("y", s.y(), kPos), within("theta", s.theta(), kAngle), covariance(s.cov()),
                variance("range_noise_std_m", s.range_noise_std_m())});
}

CheckResult check_range_rate_estimate(const idl::RangeRateEstimate& s) {
  return first({within("range", s.range(), kPos), within("range_rate", s.range_rate(), kSpeed),
                variance("range_noise_std_m", s.range_noise_std_m()), variance("range_rate_std_mps", s.range_rate_std_mps())});
}

CheckResult check_waypoint_mission(const idl::WaypointMission& s) {
  for (std::size_t i = 0; i < s.waypoints().size(); ++i) {
    const idl::Waypoint& w = s.waypoints()[i];
    if (std::fabs(w.x()) > kPos || std::fabs(w.y()) > kPos) {
      return fail(check_reason::kAbsurdMagnitude, "waypoints[" + std::to_string(i) + "]",
                  "is (" + shortest_text(w.x()) + ", " + shortest_text(w.y()) + "), beyond the bound " + shortest_text(kPos));
    }
  }
  return std::nullopt;
}

CheckResult check_target_assignment(const idl::TargetAssignment& s) {
  if (s.team_size() > robot_bounds::kTeamSize || (s.team_size() > 0 && s.slot() >= s.team_size())) {
    return fail(check_reason::kBadSize, "slot",
                "is " + std::to_string(s.slot()) + " of team_size " + std::to_string(s.team_size()) +
                    " (slot < team_size <= " + std::to_string(robot_bounds::kTeamSize) + " expected)");
  }
  if (s.desired_radius() < 0.0) {
    return fail(check_reason::kAbsurdMagnitude, "desired_radius", "is " + shortest_text(s.desired_radius()) + " (a radius is >= 0)");
  }
  return first({within("desired_radius", s.desired_radius(), kPos), within("target_x", s.target_x(), kPos),
                within("target_y", s.target_y(), kPos)});
}

CheckResult check_controller_status(const idl::ControllerStatus& s) {
  if (static_cast<std::uint32_t>(s.state()) > static_cast<std::uint32_t>(idl::DONE)) {
    return fail(check_reason::kBadEnum, "state",
                "is " + std::to_string(static_cast<std::uint32_t>(s.state())) + ", ControlState has 0..5");
  }
  if (s.waypoints_reached() > s.waypoints_total()) {
    return fail(check_reason::kBadSize, "waypoints_reached",
                "is " + std::to_string(s.waypoints_reached()) + " of waypoints_total " + std::to_string(s.waypoints_total()));
  }
  return first({within("distance_to_waypoint", s.distance_to_waypoint(), kPos), within("distance_to_final", s.distance_to_final(), kPos),
                within("alpha", s.alpha(), kAngle), within("sigma", s.sigma(), kAngle),
                within("switch_distance", s.switch_distance(), kPos), within("epsilon", s.epsilon(), kPos)});
}

void install_sample_checks() {
  set_content_check(&check_robot_state);
  set_content_check(&check_velocity_command);
  set_content_check(&check_position_measurement);
  set_content_check(&check_odometry);
  set_content_check(&check_range_measurement);
  set_content_check(&check_uwb_ranges);
  set_content_check(&check_pose_estimate);
  set_content_check(&check_relative_pose_estimate);
  set_content_check(&check_range_rate_estimate);
  set_content_check(&check_waypoint_mission);
  set_content_check(&check_target_assignment);
  set_content_check(&check_controller_status);
}

}  // namespace robodds::system
