#pragma once
// Differential-drive (unicycle) kinematics of paper 1, eq. (1). Pure maths: SI units, world
// frame x/y in m, heading theta in rad counter-clockwise from +x.

#include "common/model/pose2.hpp"
#include "common/model/twist.hpp"

namespace robodds::model {

/// Wheel rim speeds -> body twist for wheel base D (m).
/// Paper 1 prints omega = (v_l - v_r)/D, which turns counter-clockwise when the left wheel is
/// faster; with theta counter-clockwise positive a faster *right* wheel turns left, so we use
/// omega = (v_r - v_l)/D (the paper's labelling of the wheels is mirrored; see docs/results/paper1.md).
Twist twist_from_wheel_speeds(double v_left, double v_right, double wheel_base_m);

/// sin(x) / x, continuous at x = 0 (value 1). Below |x| = 0.1 it is the Taylor series up to
/// x^10, exact to double rounding there (the first omitted term, x^12 / 13!, is below 2e-22) and
/// several times cheaper than a sin call; integrate_exact runs once per particle per prediction.
double sinc(double x);

/// Exact integration of the unicycle over dt seconds with constant (v, omega): the robot moves
/// on a circular arc (a straight line when omega is ~0, handled without dividing by omega).
Pose2 integrate_exact(const Pose2& start, const Twist& twist, double dt_s);

}  // namespace robodds::model
