// The co-located lockstep bus: components' samples reach this process's readers in memory,
// inside write(); the network side only gets writes (while a reader is matched there, or always
// for the transient-local mission profile) and never a reader.
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
  std::shared_ptr<ReaderHandle> reader(const std::string&, const std::string&, const std::string&, SampleCallback,
                                       ReaderEventCallback) override {
    ++readers_made;
    return nullptr;
  }
  void flush(std::chrono::milliseconds) override { ++flushes; }

  bool matched = false;
  int writes = 0;
  int writers_made = 0;
  int readers_made = 0;
  int flushes = 0;
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

}  // namespace
}  // namespace robodds
