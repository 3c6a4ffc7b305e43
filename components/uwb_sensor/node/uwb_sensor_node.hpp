#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::uwb_sensor {
/// plant/state of every scenario robot in; sensor/uwb (robot_id, peer_id) out at rate_hz for each
/// served robot and every other scenario robot. Lockstep: every pair at every due step, an empty
/// sample (rows = cols = 0) when the pair is out of range or the frame is lost; real time: those
/// are not published.
std::unique_ptr<Component> make_uwb_sensor_node();
}  // namespace robodds::uwb_sensor
