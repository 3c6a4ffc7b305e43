// docs/topics.md's topic table against the catalog, and the rendering itself.
#include "runtime/topics/topic_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "common/line_diff.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {


TEST(TopicTable, DocsTopicsMdMatchesTheCatalog) {
  const std::string path = std::string(ROBODDS_SOURCE_DIR) + "/docs/topics.md";
  std::ifstream in(path);
  ASSERT_TRUE(in.good()) << "cannot read " << path;
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string in_doc = generated_topic_table(doc, path);
  const std::string rendered = render_topic_table(topic_catalog());
  // Not EXPECT_EQ: its dump of both tables would bury the diff.
  EXPECT_TRUE(in_doc == rendered) << "docs/topics.md's topic table differs from the topic catalog "
                                  << "(- doc, + catalog):\n"
                                  << line_diff(in_doc, rendered) << "Regenerate it with scripts/regenerate_topics_doc.sh";
}

TEST(TopicTable, RendersOneRowPerTopicInCatalogOrder) {
  const std::vector<TopicInfo> topics = {
      {"sim/clock", "robodds::idl::SimTick", QosClass::kLockstep, "-", "coordinator", "every host"},
      {"sensor/uwb", "robodds::idl::UwbRanges", QosClass::kSensor, "robot_id, peer_id", "UWB sensor", "estimator"},
      {"mission/target", "robodds::idl::TargetAssignment", QosClass::kMission, "robot_id", "mission source", "guidance"},
  };
  EXPECT_EQ(render_topic_table(topics),
            "| Topic | IDL type | Key | Real time | Lockstep | Producers | Consumers |\n"
            "|---|---|---|---|---|---|---|\n"
            "| `sim/clock` | `SimTick` | — (unkeyed) | — (lockstep only) | `lockstep` | coordinator | every host |\n"
            "| `sensor/uwb` | `UwbRanges` | `robot_id, peer_id` | `sensor` | `lockstep` | UWB sensor | estimator |\n"
            "| `mission/target` | `TargetAssignment` | `robot_id` | `mission` | `mission` | mission source | guidance |\n");
}

TEST(TopicTable, ReplacesOnlyTheTextBetweenTheMarkers) {
  const std::string doc = std::string("intro\n") + kTopicTableBegin + "\nold table\n" + kTopicTableEnd + "\noutro\n";
  EXPECT_EQ(generated_topic_table(doc, "d.md"), "old table\n");
  EXPECT_EQ(with_generated_topic_table(doc, "new\n", "d.md"),
            std::string("intro\n") + kTopicTableBegin + "\nnew\n" + kTopicTableEnd + "\noutro\n");
}

TEST(TopicTable, MissingMarkerNamesTheDoc) {
  try {
    generated_topic_table(std::string("intro\n") + kTopicTableEnd + "\n", "docs/topics.md");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), testing::StartsWith("docs/topics.md: expected the line '<!-- topic table"));
  }
}

}  // namespace
}  // namespace robodds
