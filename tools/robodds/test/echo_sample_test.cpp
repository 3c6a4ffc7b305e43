#include "tools/robodds/echo_sample.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

std::string value_of(const EchoFields& fields, const std::string& name) {
  for (const auto& [field, value] : fields) {
    if (field == name) {
      return echo_inline(value);
    }
  }
  return "(none)";
}

TEST(EchoSample, EnumsByTheirIdlNameBooleansAsWords) {
  idl::ControllerStatus status;
  status.robot_id(3);
  status.state(idl::ControlState::ESTIMATE_STALE);
  status.done(true);
  status.alpha(0.1);
  const EchoFields fields = echo_fields(status);
  EXPECT_EQ(fields.front().first, "robot_id");
  EXPECT_EQ(value_of(fields, "robot_id"), "3");
  EXPECT_EQ(value_of(fields, "state"), "ESTIMATE_STALE");
  EXPECT_EQ(value_of(fields, "done"), "true");
  EXPECT_EQ(value_of(fields, "switched"), "false");
  EXPECT_EQ(value_of(fields, "alpha"), "0.1");
  EXPECT_EQ(value_of(fields, "header.step"), "0");
  // A number the IDL does not name (a foreign writer may send one) stays a number.
  status.state(static_cast<idl::ControlState>(17));
  EXPECT_EQ(value_of(echo_fields(status), "state"), "17");
}

TEST(EchoSample, SequencesAsListsOfRecords) {
  idl::WaypointMission mission;
  mission.robot_id(1);
  idl::Waypoint a;
  a.x(60);
  a.y(20);
  idl::Waypoint b;
  b.x(75.5);
  b.y(-15);
  mission.waypoints({a, b});
  const EchoFields fields = echo_fields(mission);
  EXPECT_EQ(value_of(fields, "waypoints"), "[{x: 60, y: 20}, {x: 75.5, y: -15}]");
  EXPECT_EQ(echo_json(select_fields(fields, {"waypoints"})), R"({"waypoints":[{"x":60,"y":20},{"x":75.5,"y":-15}]})");
}

TEST(EchoSample, StringsAndNestedSequencesOfAHostReport) {
  idl::InputReport input;
  input.component_name("controller");
  input.topic("estimate/pose");
  input.accepted(5);
  idl::ReasonCount stale;
  stale.reason("stale");
  stale.count(2);
  input.rejected({stale});
  idl::HostReport report;
  report.inputs({input});
  EXPECT_EQ(value_of(echo_fields(report), "inputs"),
            "[{component_name: controller, topic: estimate/pose, accepted: 5, rejected: [{reason: stale, count: 2}], adjusted: []}]");
}

}  // namespace
}  // namespace robodds
