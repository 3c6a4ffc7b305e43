#include "tools/robodds/topic_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace robodds {
namespace {

TEST(TopicReport, HzTextIsRos2sTwoLines) {
  PeriodStats s;
  s.messages = 101;
  s.rate_hz = 100.0004;
  s.mean_s = 0.01;
  s.min_s = 0.0094;
  s.max_s = 0.0106;
  s.std_s = 0.000123;
  EXPECT_EQ(hz_text("", s), "average rate: 100.000\n\tmin: 0.009s max: 0.011s std dev: 0.00012s window: 101\n");
  EXPECT_EQ(hz_text("robot_id=2", s), "robot_id=2: average rate: 100.000\n\tmin: 0.009s max: 0.011s std dev: 0.00012s window: 101\n");
}

TEST(TopicReport, InstancesInNumericOrder) {
  std::vector<std::string> labels{"robot_id=10", "robot_id=2", "robot_id=1, peer_id=12", "robot_id=1, peer_id=3", "member=b", "member=a", "robot_id=2"};
  std::sort(labels.begin(), labels.end(), InstanceOrder{});
  EXPECT_EQ(labels, (std::vector<std::string>{"member=a", "member=b", "robot_id=1, peer_id=3", "robot_id=1, peer_id=12",
                                              "robot_id=2", "robot_id=2", "robot_id=10"}));
  EXPECT_TRUE(InstanceOrder{}("robot_id=9", "robot_id=010"));  // leading zeros do not count
  EXPECT_FALSE(InstanceOrder{}("robot_id=2", "robot_id=2"));
}

TEST(TopicReport, BytesIn1000BasedUnits) {
  EXPECT_EQ(byte_text(76), "76 B");
  EXPECT_EQ(byte_text(999.4), "999 B");
  EXPECT_EQ(byte_text(7600), "7.60 KB");
  EXPECT_EQ(byte_text(2.1e6), "2.10 MB");
}

TEST(TopicReport, BwTextIsRos2sTwoLines) {
  SizeStats s;
  s.messages = 100;
  s.bytes_per_s = 22800;
  s.mean_bytes = 76;
  s.min_bytes = 76;
  s.max_bytes = 76;
  EXPECT_EQ(bw_text(s), "22.80 KB/s from 100 messages\n\tMessage size mean: 76 B min: 76 B max: 76 B\n");
}

EndpointQos state_qos() {
  EndpointQos q;
  q.reliability = "RELIABLE";
  q.durability = "VOLATILE";
  q.deadline_s = 0.5;
  q.liveliness = "MANUAL_BY_TOPIC";
  q.liveliness_lease_s = 1.0;
  q.ownership = "SHARED";
  return q;
}

TEST(TopicReport, QosLineNamesOnlyWhatIsSet) {
  EXPECT_EQ(qos_line(state_qos()), "RELIABLE, VOLATILE, deadline 0.5 s, liveliness MANUAL_BY_TOPIC 1 s");
  EndpointQos plain;
  plain.reliability = "BEST_EFFORT";
  plain.durability = "VOLATILE";
  plain.liveliness = "AUTOMATIC";
  plain.ownership = "SHARED";
  EXPECT_EQ(qos_line(plain), "BEST_EFFORT, VOLATILE");
  plain.lifespan_s = 2.0;
  plain.ownership = "EXCLUSIVE";
  plain.ownership_strength = 10;
  EXPECT_EQ(qos_line(plain), "BEST_EFFORT, VOLATILE, lifespan 2 s, ownership EXCLUSIVE 10");
}

DiscoveredTopic plant_state() {
  DiscoveredTopic t;
  t.name = "plant/state";
  t.type_name = "robodds::idl::RobotState";
  t.writers = 1;
  t.readers = 1;
  t.endpoints.push_back(DiscoveredEndpoint{true, "01.0f.aa|0.0.1.3", "robodds-sim", "node7", state_qos()});
  EndpointQos reader = state_qos();
  reader.reliability = "BEST_EFFORT";
  reader.deadline_s.reset();
  reader.liveliness = "AUTOMATIC";
  reader.liveliness_lease_s.reset();
  t.endpoints.push_back(DiscoveredEndpoint{false, "01.0f.bb|0.0.1.4", "robodds-echo", "", reader});
  return t;
}

TEST(TopicReport, TopicsVerboseListsEveryEndpointUnderItsTopic) {
  EXPECT_EQ(topics_verbose_text({plant_state()}),
            "plant/state [robodds::idl::RobotState] 1 writer, 1 reader\n"
            "    writer  robodds-sim @ node7  RELIABLE, VOLATILE, deadline 0.5 s, liveliness MANUAL_BY_TOPIC 1 s\n"
            "    reader  robodds-echo @ (host not announced)  BEST_EFFORT, VOLATILE\n");
}

TEST(TopicReport, InfoIsRos2sTopicInfoVerbose) {
  EXPECT_EQ(topic_info_text(plant_state()),
            "Type: robodds::idl::RobotState\n"
            "\nWriter count: 1\n"
            "\nParticipant: robodds-sim\nHost: node7\nEndpoint type: WRITER\nGUID: 01.0f.aa|0.0.1.3\nQoS:\n"
            "  Reliability: RELIABLE\n  History (Depth): UNKNOWN (not announced in discovery)\n  Durability: VOLATILE\n"
            "  Lifespan: Infinite\n  Deadline: 0.5 s\n  Liveliness: MANUAL_BY_TOPIC\n  Liveliness lease duration: 1 s\n"
            "  Ownership: SHARED\n"
            "\nReader count: 1\n"
            "\nParticipant: robodds-echo\nHost: (not announced)\nEndpoint type: READER\nGUID: 01.0f.bb|0.0.1.4\nQoS:\n"
            "  Reliability: BEST_EFFORT\n  History (Depth): UNKNOWN (not announced in discovery)\n  Durability: VOLATILE\n"
            "  Lifespan: Infinite\n  Deadline: Infinite\n  Liveliness: AUTOMATIC\n  Liveliness lease duration: Infinite\n"
            "  Ownership: SHARED\n");
  DiscoveredTopic none;
  none.type_name = "robodds::idl::UwbRanges";
  EXPECT_EQ(topic_info_text(none), "Type: robodds::idl::UwbRanges\n\nWriter count: 0\n\nReader count: 0\n");
}

}  // namespace
}  // namespace robodds
