#pragma once
// Differential-drive (unicycle) kinematics of paper 1, eq. (1). Pure maths: SI units, world
// frame x/y in m, heading theta in rad counter-clockwise from +x.

namespace robodds::plant {

struct Pose2 {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad, (-pi, pi]
};

struct Twist {
  double v = 0.0;      // m/s, forward speed
  double omega = 0.0;  // rad/s, turn rate (counter-clockwise positive)
};

/// Wheel rim speeds -> body twist for wheel base D (m).
/// Paper 1 prints omega = (v_l - v_r)/D, which turns counter-clockwise when the left wheel is
/// faster; with theta counter-clockwise positive a faster *right* wheel turns left, so we use
/// omega = (v_r - v_l)/D (the paper's labelling of the wheels is mirrored; see docs/results/paper1.md).
Twist twist_from_wheel_speeds(double v_left, double v_right, double wheel_base_m);

/// Limits on the commanded twist; a limit <= 0 means "unlimited" (the paper has none).
struct TwistLimits {
  double max_speed_mps = 0.0;
  double max_turn_rate_radps = 0.0;
};

/// Clamps |v| and |omega| to the limits independently.
Twist saturate(const Twist& twist, const TwistLimits& limits);

/// sin(x) / x, continuous at x = 0 (value 1). Below |x| = 0.1 it is the Taylor series up to
/// x^10, exact to double rounding there (the first omitted term, x^12 / 13!, is below 2e-22) and
/// several times cheaper than a sin call; integrate_exact runs once per particle per prediction.
double sinc(double x);

/// Exact integration of the unicycle over dt seconds with constant (v, omega): the robot moves
/// on a circular arc (a straight line when omega is ~0, handled without dividing by omega).
Pose2 integrate_exact(const Pose2& start, const Twist& twist, double dt_s);

}  // namespace robodds::plant
