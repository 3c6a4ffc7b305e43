#pragma once
// Angle helpers shared by every algorithm. Radians throughout.

namespace robodds {

inline constexpr double kPi = 3.14159265358979323846;

/// Wraps an angle to (-pi, pi]. Non-finite input is returned unchanged.
double wrap_angle(double angle_rad);

}  // namespace robodds
