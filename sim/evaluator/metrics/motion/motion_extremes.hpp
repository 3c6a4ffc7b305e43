#pragma once
// The largest speeds, wheel speeds and accelerations of a stream of body twists (what the plant
// applied, plant/state, or what the controller commanded, plant/cmd), accumulated sample by
// sample. Pure: steps are simulation steps, SI units.

#include <cstddef>
#include <cstdint>

namespace robodds::evaluator {

struct TwistSample {
  std::uint64_t step = 0;
  double v = 0.0;      // m/s
  double omega = 0.0;  // rad/s
};

struct MotionExtremes {
  double max_abs_v_mps = 0.0;
  double max_abs_omega_radps = 0.0;
  double max_abs_wheel_speed_mps = 0.0;        // max over both wheels of |v -+ omega D / 2|
  double max_abs_accel_mps2 = 0.0;             // max |v_k - v_(k-1)| / (time between the samples)
  double max_abs_angular_accel_radps2 = 0.0;   // the same for omega
  std::size_t samples = 0;
};

class MotionExtremesTracker {
 public:
  /// step_s: the simulation step (s); wheel_base_m: D, for the wheel speeds.
  MotionExtremesTracker(double step_s, double wheel_base_m) : step_s_(step_s), wheel_base_m_(wheel_base_m) {}
  /// Samples in step order; a second sample at the same step counts for the speeds, not for
  /// the accelerations.
  void add(const TwistSample& sample);
  bool seen() const { return extremes_.samples > 0; }
  const MotionExtremes& extremes() const { return extremes_; }

 private:
  double step_s_;
  double wheel_base_m_;
  TwistSample previous_;
  MotionExtremes extremes_;
};

}  // namespace robodds::evaluator
