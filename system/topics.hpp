#pragma once
// The robot system's topics (docs/topics.md is generated from the catalog they join):
// robot_topics() lists them; install_robot_system() hands the runtime everything of the robot
// system it must know without naming it: these topics, their sample checks
// (system/sample_checks.hpp) and the scenario sections of the mission (system/mission_plan.hpp).

#include <vector>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds::system {

/// Every topic of the robot system, in the order docs/topics.md shows them.
std::vector<TopicInfo> robot_topics();

/// Adds robot_topics() to the runtime's catalog, installs the sample checks of their types and
/// lets scenarios have the mission's sections (system/mission_plan.hpp); once per process (later calls do nothing). Every program that links robodds_system calls it
/// before main() (system/install_at_start.cpp), so no run, tool or test can forget it.
void install_robot_system();

}  // namespace robodds::system
