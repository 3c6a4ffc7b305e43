#pragma once
// Hot-path angle wrapping for the filter's inner loops.

#include "common/angle.hpp"

namespace robodds::pf {

/// Same value as robodds::wrap_angle, i.e. wrapped to (-pi, pi], but one compare-and-shift for
/// the angles met in the particle loops (a wrapped heading plus one step of noise, or the
/// difference of two wrapped headings, both within (-3 pi, 3 pi)). There a - 2 pi is exact
/// (Sterbenz), so the result is bit-identical to wrap_angle; larger angles go to wrap_angle.
/// Saves the std::remainder call (~12 ns) per particle.
inline double wrap_angle_near(double angle_rad) {
  if (angle_rad > kPi) {
    const double shifted = angle_rad - 2.0 * kPi;
    return shifted <= kPi ? shifted : wrap_angle(angle_rad);
  }
  if (angle_rad <= -kPi) {
    const double shifted = angle_rad + 2.0 * kPi;
    return shifted > -kPi ? shifted : wrap_angle(angle_rad);
  }
  return angle_rad;  // already in range (NaN also lands here and stays NaN)
}

}  // namespace robodds::pf
