#include "common/angle.hpp"

#include <cmath>

namespace robodds {

double wrap_angle_by_remainder(double angle_rad) {
  if (!std::isfinite(angle_rad)) {
    return angle_rad;
  }
  double wrapped = std::remainder(angle_rad, 2.0 * kPi);  // [-pi, pi]
  if (wrapped <= -kPi) {
    wrapped += 2.0 * kPi;
  }
  return wrapped;
}

}  // namespace robodds
