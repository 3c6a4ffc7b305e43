// The co-located bus: components' samples reach this process's readers in memory, inside
// write(); the network side only gets writes (while a reader is matched there, or always for the
// transient-local mission profile) and, in lockstep, never a reader; in real time (kOpen) the
// readers of topics no component here produces are the network's.
#include "runtime/bus/colocated_bus.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/bus/qos_profiles.hpp"

namespace robodds {
namespace {

const std::string kState = "plant/state";
const std::string kStateType = idl::type_name<idl::RobotState>();
const ReaderEventCallback kNoEvents = [](const std::string&) {};

/// Stands for the DDS bus: counts writes per topic and reader requests; its writers report
/// `matched` as their matched-reader state.
class NetworkStandIn : public Bus {
 public:
  struct Writer : public WriterHandle {
    explicit Writer(NetworkStandIn* bus, std::string topic) : bus_(bus), topic_(std::move(topic)) {}
    void write(const void*) override { ++bus_->writes; }
    const std::string& topic() const override { return topic_; }
    bool has_matched_readers() const override { return bus_->matched; }
    NetworkStandIn* bus_;
    std::string topic_;
  };
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string&, const std::string&) override {
    ++writers_made;
    return std::make_shared<Writer>(this, topic);
  }
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string&, const std::string&, SampleCallback,
                                       ReaderEventCallback) override {
    ++readers_made;
    read_topics.push_back(topic);
    return nullptr;
  }
  std::shared_ptr<ReaderHandle> filtered_reader(const std::string& topic, const std::string&, const std::string&,
                                                SampleCallback, ReaderEventCallback, KeyFilter) override {
    ++filtered_readers_made;
    read_topics.push_back(topic);
    return nullptr;
  }
  std::string writer_name(std::uint64_t writer_id) const override { return "dds writer " + std::to_string(writer_id); }
  bool writer_runs_any(std::uint64_t writer_id, const std::vector<std::string>&) const override {
    return writer_id == kAnnouncedWriter;
  }
  std::map<std::string, std::uint64_t> undecodable_samples() const override { return {{"plant/cmd", 3}}; }

  static constexpr std::uint64_t kAnnouncedWriter = 0xabcdef0123456789ULL;
  void flush(std::chrono::milliseconds) override { ++flushes; }

  bool matched = false;
  int writes = 0;
  int writers_made = 0;
  int readers_made = 0;
  int filtered_readers_made = 0;
  int flushes = 0;
  std::vector<std::string> read_topics;
};

idl::RobotState state(std::uint32_t robot, std::uint64_t step) {
  idl::RobotState s;
  s.robot_id(robot);
  s.header().step(step);
  return s;
}

TEST(ColocatedBus, ReadersGetSamplesInMemoryAndTheNetworkOnlyWhileMatched) {
  NetworkStandIn network;
  ColocatedBus bus(network);
  std::vector<std::uint64_t> seen;
  auto reader = bus.reader(kState, kStateType, kLockstepLocalProfile,
                           [&seen](const void* p, const SampleMeta& meta) {
                             EXPECT_NE(meta.writer_id, 0U);
                             seen.push_back(static_cast<const idl::RobotState*>(p)->header().step());
                           },
                           kNoEvents);
  EXPECT_EQ(network.readers_made, 0);  // a closed world: nothing from the network reaches it
  auto writer = bus.writer(kState, kStateType, kLockstepLocalProfile);
  const idl::RobotState s0 = state(1, 0);
  writer->write(&s0);
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{0}));  // delivered inside write()
  EXPECT_EQ(network.writes, 0);                      // no observer: nothing written to DDS
  network.matched = true;                            // `robodds echo` joined
  const idl::RobotState s1 = state(1, 1);
  writer->write(&s1);
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{0, 1}));
  EXPECT_EQ(network.writes, 1);
  bus.flush(std::chrono::milliseconds(1));
  EXPECT_EQ(network.flushes, 1);
}

