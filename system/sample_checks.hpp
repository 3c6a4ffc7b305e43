#pragma once
// The content checks of the robot system's message types (header excluded: every header is the
// runtime's, runtime/io/sample_checks.hpp). install_sample_checks() hands them to the runtime,
// which runs them on every sample an Input receives; the table of checks and bounds is in
// docs/architecture.md, "Input checks".

#include <cstdint>

#include "robodds/idl/robodds.h"
#include "runtime/io/sample_checks.hpp"

namespace robodds::system {

/// Generous physical bounds of the robots of this system, per field kind: far beyond anything
/// one does, tight enough that nothing above them is integrated (v = 1e300 is refused, not
/// saturated). Variances and durations: sample_bounds (runtime).
namespace robot_bounds {
inline constexpr double kPositionM = 1e6;          // |x|, |y|, way-points, ranges, distances
inline constexpr double kSpeedMps = 1e3;           // |v|, |v_left|, |v_right|, |range_rate|
inline constexpr double kTurnRateRadps = 1e3;      // |omega|
inline constexpr double kAngleRad = 1e3;           // |theta|, |alpha|, |sigma| (wrapped or not)
inline constexpr std::uint32_t kTeamSize = 1u << 16;  // TargetAssignment::team_size
}  // namespace robot_bounds

CheckResult check_robot_state(const idl::RobotState& s);
CheckResult check_velocity_command(const idl::VelocityCommand& s);
CheckResult check_position_measurement(const idl::PositionMeasurement& s);
CheckResult check_odometry(const idl::Odometry& s);
CheckResult check_range_measurement(const idl::RangeMeasurement& s);
CheckResult check_uwb_ranges(const idl::UwbRanges& s);
CheckResult check_pose_estimate(const idl::PoseEstimate& s);
CheckResult check_relative_pose_estimate(const idl::RelativePoseEstimate& s);
CheckResult check_range_rate_estimate(const idl::RangeRateEstimate& s);
CheckResult check_waypoint_mission(const idl::WaypointMission& s);
CheckResult check_target_assignment(const idl::TargetAssignment& s);
CheckResult check_controller_status(const idl::ControllerStatus& s);

/// Installs each check above as its type's content check in the runtime (set_content_check()).
void install_sample_checks();

}  // namespace robodds::system
