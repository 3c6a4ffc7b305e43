#pragma once
// Test support: robot 1's route in the paper's experiment 1-a, the truth of the window and
// tightly coupled tests that run it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"

namespace robodds::uwb_relative_estimator::testing {

/// Robot 1 of the paper's experiment 1-a at time `t` (s): the rectangle with corners (+-3.5, +-3) m
/// counter-clockwise from (-3.5, -3) at 0.2 m/s, turning in place by 90 deg at 0.5 rad/s at each
/// corner, in the world frame (robot 2, static, at the origin).
inline model::Pose2 exp1a_rectangle_pose(double t) {
  constexpr double kSpeed = 0.2;
  constexpr double kTurnRate = 0.5;
  const std::array<double, 4> lengths{7.0, 6.0, 7.0, 6.0};
  const std::array<std::array<double, 2>, 4> corners{{{-3.5, -3.0}, {3.5, -3.0}, {3.5, 3.0}, {-3.5, 3.0}}};
  const double turn_s = (kPi / 2.0) / kTurnRate;
  const double lap_s = (lengths[0] + lengths[1] + lengths[2] + lengths[3]) / kSpeed + 4.0 * turn_s;
  double rest = std::fmod(t, lap_s);
  for (std::size_t side = 0; side < 4; ++side) {
    const double heading = kPi / 2.0 * static_cast<double>(side);
    const double drive_s = lengths[side] / kSpeed;
    if (rest < drive_s) {
      const double s = kSpeed * rest;
      return {corners[side][0] + s * std::cos(heading), corners[side][1] + s * std::sin(heading), wrap_angle(heading)};
    }
    rest -= drive_s;
    const std::array<double, 2>& end = corners[(side + 1) % 4];
    if (rest < turn_s || side == 3) {
      return {end[0], end[1], wrap_angle(heading + kTurnRate * std::min(rest, turn_s))};
    }
    rest -= turn_s;
  }
  return {};
}

}  // namespace robodds::uwb_relative_estimator::testing
