#pragma once
// Body twist of a planar robot and its limits. SI units: v in m/s along the heading, omega in
// rad/s counter-clockwise positive.

namespace robodds::model {

struct Twist {
  double v = 0.0;      // m/s, forward speed
  double omega = 0.0;  // rad/s, turn rate (counter-clockwise positive)
};

/// Limits on the commanded twist; a limit <= 0 means "unlimited" (the paper has none).
struct TwistLimits {
  double max_speed_mps = 0.0;
  double max_turn_rate_radps = 0.0;
};

/// Clamps |v| and |omega| to the limits independently.
Twist saturate(const Twist& twist, const TwistLimits& limits);

}  // namespace robodds::model