TEST(ColocatedBus, MissionsAreAlwaysWrittenForLateReaders) {
  NetworkStandIn network;
  ColocatedBus bus(network);
  auto writer = bus.writer("mission/waypoints", idl::type_name<idl::WaypointMission>(), kMissionProfile);
  idl::WaypointMission m;
  m.robot_id(1);
  writer->write(&m);
  EXPECT_EQ(network.writes, 1);  // transient local: a reader matched later still gets it
}

TEST(ColocatedBus, OneWriterPerTopicAndProfile) {
  NetworkStandIn network;
  ColocatedBus bus(network);
  auto a = bus.writer(kState, kStateType, kLockstepLocalProfile);
  auto b = bus.writer(kState, kStateType, kLockstepLocalProfile);
  EXPECT_EQ(a, b);
  EXPECT_EQ(network.writers_made, 1);
  EXPECT_NE(bus.writer(kState, kStateType, kMissionProfile), a);
}

TEST(ColocatedBus, RealTimeReadsTopicsProducedHereInMemoryAndTheOthersFromTheNetwork) {
  NetworkStandIn network;
  ColocatedBus bus(network, ColocatedWorld::kOpen, {kState});
  std::vector<std::uint64_t> writers_seen;
  auto local = bus.reader(kState, kStateType, "state",
                          [&writers_seen](const void*, const SampleMeta& meta) { writers_seen.push_back(meta.writer_id); },
                          kNoEvents);
  EXPECT_EQ(network.readers_made, 0);  // produced here: in memory only
  const KeyFilter takes_all{[](std::uint64_t) { return true; }, [](std::uint64_t, std::uint64_t) {}};
  auto local_filtered = bus.filtered_reader(kState, kStateType, "state", [](const void*, const SampleMeta&) {}, kNoEvents,
                                            takes_all);
  EXPECT_EQ(network.filtered_readers_made, 0);
  // plant/cmd has no producer in this process (a commander outside the run): the network's reader.
  auto external = bus.reader("plant/cmd", idl::type_name<idl::VelocityCommand>(), "command",
                             [](const void*, const SampleMeta&) {}, kNoEvents);
  auto external_filtered = bus.filtered_reader("plant/cmd", idl::type_name<idl::VelocityCommand>(), "command",
                                               [](const void*, const SampleMeta&) {}, kNoEvents, takes_all);
  EXPECT_EQ(network.readers_made, 1);
  EXPECT_EQ(network.filtered_readers_made, 1);
  EXPECT_EQ(network.read_topics, (std::vector<std::string>{"plant/cmd", "plant/cmd"}));

  auto writer = bus.writer(kState, kStateType, "state");
  const idl::RobotState s0 = state(1, 0);
  writer->write(&s0);
  ASSERT_EQ(writers_seen.size(), 1U);
  EXPECT_EQ(network.writes, 0);  // no reader on the network: not written there
  // Writer ids: an in-memory writer is this process's; a DDS writer is judged by the network.
  const std::vector<std::string> components{"plant"};
  EXPECT_TRUE(bus.writer_runs_any(writers_seen[0], components));
  EXPECT_TRUE(bus.writer_runs_any(NetworkStandIn::kAnnouncedWriter, components));
  EXPECT_FALSE(bus.writer_runs_any(0x1234567812345678ULL, components));
  EXPECT_EQ(bus.writer_name(0x1234567812345678ULL), network.writer_name(0x1234567812345678ULL));
  EXPECT_NE(bus.writer_name(writers_seen[0]).find("in-memory writer"), std::string::npos);
  EXPECT_EQ(bus.undecodable_samples(), (std::map<std::string, std::uint64_t>{{"plant/cmd", 3}}));
}

TEST(ColocatedBus, LockstepIsAClosedWorldWhateverIsProducedHere) {
  NetworkStandIn network;
  ColocatedBus bus(network);
  auto reader = bus.reader("plant/cmd", idl::type_name<idl::VelocityCommand>(), kLockstepLocalProfile,
                           [](const void*, const SampleMeta&) {}, kNoEvents);
  EXPECT_EQ(network.readers_made, 0);
}

}  // namespace
}  // namespace robodds
