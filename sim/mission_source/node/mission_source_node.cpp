#include "sim/mission_source/node/mission_source_node.hpp"

#include <array>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "sim/mission_source/node/mission_source_params.hpp"

namespace robodds::mission_source {
namespace {

class MissionNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    waypoints_ = read_params(ctx.params(), mission_source_param_table()).waypoints;  // 1 to 256, checked
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.push_back(robot.id);
    }
    out_ = &ctx.advertise<idl::WaypointMission>("mission/waypoints");
  }

  void on_step(const StepInfo&) override {
    if (published_) {
      return;
    }
    for (std::uint32_t id : robots_) {
      idl::WaypointMission mission;
      mission.robot_id(id);
      for (const auto& point : waypoints_) {
        idl::Waypoint w;
        w.x(point[0]);
        w.y(point[1]);
        mission.waypoints().push_back(w);
      }
      out_->publish_final(mission);
    }
    published_ = true;
  }

 private:
  std::vector<std::array<double, 2>> waypoints_;
  std::vector<std::uint32_t> robots_;
  Output<idl::WaypointMission>* out_ = nullptr;
  bool published_ = false;
};

}  // namespace

std::unique_ptr<Component> make_mission_node() { return std::make_unique<MissionNode>(); }

}  // namespace robodds::mission_source

ROBODDS_REGISTER_COMPONENT(mission_source, "publishes the way-point mission (transient local) -> mission/waypoints",
                           robodds::mission_source::make_mission_node,
                           robodds::mission_source::mission_source_param_table);
