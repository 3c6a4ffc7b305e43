#include "components/odometry_sensor/wheel_speeds.hpp"

namespace robodds::odometry_sensor {

WheelSpeeds wheel_speeds_from_twist(const model::Twist& twist, double wheel_base_m) {
  const double rim_speed_from_turn = 0.5 * twist.omega * wheel_base_m;
  return WheelSpeeds{twist.v - rim_speed_from_turn, twist.v + rim_speed_from_turn};
}

}  // namespace robodds::odometry_sensor
