#pragma once
// The way-point tracking control law of paper 1, eq. (10), with the gain-set choice of
// section 4 (forward gains while |alpha| <= pi/2, backward gains beyond) and optional limits.

#include "common/model/actuator.hpp"
#include "components/waypoint_controller/controller_params.hpp"
#include "components/waypoint_controller/polar.hpp"

namespace robodds::waypoint_controller {

/// Velocity command for a differential-drive robot (body frame).
struct Command {
  double v = 0.0;      // m/s, forward speed (< 0 = backing up)
  double omega = 0.0;  // rad/s, turn rate, counter-clockwise positive
};

/// sgn* = sgn(pi/2 - |alpha|) of eq. (9): +1 for |alpha| < pi/2, 0 at exactly pi/2, -1 beyond.
int sgn_star(double alpha_rad);

/// True while |alpha| <= pi/2 (way-point ahead or abeam): the forward gain set applies.
bool uses_forward_gains(double alpha_rad);

/// The gain set that applies at bearing alpha_rad (forward for |alpha| <= pi/2, else backward).
const GainSet& select_gains(const ControllerParams& params, double alpha_rad);

/// Eq. (10) alone, no limits: v = kd·d, omega = ka·alpha + sgn*(alpha)·ksigma·sigma.
Command control_law(const PolarError& error, const GainSet& gains);

/// Issue 12: what eq. (10) asks for, slowed where the robot could not stop in time. The law
/// drives the error e = v / kd (the distance d) and e = omega / ka (alpha minus its equilibrium
/// sgn*·ksigma·sigma / -ka) to zero; at a limited acceleration a a speed u can be braked to 0
/// within e only if |u| <= sqrt(2 a |e|), so |v| and |omega| are bounded by that (sign and zeros
/// of the law kept). A limit <= 0: unchanged. Without it the heading loop (ka = 20 1/s) overshoots
/// on a robot with 5 rad/s^2 and, on a noisy estimate, circles the way-point.
Command brakeable(const Command& command, const GainSet& gains, const model::ActuatorLimits& limits);

/// A law's output made drivable: brakeable() with `gains`, then |v| and |omega| clamped
/// independently to the params' optional limits (0 = unlimited), then v and omega scaled by one
/// factor so that neither wheel exceeds max_wheel_speed_mps (the curvature is kept).
Command within_limits(const Command& law_output, const GainSet& gains, const ControllerParams& params);

/// The controller output: eq. (10) with the gain set chosen by |alpha|, then |v| and |omega|
/// clamped independently to the params' optional limits (0 = unlimited), then v and omega scaled
/// by one factor so that neither wheel exceeds max_wheel_speed_mps (the curvature is kept).
/// The acceleration limits need the previous command: WaypointTracker applies them.
Command waypoint_command(const PolarError& error, const ControllerParams& params);

}  // namespace robodds::waypoint_controller
