#include "sim/evaluator/metrics/motion/motion_extremes.hpp"

#include <algorithm>
#include <cmath>

#include "common/model/actuator.hpp"

namespace robodds::evaluator {

void MotionExtremesTracker::add(const TwistSample& s) {
  MotionExtremes& e = extremes_;
  e.max_abs_v_mps = std::max(e.max_abs_v_mps, std::abs(s.v));
  e.max_abs_omega_radps = std::max(e.max_abs_omega_radps, std::abs(s.omega));
  const model::WheelSpeeds w = model::wheel_speeds_from_twist(model::Twist{s.v, s.omega}, wheel_base_m_);
  e.max_abs_wheel_speed_mps = std::max({e.max_abs_wheel_speed_mps, std::abs(w.left), std::abs(w.right)});
  if (e.samples > 0 && s.step > previous_.step) {
    const double dt = static_cast<double>(s.step - previous_.step) * step_s_;
    e.max_abs_accel_mps2 = std::max(e.max_abs_accel_mps2, std::abs(s.v - previous_.v) / dt);
    e.max_abs_angular_accel_radps2 = std::max(e.max_abs_angular_accel_radps2, std::abs(s.omega - previous_.omega) / dt);
  }
  ++e.samples;
  previous_ = s;
}

}  // namespace robodds::evaluator
