// The run recorder on the in-memory bus: every published topic it is given, observed on the bus
// in a co-located run and through gated inputs as a host of a run across processes (the same
// bytes), one channel per topic in name order, each step's samples in topic then instance order, log_time
// the sample's sim step (ns), publish_time its stamp; foxglove_scene's derived channel; bad
// parameters named.
#include "sim/run_recorder/node/run_recorder_node.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/mcap/mcap_reader.hpp"
#include "runtime/testing/node_test_scenario.hpp"
#include "system/foxglove/robot_poses.hpp"

ROBODDS_DECLARE_COMPONENT(run_recorder);

namespace robodds::run_recorder {
namespace {

using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_run_recorder>;

/// A codec that spells what the recorder must keep apart: type, robot, step (the DDS one is
/// runtime/dds's, tested there).
class SpellingCodec : public SampleCodec {
 public:
  template <class Msg>
  static std::string spelled(const Msg& m) {
    return " robot " + std::to_string(m.robot_id()) + " step " + std::to_string(m.header().step());
  }
  std::vector<std::uint8_t> serialize(const std::string& type_name, const void* sample) const override {
    std::string text = type_name;
    if (type_name == idl::type_name<idl::RobotState>()) {
      text += spelled(*static_cast<const idl::RobotState*>(sample));
    } else if (type_name == idl::type_name<idl::VelocityCommand>()) {
      text += spelled(*static_cast<const idl::VelocityCommand*>(sample));
    } else if (type_name == idl::type_name<idl::RangeMeasurement>()) {
      const auto& m = *static_cast<const idl::RangeMeasurement*>(sample);
      text += spelled(m) + " target " + std::to_string(m.target_id());
    } else if (type_name == idl::type_name<idl::UwbRanges>()) {
      const auto& m = *static_cast<const idl::UwbRanges*>(sample);
      text += spelled(m) + " peer " + std::to_string(m.peer_id());
    }
    return std::vector<std::uint8_t>(text.begin(), text.end());
  }
  std::shared_ptr<void> deserialize(const std::string&, const std::uint8_t*, std::size_t) const override { return nullptr; }
};

std::string file_in_temp(const std::string& name) { return ::testing::TempDir() + "/" + name; }

std::string scenario_recording_to(const std::string& file, const std::string& more = "") {
  return ScenarioText("run_recorder_node", 0.01, 0.03)
      .robots({1, 2})
      .component("{name: rec, type: run_recorder, params: {file: " + file + more + "}}");
}

void feed_state_and_commands(Harness& h) {
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {2u, 1u}) {  // written out of key order: the recorder sorts
      idl::VelocityCommand c;
      c.robot_id(robot);
      h.publish("plant/cmd", c, step, step + 1);
      idl::RobotState s;
      s.robot_id(robot);
      h.publish("plant/state", s, step, step + 1);
    }
  });
  h.assign_producers({{"plant/state", {{1, {"feeder"}}, {2, {"feeder"}}}}, {"plant/cmd", {{1, {"feeder"}}, {2, {"feeder"}}}}});
}

TEST(RunRecorderNode, RecordsEveryPublishedTopicInTopicThenInstanceOrderWithSimTimes) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_order.mcap");
  Harness h(scenario_recording_to(file));
  feed_state_and_commands(h);
  h.run({"rec"});
  const mcap::McapContents contents = mcap::read_mcap(file);
  ASSERT_TRUE(contents.report.valid());
  ASSERT_EQ(contents.report.channels.size(), 2u);
  EXPECT_EQ(contents.report.channels[0].topic, "plant/cmd") << "channels in topic name order";
  EXPECT_EQ(contents.report.channels[1].topic, "plant/state");
  EXPECT_EQ(contents.report.channels[0].message_encoding, "cdr");
  EXPECT_EQ(contents.report.channels[0].metadata.at("key"), "robot_id");
  EXPECT_EQ(contents.report.schemas.at(0).encoding, "omgidl");
  ASSERT_EQ(contents.messages.size(), 4u * 4u) << "steps 0..3, two topics, two robots: nothing lost";
  std::size_t i = 0;
  for (std::uint64_t step = 0; step <= 3; ++step) {
    for (const char* type : {"robodds::idl::VelocityCommand", "robodds::idl::RobotState"}) {
      for (int robot : {1, 2}) {
        const mcap::Message& m = contents.messages[i++];
        EXPECT_EQ(std::string(m.data.begin(), m.data.end()),
                  std::string(type) + " robot " + std::to_string(robot) + " step " + std::to_string(step));
        EXPECT_EQ(m.log_time, step * 10'000'000u) << "sim time of the sample's step, ns";
        EXPECT_EQ(m.publish_time, step * 10'000'000u) << "the sample's stamp";
      }
    }
  }
  std::remove(file.c_str());
}

