// The robot system's topics join the runtime's catalog before main() (system/install_at_start.cpp)
// and every one of their types has a content check installed.
#include "system/topics.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"
#include "runtime/io/sample_checks.hpp"

namespace robodds::system {
namespace {

TEST(RobotTopics, InCatalogBeforeMainAfterTheRuntimesOwn) {
  const std::vector<TopicInfo>& catalog = topic_catalog();
  ASSERT_GE(catalog.size(), 4u);
  EXPECT_EQ(catalog[0].name, "sim/clock");
  EXPECT_EQ(catalog[1].name, "sim/step_done");
  EXPECT_EQ(catalog[2].name, "run/health");
  EXPECT_EQ(catalog[3].name, "run/alive");
  for (const TopicInfo& topic : robot_topics()) {
    const TopicInfo* found = find_topic(topic.name);
    ASSERT_NE(found, nullptr) << topic.name;
    EXPECT_EQ(found->type_name, topic.type_name);
  }
  EXPECT_EQ(catalog.size(), 4u + robot_topics().size());
}

TEST(RobotTopics, EveryTypeHasAContentCheck) {
  for (const TopicInfo& topic : topic_catalog()) {
    bool checked = false;
    idl::dispatch_type(topic.type_name, [&](auto tag) {
      using Msg = typename decltype(tag)::type;
      checked = require_content_check<Msg>(topic.name) != nullptr;
    });
    EXPECT_TRUE(checked) << topic.name;
  }
}

TEST(RobotTopics, InstallingTwiceChangesNothing) {
  const std::size_t before = topic_catalog().size();
  install_robot_system();
  add_topics(robot_topics());
  EXPECT_EQ(topic_catalog().size(), before);
}

TEST(RobotTopics, SameNameOtherTypeIsRefused) {
  std::vector<TopicInfo> clash = {make_topic<idl::Odometry>("plant/state", QosClass::kState, "x", "y")};
  try {
    add_topics(clash);
    FAIL() << "a second plant/state of another type was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'plant/state'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace robodds::system
