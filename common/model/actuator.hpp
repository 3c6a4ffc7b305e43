#pragma once
// Actuator limits of a differential-drive robot: wheel-speed saturation and acceleration limits.
// Pure maths: SI units, wheel speeds are rim speeds (m/s), forward positive. Shared by the plant
// (what the robot can do) and the way-point controller (commands the robot can follow).

#include "common/model/twist.hpp"

namespace robodds::model {

/// Each limit <= 0 means "unlimited" (the paper's ideal robot has none).
struct ActuatorLimits {
  double max_wheel_speed_mps = 0.0;       // |rim speed| of each wheel
  double max_accel_mps2 = 0.0;            // |dv/dt|
  double max_angular_accel_radps2 = 0.0;  // |domega/dt|
};

struct WheelSpeeds {
  double left = 0.0;   // m/s
  double right = 0.0;  // m/s
};

/// Inverse of twist_from_wheel_speeds: v -+ omega D / 2 (a faster right wheel turns left).
WheelSpeeds wheel_speeds_from_twist(const Twist& twist, double wheel_base_m);

/// Each wheel clamped to [-max, max] on its own, as a motor driver does: the curvature omega / v
/// changes when one wheel saturates. max <= 0: `twist` unchanged.
Twist clamp_wheel_speeds(const Twist& twist, double wheel_base_m, double max_wheel_speed_mps);

/// v and omega scaled by one factor in (0, 1] so that neither wheel exceeds max: the curvature
/// omega / v (the path's shape) is kept, only the pace drops. max <= 0: `twist` unchanged.
Twist scale_to_wheel_limit(const Twist& twist, double wheel_base_m, double max_wheel_speed_mps);

/// The twist reached from `previous` after dt_s seconds on the way to `target`: the change
/// (target - previous) is scaled by one factor in [0, 1] so that |dv| <= max_accel dt and
/// |domega| <= max_angular_accel dt. The result lies on the segment previous -> target, so it
/// stays inside every convex set that holds both (wheel limits, |v| and |omega| limits).
/// Both limits <= 0, or a change within them: `target` exactly. dt_s <= 0: `previous`.
Twist limit_acceleration(const Twist& target, const Twist& previous, double dt_s, const ActuatorLimits& limits);

}  // namespace robodds::model
