#pragma once
// Sums the true twist of consecutive plant steps into the mean twist over an odometry period,
// as wheel encoders do: distance and turn add up, and the reading is their rate over the time
// actually covered. Each plant state covers its own step, so a lost state (best effort in real
// time) shortens the covered time instead of inflating the speed.

#include "common/model/twist.hpp"

namespace robodds::odometry_sensor {

class TwistAccumulator {
 public:
  /// Adds a twist (m/s, rad/s, body frame) applied for dt_s seconds (>= 0).
  void add(const model::Twist& twist, double dt_s);
  /// Time covered since the last reset, s.
  double elapsed_s() const { return elapsed_s_; }
  /// Mean twist over the covered time; zero twist if nothing was added.
  model::Twist mean() const;
  void reset();

 private:
  double distance_m_ = 0.0;
  double turn_rad_ = 0.0;
  double elapsed_s_ = 0.0;
};

}  // namespace robodds::odometry_sensor
