// The replay_source node on the in-memory bus, on recordings written here with our MCAP writer and
// the DDS sample codec (the bytes a recorder gets off the wire): each sample published at its
// recorded step with its recorded next_step; a recording that cannot drive the run, a topic not in
// it, a schema that is not ours and real time are ConfigErrors naming why. A pair-keyed topic's
// instances are the recorded pairs, declared at every configure (the producer check's dry one too),
// and a pair of a robot the scenario does not have is refused.
#include "sim/replay_source/node/replay_source_node.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "idl/idl_schema.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/dds/dds_sample_codec.hpp"
#include "runtime/host/producer_check.hpp"
#include "runtime/mcap/mcap_writer.hpp"
#include "runtime/testing/node_test_scenario.hpp"
#include "tests/support/temp_file.hpp"

ROBODDS_DECLARE_COMPONENT(replay_source);

namespace robodds::replay_source {
namespace {

using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_replay_source>;

struct Fix {
  std::uint64_t step, next_step;
  double x;
};

/// A recording of sensor/position (robot 1) with these fixes, under schema `schema_name`.
std::string recording(const std::vector<Fix>& fixes, const std::string& schema_name = "robodds::idl::PositionMeasurement",
                      mcap::Compression compression = mcap::Compression::kZstd) {
  install_dds_sample_codec();
  const std::string path = test_support::write_test_file("rec.mcap", "");
  mcap::WriterOptions options;
  options.compression = compression;
  mcap::Writer writer(path, options);
  const std::string type = "robodds::idl::PositionMeasurement";
  const auto schema = writer.add_schema(schema_name, "omgidl", idl_schema_text(type));
  const auto channel = writer.add_channel(schema, "sensor/position", "cdr", {});
  std::uint32_t sequence = 0;
  for (const Fix& f : fixes) {
    idl::PositionMeasurement m;
    m.robot_id(1);
    m.header().step(f.step);
    m.header().next_step(f.next_step);
    m.header().stamp_ns(static_cast<std::int64_t>(f.step) * 10'000'000);
    m.x(f.x);
    const std::vector<std::uint8_t> bytes = sample_codec().serialize(type, &m);
    writer.write(channel, ++sequence, 1000 + f.step, 1000 + f.step, bytes.data(), bytes.size());
  }
  writer.close();
  return path;
}

std::string scenario(const std::string& file, const std::string& topics = "[sensor/position]") {
  return ScenarioText("replay_node", 0.01, 0.04)  // steps 0..4
      .robots({1})
      .component("{name: replay, type: replay_source, params: {file: " + file + ", topics: " + topics + "}}");
}

TEST(ReplaySourceNode, PublishesEachSampleAtItsRecordedStepWithItsNextStep) {
  Harness h(scenario(recording({{0, 2, 10.0}, {2, 4, 12.0}, {4, 6, 14.0}})));
  const auto& fixes = h.record<idl::PositionMeasurement>("sensor/position");
  h.run({"replay"});
  ASSERT_EQ(fixes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(fixes[i].header().step(), 2 * i);
    EXPECT_EQ(fixes[i].header().next_step(), 2 * i + 2) << "the recorded next_step, not the source's period (1 step)";
    EXPECT_EQ(fixes[i].header().stamp_ns(), static_cast<std::int64_t>(2 * i) * 10'000'000);
    EXPECT_DOUBLE_EQ(fixes[i].x(), 10.0 + 2.0 * static_cast<double>(i));
    EXPECT_EQ(fixes[i].robot_id(), 1u);
  }
}

/// The DDS codec, counting the samples it decodes.
class CountingCodec : public SampleCodec {
 public:
  std::vector<std::uint8_t> serialize(const std::string& type_name, const void* sample) const override {
    return dds_->serialize(type_name, sample);
  }
  std::shared_ptr<void> deserialize(const std::string& type_name, const std::uint8_t* data, std::size_t size) const override {
    ++decoded;
    return dds_->deserialize(type_name, data, size);
  }
  mutable int decoded = 0;

 private:
  std::shared_ptr<const SampleCodec> dds_ = make_dds_sample_codec();
};

TEST(ReplaySourceNode, DecodesEachSampleOnceForTheDryConfiguresAndTheRun) {
  const auto codec = std::make_shared<CountingCodec>();
  set_sample_codec(codec);
  Harness h(scenario(recording({{0, 2, 10.0}, {2, 4, 12.0}, {4, 6, 14.0}})));
  // What `robodds run` does: the producer check's dry configure, then the run's configure (each a
  // new component object).
  scenario_producers(h.registry(), h.scenario(), TimeMode::kLockstep);
  const auto& fixes = h.record<idl::PositionMeasurement>("sensor/position");
  h.run({"replay"});
  EXPECT_EQ(fixes.size(), 3u);
  EXPECT_EQ(codec->decoded, 3) << "each recorded sample decoded once in the process";
  set_sample_codec(make_dds_sample_codec());
}

TEST(ReplaySourceNode, ARecordingRewrittenBetweenTwoRunsIsReadAgain) {
  const std::string schema = "robodds::idl::PositionMeasurement";
  const std::string path = recording({{0, 2, 10.0}, {2, 4, 12.0}, {4, 6, 14.0}}, schema, mcap::Compression::kNone);
  const auto size = std::filesystem::file_size(path);
  {
    Harness h(scenario(path));
    const auto& fixes = h.record<idl::PositionMeasurement>("sensor/position");
    h.run({"replay"});
    ASSERT_EQ(fixes.size(), 3u);
  }
  ASSERT_EQ(recording({{0, 2, 10.0}, {2, 6, 12.0}, {4, 6, 14.0}}, schema, mcap::Compression::kNone), path);
  ASSERT_EQ(std::filesystem::file_size(path), size) << "the same file, the same size: its stamp tells them apart";
  Harness h(scenario(path));
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find("the sample of step 2 announces step 6 but the next one recorded is of step 4"),
            std::string::npos);
}

TEST(ReplaySourceNode, ALostSampleStopsTheRunBeforeItStarts) {
  Harness h(scenario(recording({{0, 2, 10.0}, {4, 6, 14.0}})));
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find(
                "sensor/position (robot_id=1): the sample of step 0 announces step 2 but the next one recorded is of step 4"),
            std::string::npos);
}