std::uint64_t pair(std::uint32_t robot, std::uint32_t peer) {
  idl::UwbRanges key;
  key.robot_id(robot);
  key.peer_id(peer);
  return idl::instance_key(key);
}

/// Feeds sensor/uwb for the pairs (1, 2), (2, 1), (1, 3) every step, out of key order.
void feed_pairs(Harness& h, bool declare) {
  h.feed([&h](std::uint64_t step) {
    for (const auto& [robot, peer] : {std::pair{2u, 1u}, std::pair{1u, 3u}, std::pair{1u, 2u}}) {
      idl::UwbRanges m;
      m.robot_id(robot);
      m.peer_id(peer);
      h.publish("sensor/uwb", m, step, step + 1);
    }
  });
  h.assign_producers({{"sensor/uwb", {{1, {"feeder"}}, {2, {"feeder"}}}}});
  if (declare) {
    h.produce_instances({{"sensor/uwb", {pair(1, 2), pair(1, 3), pair(2, 1)}}});
  }
}

/// The bytes of a recording of three steps of plant/state, plant/cmd (by robot), sensor/range (by
/// robot, two targets for robot 1) and sensor/uwb (declared pairs), each step's samples written
/// out of key order; `single_process`: co-located (the recorder observes the bus) or as a host of
/// a run across processes (it reads through inputs).
std::string recording_of_every_key_kind(bool single_process) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp(single_process ? "run_recorder_local.mcap" : "run_recorder_inputs.mcap");
  Harness h(ScenarioText("run_recorder_node", 0.01, 0.03)
                .robots({1, 2, 3})
                .component("{name: rec, type: run_recorder, params: {file: " + file + ", compression: none}}"));
  h.set_single_process(single_process);
  h.feed([&h](std::uint64_t step) {
    for (const auto& [robot, target] : {std::pair{2u, 9u}, std::pair{1u, 5u}, std::pair{1u, 4u}}) {
      idl::RangeMeasurement r;
      r.robot_id(robot);
      r.target_id(target);
      h.publish("sensor/range", r, step, step + 1);
    }
    for (const auto& [robot, peer] : {std::pair{2u, 1u}, std::pair{1u, 3u}, std::pair{1u, 2u}}) {
      idl::UwbRanges u;
      u.robot_id(robot);
      u.peer_id(peer);
      h.publish("sensor/uwb", u, step, step + 1);
    }
    for (std::uint32_t robot : {2u, 1u}) {
      idl::VelocityCommand c;
      c.robot_id(robot);
      h.publish("plant/cmd", c, step, step + 1);
      idl::RobotState s;
      s.robot_id(robot);
      h.publish("plant/state", s, step, step + 1);
    }
  });
  const std::map<std::uint32_t, std::vector<std::string>> robots_1_2{{1, {"feeder"}}, {2, {"feeder"}}};
  h.assign_producers({{"plant/state", robots_1_2}, {"plant/cmd", robots_1_2}, {"sensor/range", robots_1_2}, {"sensor/uwb", robots_1_2}});
  h.produce_instances({{"sensor/uwb", {pair(1, 2), pair(1, 3), pair(2, 1)}}});
  h.run({"rec"});
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::remove(file.c_str());
  return bytes;
}

TEST(RunRecorderNode, ObservingTheBusCoLocatedWritesWhatInputsWouldAcrossProcesses) {
  const std::string local = recording_of_every_key_kind(true);
  const std::string inputs = recording_of_every_key_kind(false);
  ASSERT_FALSE(local.empty());
  EXPECT_TRUE(local == inputs) << "co-located " << local.size() << " bytes, through inputs " << inputs.size() << " bytes";
  // Robot 1's targets in key order (4, then 5; written 5 first), then robot 2's.
  const std::size_t five = local.find("RangeMeasurement robot 1 step 0 target 5");
  const std::size_t four = local.find("RangeMeasurement robot 1 step 0 target 4");
  const std::size_t nine = local.find("RangeMeasurement robot 2 step 0 target 9");
  ASSERT_NE(five, std::string::npos);
  EXPECT_LT(four, five);
  EXPECT_LT(five, nine);
}

