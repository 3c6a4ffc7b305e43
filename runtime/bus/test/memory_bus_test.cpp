// The in-memory bus keeps the delivery rules the lockstep contract relies on (write order,
// every reader, synchronous delivery, transient-local missions, safe reentrancy).
#include "runtime/bus/memory_bus.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

const std::string kState = "plant/state";
const std::string kStateType = idl::type_name<idl::RobotState>();
const std::string kMission = "mission/waypoints";
const std::string kMissionType = idl::type_name<idl::WaypointMission>();

idl::RobotState state(std::uint32_t robot, std::uint64_t step) {
  idl::RobotState s;
  s.robot_id(robot);
  s.header().step(step);
  return s;
}

idl::WaypointMission mission(std::uint32_t robot, double x) {
  idl::WaypointMission m;
  m.robot_id(robot);
  idl::Waypoint w;
  w.x(x);
  m.waypoints().push_back(w);
  return m;
}

/// Records (robot, step) of every RobotState it receives.
struct StateLog {
  std::vector<std::pair<std::uint32_t, std::uint64_t>> seen;
  SampleCallback callback() {
    return [this](const void* p, const SampleMeta&) {
      const auto& s = *static_cast<const idl::RobotState*>(p);
      seen.emplace_back(s.robot_id(), s.header().step());
    };
  }
};

const ReaderEventCallback kNoEvents = [](const std::string&) {};

TEST(MemoryBus, DeliversInWriteOrderInsideWrite) {
  MemoryBus bus;
  StateLog log;
  auto reader = bus.reader(kState, kStateType, "lockstep_local", log.callback(), kNoEvents);
  auto writer = bus.writer(kState, kStateType, "lockstep_local");
  const std::vector<std::pair<std::uint32_t, std::uint64_t>> written = {{1, 0}, {2, 0}, {1, 1}, {2, 1}, {1, 2}};
  for (const auto& [robot, step] : written) {
    idl::RobotState s = state(robot, step);
    writer->write(&s);
    // Synchronous: the sample is there before write() returns.
    ASSERT_EQ(log.seen.back(), std::make_pair(robot, step));
  }
  EXPECT_EQ(log.seen, written);
}

TEST(MemoryBus, EveryReaderAndEveryCallbackGetsEverySample) {
  MemoryBus bus;
  StateLog a, b, c;
  auto ra = bus.reader(kState, kStateType, "lockstep_local", a.callback(), kNoEvents);
  auto rb = bus.reader(kState, kStateType, "lockstep_local", b.callback(), kNoEvents);  // same reader, 2nd callback
  auto rc = bus.reader(kState, kStateType, "state", c.callback(), kNoEvents);           // another profile
  auto writer = bus.writer(kState, kStateType, "lockstep_local");
  for (std::uint64_t step = 0; step < 3; ++step) {
    idl::RobotState s = state(7, step);
    writer->write(&s);
  }
  const std::vector<std::pair<std::uint32_t, std::uint64_t>> expected = {{7, 0}, {7, 1}, {7, 2}};
  EXPECT_EQ(a.seen, expected);
  EXPECT_EQ(b.seen, expected);
  EXPECT_EQ(c.seen, expected);
}

// Every reader of one write shares one SampleMeta::checks_passed flag (Input<Msg> checks a
// sample's content once per delivery); each write starts with a fresh, unset one.
TEST(MemoryBus, TheReadersOfOneSampleShareOneChecksFlag) {
  MemoryBus bus;
  std::vector<std::pair<bool*, bool>> first, second;  // (flag, its value on arrival)
  auto ra = bus.reader(kState, kStateType, "lockstep_local", [&first](const void*, const SampleMeta& meta) {
    first.emplace_back(meta.checks_passed, meta.checks_passed != nullptr && *meta.checks_passed);
    *meta.checks_passed = true;
  }, kNoEvents);
  auto rb = bus.reader(kState, kStateType, "state", [&second](const void*, const SampleMeta& meta) {
    second.emplace_back(meta.checks_passed, meta.checks_passed != nullptr && *meta.checks_passed);
  }, kNoEvents);
  auto writer = bus.writer(kState, kStateType, "lockstep_local");
  for (std::uint64_t step = 0; step < 2; ++step) {
    idl::RobotState s = state(7, step);
    writer->write(&s);
  }
  ASSERT_EQ(first.size(), 2u);
  ASSERT_EQ(second.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_NE(first[i].first, nullptr);
    EXPECT_EQ(second[i].first, first[i].first) << "one flag for both readers of write " << i;
    EXPECT_FALSE(first[i].second) << "unset when write " << i << " starts";
    EXPECT_TRUE(second[i].second) << "set by the first reader of write " << i;
  }
}

TEST(MemoryBus, OneWriterPerTopicAndProfile) {
  MemoryBus bus;
  EXPECT_EQ(bus.writer(kState, kStateType, "lockstep_local"), bus.writer(kState, kStateType, "lockstep_local"));
  EXPECT_NE(bus.writer(kState, kStateType, "lockstep_local"), bus.writer(kState, kStateType, "state"));
}

TEST(MemoryBus, DestroyedReaderHandleStopsDelivery) {
  MemoryBus bus;
  StateLog log;
  auto writer = bus.writer(kState, kStateType, "lockstep_local");
  auto reader = bus.reader(kState, kStateType, "lockstep_local", log.callback(), kNoEvents);
  idl::RobotState s = state(1, 0);
  writer->write(&s);
  reader.reset();
  writer->write(&s);
  EXPECT_EQ(log.seen.size(), 1u);
}

