#include "components/odometry_sensor/twist_accumulator.hpp"

namespace robodds::odometry_sensor {

void TwistAccumulator::add(const model::Twist& twist, double dt_s) {
  distance_m_ += twist.v * dt_s;
  turn_rad_ += twist.omega * dt_s;
  elapsed_s_ += dt_s;
}

model::Twist TwistAccumulator::mean() const {
  if (!(elapsed_s_ > 0.0)) {
    return model::Twist{};
  }
  return model::Twist{distance_m_ / elapsed_s_, turn_rad_ / elapsed_s_};
}

void TwistAccumulator::reset() { *this = TwistAccumulator{}; }

}  // namespace robodds::odometry_sensor
