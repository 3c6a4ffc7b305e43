#include "common/model/twist.hpp"

#include <algorithm>

namespace robodds::model {

Twist saturate(const Twist& twist, const TwistLimits& limits) {
  Twist out = twist;
  if (limits.max_speed_mps > 0.0) {
    out.v = std::clamp(out.v, -limits.max_speed_mps, limits.max_speed_mps);
  }
  if (limits.max_turn_rate_radps > 0.0) {
    out.omega = std::clamp(out.omega, -limits.max_turn_rate_radps, limits.max_turn_rate_radps);
  }
  return out;
}

}  // namespace robodds::model