TEST(RunRecorderNode, RecordsPairKeyedTopicsForTheInstancesTheirProducersDeclare) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_pairs.mcap");
  Harness h(ScenarioText("run_recorder_node", 0.01, 0.03)
                .robots({1, 2, 3})
                .component("{name: rec, type: run_recorder, params: {file: " + file + "}}"));
  feed_pairs(h, true);
  h.run({"rec"});
  const mcap::McapContents contents = mcap::read_mcap(file);
  ASSERT_EQ(contents.report.channels.size(), 1u);
  EXPECT_EQ(contents.report.channels[0].metadata.at("key"), "robot_id, peer_id");
  ASSERT_EQ(contents.messages.size(), 4u * 3u) << "steps 0..3, three pairs: nothing lost";
  std::size_t i = 0;
  for (std::uint64_t step = 0; step <= 3; ++step) {
    for (const auto& [robot, peer] : {std::pair{1, 2}, std::pair{1, 3}, std::pair{2, 1}}) {  // key order
      const mcap::Message& m = contents.messages[i++];
      EXPECT_EQ(std::string(m.data.begin(), m.data.end()), "robodds::idl::UwbRanges robot " + std::to_string(robot) + " step " +
                                                               std::to_string(step) + " peer " + std::to_string(peer));
      EXPECT_EQ(m.log_time, step * 10'000'000u);
    }
  }
  std::remove(file.c_str());
}

TEST(RunRecorderNode, APairKeyedTopicWithoutDeclaredInstancesIsNotRecordedAndNamingItIsRefused) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_undeclared.mcap");
  {
    Harness h(ScenarioText("run_recorder_node", 0.01, 0.03).robots({1, 2, 3}).component(
        "{name: rec, type: run_recorder, params: {file: " + file + ", topics: [sensor/uwb]}}"));
    feed_pairs(h, false);
    EXPECT_NE(h.run_error<ConfigError>({"rec"}).find("'sensor/uwb' is keyed (robot_id, peer_id) and its producers declare no instances"),
              std::string::npos);
  }
  std::remove(file.c_str());
}

TEST(RunRecorderNode, RecordsOnlyTheTopicsNamed) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_named.mcap");
  Harness h(scenario_recording_to(file, ", topics: [plant/state]"));
  feed_state_and_commands(h);
  h.run({"rec"});
  const mcap::McapContents contents = mcap::read_mcap(file);
  ASSERT_EQ(contents.report.channels.size(), 1u);
  EXPECT_EQ(contents.messages.size(), 8u);
  std::remove(file.c_str());
}