TEST(ReplaySourceNode, ARecordingShorterThanTheRunIsRefused) {
  Harness h(scenario(recording({{0, 2, 10.0}, {2, 4, 12.0}})));
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find("the recording ends at step 2 but the run goes to step 4"), std::string::npos);
}

TEST(ReplaySourceNode, ATopicNotInTheFileIsNamed) {
  Harness h(scenario(recording({{0, kNeverAgain, 1.0}}), "[sensor/odometry]"));
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find("replay.topics: "), std::string::npos);
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find("has no topic 'sensor/odometry' (its topics: sensor/position)"),
            std::string::npos);
}

TEST(ReplaySourceNode, ASchemaThatIsNotOursIsNamed) {
  Harness h(scenario(recording({{0, kNeverAgain, 1.0}}, "their::Position")));
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find(
                "channel 'sensor/position' has schema 'their::Position' (omgidl), a schema that is not ours"),
            std::string::npos);
}

TEST(ReplaySourceNode, RealTimeIsRefused) {
  Harness h(scenario(recording({{0, kNeverAgain, 1.0}})));
  h.set_mode(TimeMode::kRealtime);
  EXPECT_NE(h.run_error<ConfigError>({"replay"}).find("replay_source runs in lockstep only"), std::string::npos);
}

/// A recording of sensor/uwb with the directions (robot, peer) at steps 0, 2, 4 (each announcing
/// the next, the last one step 6).
std::string uwb_recording(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& directions) {
  install_dds_sample_codec();
  const std::string path = test_support::write_test_file("uwb.mcap", "");
  mcap::Writer writer(path, mcap::WriterOptions{});
  const std::string type = "robodds::idl::UwbRanges";
  const auto channel = writer.add_channel(writer.add_schema(type, "omgidl", idl_schema_text(type)), "sensor/uwb", "cdr", {});
  std::uint32_t sequence = 0;
  for (std::uint64_t step = 0; step <= 4; step += 2) {
    for (const auto& [robot, peer] : directions) {
      idl::UwbRanges m;
      m.robot_id(robot);
      m.peer_id(peer);
      m.header().step(step);
      m.header().next_step(step + 2);
      m.header().stamp_ns(static_cast<std::int64_t>(step) * 10'000'000);
      const std::vector<std::uint8_t> bytes = sample_codec().serialize(type, &m);
      writer.write(channel, ++sequence, 1000 + step, 1000 + step, bytes.data(), bytes.size());
    }
  }
  writer.close();
  return path;
}

std::string uwb_scenario(const std::string& file) {
  return ScenarioText("replay_uwb", 0.01, 0.04)
      .robots({1, 2, 3})
      .component("{name: replay, type: replay_source, params: {file: " + file + ", topics: [sensor/uwb]}}");
}

TEST(ReplaySourceNode, DeclaresThePairsTheRecordingHoldsInTheDryConfigure) {
  Harness h(uwb_scenario(uwb_recording({{2, 3}, {1, 2}, {1, 3}})));
  // What every host finds before the run (RunContext::produced_instances): the recorded pairs.
  const ScenarioProducers producers = scenario_producers(h.registry(), h.scenario(), TimeMode::kLockstep);
  const ProducedInstances instances = produced_instances(h.registry(), h.scenario(), producers, TimeMode::kLockstep);
  ASSERT_EQ(instances.count("sensor/uwb"), 1u);
  EXPECT_EQ(instances.at("sensor/uwb"), (std::vector<std::uint64_t>{1ULL << 32 | 2, 1ULL << 32 | 3, 2ULL << 32 | 3}));
  const auto& ranges = h.record<idl::UwbRanges>("sensor/uwb");
  h.run({"replay"});
  EXPECT_EQ(ranges.size(), 9u) << "three directions at steps 0, 2, 4";
}

TEST(ReplaySourceNode, APairOfARobotTheScenarioDoesNotHaveIsRefused) {
  Harness h(uwb_scenario(uwb_recording({{1, 2}, {1, 4}})));
  const std::string error = h.run_error<ConfigError>({"replay"});
  EXPECT_NE(error.find("replay: "), std::string::npos) << error;
  EXPECT_NE(error.find("uwb.mcap cannot drive this run: sensor/uwb (robot_id=1 peer_id=4): robot 4 is not a robot of the "
                       "scenario (its robots: 1, 2, 3)"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace robodds::replay_source