TEST(MemoryBus, LateJoinerGetsNewestMissionPerInstanceButNoVolatileSamples) {
  MemoryBus bus;
  auto missions = bus.writer(kMission, kMissionType, "mission");
  auto states = bus.writer(kState, kStateType, "lockstep_local");
  idl::WaypointMission old1 = mission(1, 1.0), new1 = mission(1, 2.0), only2 = mission(2, 3.0);
  missions->write(&old1);
  missions->write(&only2);
  missions->write(&new1);
  idl::RobotState s = state(1, 0);
  states->write(&s);

  std::vector<std::pair<std::uint32_t, double>> got;
  auto mission_reader = bus.reader(kMission, kMissionType, "mission", [&got](const void* p, const SampleMeta&) {
    const auto& m = *static_cast<const idl::WaypointMission*>(p);
    got.emplace_back(m.robot_id(), m.waypoints().at(0).x());
  }, kNoEvents);
  StateLog late;
  auto state_reader = bus.reader(kState, kStateType, "lockstep_local", late.callback(), kNoEvents);

  // Newest per instance, in key order, delivered inside reader().
  EXPECT_EQ(got, (std::vector<std::pair<std::uint32_t, double>>{{1, 2.0}, {2, 3.0}}));
  EXPECT_TRUE(late.seen.empty()) << "a volatile topic must not replay old samples";
}

TEST(MemoryBus, EachSampleNamesItsWriterAndItsReceiveTime) {
  MemoryBus bus;
  auto first = bus.writer(kState, kStateType, "lockstep_local");
  auto second = bus.writer(kState, kStateType, "realtime");  // another profile: another writer
  std::vector<SampleMeta> metas;
  auto reader = bus.reader(kState, kStateType, "lockstep_local",
                           [&metas](const void*, const SampleMeta& meta) { metas.push_back(meta); }, kNoEvents);
  const std::int64_t before = monotonic_now_ns();
  idl::RobotState s = state(1, 0);
  first->write(&s);
  first->write(&s);
  second->write(&s);
  ASSERT_EQ(metas.size(), 3u);
  EXPECT_NE(metas[0].writer_id, 0u);
  EXPECT_EQ(metas[0].writer_id, metas[1].writer_id);
  EXPECT_NE(metas[0].writer_id, metas[2].writer_id);
  EXPECT_GE(metas[0].received_ns, before);
  EXPECT_LE(metas[2].received_ns, monotonic_now_ns());
  EXPECT_NE(bus.writer_name(metas[2].writer_id).find("plant/state|realtime"), std::string::npos)
      << bus.writer_name(metas[2].writer_id);
}

TEST(MemoryBus, VolatileReaderOfAMissionTopicGetsNoHistory) {
  MemoryBus bus;
  auto missions = bus.writer(kMission, kMissionType, "mission");
  idl::WaypointMission m = mission(1, 1.0);
  missions->write(&m);
  int count = 0;
  auto reader = bus.reader(kMission, kMissionType, "state", [&count](const void*, const SampleMeta&) { ++count; }, kNoEvents);
  EXPECT_EQ(count, 0);
}

TEST(MemoryBus, WriteFromACallbackIsSafeAndKeepsOneOrderForAllReaders) {
  MemoryBus bus;
  auto writer = bus.writer(kState, kStateType, "lockstep_local");
  // The first reader answers step 0 with step 100 on the same topic (reentrant write) and
  // subscribes a new callback from inside delivery: neither may deadlock.
  StateLog first, second, added;
  std::shared_ptr<ReaderHandle> added_reader;
  auto r1 = bus.reader(kState, kStateType, "lockstep_local", [&](const void* p, const SampleMeta&) {
    first.callback()(p, SampleMeta{});
    const auto& s = *static_cast<const idl::RobotState*>(p);
    if (s.header().step() == 0) {
      idl::RobotState echo = state(s.robot_id(), 100);
      writer->write(&echo);
      added_reader = bus.reader(kState, kStateType, "lockstep_local", added.callback(), kNoEvents);
    }
  }, kNoEvents);
  auto r2 = bus.reader(kState, kStateType, "lockstep_local", second.callback(), kNoEvents);

  idl::RobotState s0 = state(1, 0);
  writer->write(&s0);
  const std::vector<std::pair<std::uint32_t, std::uint64_t>> expected = {{1, 0}, {1, 100}};
  EXPECT_EQ(first.seen, expected);
  EXPECT_EQ(second.seen, expected) << "the reentrant write overtook the sample being delivered";
  EXPECT_TRUE(added.seen.empty()) << "subscribed after step 100 was written";

  idl::RobotState s1 = state(1, 1);
  writer->write(&s1);
  EXPECT_EQ(added.seen, (std::vector<std::pair<std::uint32_t, std::uint64_t>>{{1, 1}}));
}

TEST(MemoryBus, WrongOrUnknownTypeIsAConfigError) {
  MemoryBus bus;
  bus.writer(kState, kStateType, "lockstep_local");
  EXPECT_THROW(bus.reader(kState, kMissionType, "lockstep_local", [](const void*, const SampleMeta&) {}, kNoEvents), ConfigError);
  EXPECT_THROW(bus.writer("x/y", "robodds::idl::NoSuchType", "state"), ConfigError);
}

TEST(MemoryBus, FlushAndMatchReportAreEmpty) {
  MemoryBus bus;
  bus.flush(std::chrono::milliseconds(1));
  EXPECT_EQ(bus.match_report(), "");
}

}  // namespace
}  // namespace robodds