TEST(RunRecorderNode, TheFoxgloveSceneFollowsThePlantStateBatchesOncePer50MsOfTheirStamps) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_scene.mcap");
  Harness h(ScenarioText("run_recorder_node", 0.01, 0.07)
                .robots({1, 2})
                .component("{name: rec, type: run_recorder, params: {file: " + file + ", foxglove_scene: true}}"));
  constexpr std::int64_t kStampStepNs = 20'000'000;  // stamps 20 ms apart, steps 10 ms: due is the stamps'
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {2u, 1u}) {
      idl::VelocityCommand c;
      c.robot_id(robot);
      h.publish("plant/cmd", c, step, step + 1);
      idl::RobotState s;
      s.robot_id(robot);
      s.x(robot);
      s.y(static_cast<double>(step));
      s.theta(robot == 2 ? M_PI : 0.0);
      h.publish_stamped("plant/state", s, step, step + 1, static_cast<std::int64_t>(step) * kStampStepNs);
    }
  });
  h.assign_producers({{"plant/state", {{1, {"feeder"}}, {2, {"feeder"}}}}, {"plant/cmd", {{1, {"feeder"}}, {2, {"feeder"}}}}});
  h.run({"rec"});
  const mcap::McapContents contents = mcap::read_mcap(file);
  ASSERT_TRUE(contents.report.valid());
  ASSERT_EQ(contents.report.channels.size(), 3u);
  EXPECT_EQ(contents.report.channels[0].topic, "plant/cmd") << "the topics' channels keep their ids";
  EXPECT_EQ(contents.report.channels[1].topic, "plant/state");
  const mcap::ChannelInfo& scene = contents.report.channels[2];
  EXPECT_EQ(scene.topic, foxglove::kRobotPosesTopic);
  EXPECT_EQ(scene.message_encoding, "json");
  ASSERT_EQ(contents.report.schemas.size(), 3u);
  EXPECT_EQ(contents.report.schemas[2].name, foxglove::kPosesInFrameSchemaName);
  EXPECT_EQ(contents.report.schemas[2].encoding, "jsonschema");
  EXPECT_EQ(contents.report.schemas[2].data, foxglove::poses_in_frame_json_schema());
  // Steps 0..7, stamps 0, 20, ..., 140 ms: due at 0, 60 and 120 ms (steps 0, 3, 6), each written
  // right after its step's plant/state samples, with every robot's pose of that step.
  std::vector<std::uint64_t> scene_steps;
  for (std::size_t i = 0; i < contents.messages.size(); ++i) {
    const mcap::Message& m = contents.messages[i];
    if (m.channel_id != scene.id) {
      continue;
    }
    const std::uint64_t step = m.log_time / 10'000'000u;
    scene_steps.push_back(step);
    EXPECT_EQ(m.log_time, step * 10'000'000u) << "the sim time of its step";
    EXPECT_EQ(m.publish_time, step * kStampStepNs) << "the plant/state samples' stamp";
    ASSERT_GE(i, 2u);
    EXPECT_EQ(std::string(contents.messages[i - 1].data.begin(), contents.messages[i - 1].data.end()),
              "robodds::idl::RobotState robot 2 step " + std::to_string(step));
    const nlohmann::json v = nlohmann::json::parse(m.data.begin(), m.data.end());
    EXPECT_EQ(v["timestamp"]["sec"].get<std::int64_t>() * 1'000'000'000 + v["timestamp"]["nsec"].get<std::int64_t>(),
              static_cast<std::int64_t>(m.publish_time));
    ASSERT_EQ(v["poses"].size(), 2u) << "every robot";
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(v["poses"][k]["position"]["x"].get<double>(), k + 1.0) << "robot id order";
      EXPECT_EQ(v["poses"][k]["position"]["y"].get<double>(), static_cast<double>(step)) << "that step's pose";
    }
    EXPECT_NEAR(v["poses"][1]["orientation"]["z"].get<double>(), 1.0, 1e-12);  // pi about z
  }
  EXPECT_EQ(scene_steps, (std::vector<std::uint64_t>{0, 3, 6}));
  std::remove(file.c_str());
}

TEST(RunRecorderNode, TheFoxgloveSceneWithoutPlantStateIsRefused) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_scene_bad.mcap");
  {
    Harness h(scenario_recording_to(file, ", foxglove_scene: true, topics: [plant/cmd]"));
    feed_state_and_commands(h);
    EXPECT_NE(h.run_error<ConfigError>({"rec"}).find("draws the robots from plant/state: add it to --record-topics"),
              std::string::npos);
  }
  {
    Harness h(ScenarioText("run_recorder_node", 0.01, 0.03)
                  .robots({1, 2, 3})
                  .component("{name: rec, type: run_recorder, params: {file: " + file + ", foxglove_scene: true}}"));
    feed_pairs(h, true);
    EXPECT_NE(h.run_error<ConfigError>({"rec"}).find("draws the robots from plant/state: no component of the scenario publishes it"),
              std::string::npos);
  }
  std::remove(file.c_str());
}

TEST(RunRecorderNode, NamesABadParameter) {
  set_sample_codec(std::make_shared<SpellingCodec>());
  const std::string file = file_in_temp("run_recorder_bad.mcap");
  {
    Harness h(scenario_recording_to(file, ", compression: gzip"));
    feed_state_and_commands(h);
    EXPECT_NE(h.run_error<ConfigError>({"rec"}).find("compression"), std::string::npos);
  }
  {
    Harness h(scenario_recording_to(file, ", topics: [sensor/position]"));
    feed_state_and_commands(h);
    EXPECT_NE(h.run_error<ConfigError>({"rec"}).find("no component of the scenario publishes 'sensor/position'"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace robodds::run_recorder
