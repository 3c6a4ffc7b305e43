// RawBus / RawPayloadType: samples read as their serialized bytes, byte-identical to what Fast
// CDR serialises, with their instances intact; raw writes reach typed readers (also key-filtered
// ones) as the samples they encode. Real DDS in this process, two participants, domain 154; each
// case its own topic (ctest may run the cases at the same time, and transient-local samples of
// one would reach the other's late readers).
#include "runtime/dds/raw_bus.hpp"

#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/dds/raw_type.hpp"
#include "runtime/dds/type_support.hpp"
#include "runtime/bus/sample_key.hpp"

namespace robodds {
namespace {

using eprosima::fastrtps::rtps::InstanceHandle_t;
using eprosima::fastrtps::rtps::SerializedPayload_t;

constexpr int kDomain = 154;

/// Every sample goes through a transport, as between processes: Fast DDS's intra-process delivery
/// hands a reader the writer's own change, key hash included, which would hide how a raw reader
/// learns a sample's instance on the wire. Called by each case before its first participant.
void over_the_wire() {
  eprosima::fastrtps::LibrarySettingsAttributes settings;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
}

DdsOptions options_named(const std::string& name) {
  over_the_wire();
  DdsOptions options;
  options.domain_id = kDomain;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  options.participant_name = name;
  return options;
}

/// What Fast CDR makes of `sample` through the generated type support: the reference bytes.
template <class Msg>
std::vector<std::uint8_t> serialized(const Msg& sample) {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(idl::type_name<Msg>()));
  SerializedPayload_t payload(type->m_typeSize);
  EXPECT_TRUE(type->serialize(const_cast<Msg*>(&sample), &payload));
  return std::vector<std::uint8_t>(payload.data, payload.data + payload.length);
}

struct Captured {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::vector<std::uint8_t>> payloads;
  std::vector<RawSample> meta;  // data pointers not valid after the callback
  template <class Pred>
  bool wait(Pred pred) {
    std::unique_lock<std::mutex> lock(mutex);
    return changed.wait_for(lock, std::chrono::seconds(10), [&] { return pred(payloads.size()); });
  }
};

RawSampleCallback capture_into(std::shared_ptr<Captured> captured) {
  return [captured](const RawSample& s) {
    std::lock_guard<std::mutex> lock(captured->mutex);
    captured->payloads.emplace_back(s.data, s.data + s.size);
    captured->meta.push_back(s);
    captured->changed.notify_all();
  };
}

TEST(RawBus, ReadsWhatATypedWriterWritesByteIdenticalToFastCdr) {
  auto captured = std::make_shared<Captured>();
  auto raw = make_raw_bus(options_named("raw_reader"));
  raw->reader("test/raw_capture", idl::type_name<idl::RobotState>(), "lockstep", capture_into(captured), nullptr);
  raw->start();
  auto typed = make_dds_bus(options_named("typed_writer"));
  auto writer = typed->writer("test/raw_capture", idl::type_name<idl::RobotState>(), "lockstep");
  std::vector<std::vector<std::uint8_t>> expected;
  const auto before = std::chrono::system_clock::now();
  for (int round = 0; round < 3; ++round) {
    for (std::uint32_t robot = 1; robot <= 4; ++robot) {
      idl::RobotState sample;
      sample.robot_id(robot);
      sample.x(0.1 * round + robot);
      sample.theta(-1.0 / 3.0);
      writer->write(&sample);
      expected.push_back(serialized(sample));
    }
  }
  ASSERT_TRUE(captured->wait([&](std::size_t n) { return n >= expected.size(); })) << "reliable, transient local: all arrive";
  raw->close_readers();
  std::lock_guard<std::mutex> lock(captured->mutex);
  ASSERT_EQ(captured->payloads.size(), expected.size());
  // One writer, in order: sample i is sample i.
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(captured->payloads[i], expected[i]) << "sample " << i;
    EXPECT_EQ(captured->payloads[i][0], 0x00) << "XCDR1 encapsulation header kept";
    EXPECT_EQ(captured->payloads[i][1], 0x01) << "CDR_LE";
  }
  const std::int64_t before_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(before.time_since_epoch()).count();
  std::set<std::array<std::uint8_t, 16>> writers;
  for (const RawSample& m : captured->meta) {
    EXPECT_GE(m.source_time_ns, before_ns - 1'000'000) << "the writer's source timestamp, ns since the epoch";
    EXPECT_GE(m.reception_time_ns, m.source_time_ns - 1'000'000) << "received after it was written (same clock)";
    EXPECT_LT(m.reception_time_ns - before_ns, 10'000'000'000);
    writers.insert(m.writer_guid);
  }
  EXPECT_EQ(writers.size(), 1u);
  EXPECT_NE(*writers.begin(), (std::array<std::uint8_t, 16>{})) << "the writer's GUID";
}

TEST(RawBus, ALateRawReaderGetsEveryInstanceOfATransientLocalTopic) {
  // `mission`: reliable, transient local, KEEP_LAST 1 per instance. The typed writer keeps one
  // sample per robot; the late raw reader must see five instances, not one.
  auto typed = make_dds_bus(options_named("typed_writer"));
  auto writer = typed->writer("test/raw_late_reader", idl::type_name<idl::WaypointMission>(), "mission");
  std::set<std::vector<std::uint8_t>> expected;
  std::set<std::array<std::uint8_t, 16>> expected_instances;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real(make_type_support(idl::type_name<idl::WaypointMission>()));
  for (std::uint32_t robot = 1; robot <= 5; ++robot) {
    idl::WaypointMission mission;
    mission.robot_id(robot);
    mission.waypoints().resize(robot);
    writer->write(&mission);
    expected.insert(serialized(mission));
    InstanceHandle_t handle;
    real->getKey(&mission, &handle, false);
    std::array<std::uint8_t, 16> instance;
    std::memcpy(instance.data(), handle.value, 16);
    expected_instances.insert(instance);
  }
  auto captured = std::make_shared<Captured>();
  auto raw = make_raw_bus(options_named("raw_reader"));
  raw->reader("test/raw_late_reader", idl::type_name<idl::WaypointMission>(), "mission", capture_into(captured), nullptr);
  raw->start();
  captured->wait([](std::size_t n) { return n >= 5; });
  raw->close_readers();
  std::lock_guard<std::mutex> lock(captured->mutex);
  EXPECT_EQ(std::set<std::vector<std::uint8_t>>(captured->payloads.begin(), captured->payloads.end()), expected);
  std::set<std::array<std::uint8_t, 16>> instances;
  for (const RawSample& m : captured->meta) {
    instances.insert(m.instance);
  }
  EXPECT_EQ(instances, expected_instances) << "the reader's instances are the robots, as the typed writer's";
}

TEST(RawBus, RawWritesReachTypedAndKeyFilteredReadersAsTheirSamplesWithTheirInstances) {
  auto typed = make_dds_bus(options_named("typed_reader"));
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::uint32_t> all, filtered;
  const std::string type = idl::type_name<idl::WaypointMission>();
  // Two profiles: two DDS readers, one of them behind the key filter (robot 2 only).
  typed->reader("test/raw_writer", type, "mission", [&](const void* p, const SampleMeta&) {
    std::lock_guard<std::mutex> lock(mutex);
    all.push_back(static_cast<const idl::WaypointMission*>(p)->robot_id());
    changed.notify_all();
  }, nullptr);
  const std::uint64_t robot2_key = sample_key_function(type)([] {
    static idl::WaypointMission m;
    m.robot_id(2);
    return static_cast<const void*>(&m);
  }());
  typed->filtered_reader("test/raw_writer", type, "lockstep", [&](const void* p, const SampleMeta&) {
    std::lock_guard<std::mutex> lock(mutex);
    filtered.push_back(static_cast<const idl::WaypointMission*>(p)->robot_id());
    changed.notify_all();
  }, nullptr, KeyFilter{[robot2_key](std::uint64_t key) { return key == robot2_key; }, nullptr});

  // Written twice per robot before any reader exists: a late reader gets the writer's history,
  // one sample per instance (KEEP_LAST 1): five only if the raw writer's instances are the robots,
  // and only if a replay's deeper history (256) leaves a transient-local profile's depth alone.
  auto raw = make_raw_bus(options_named("raw_writer"));
  auto writer = raw->writer("test/raw_writer", type, "mission", 256);
  for (int round = 0; round < 2; ++round) {
    for (std::uint32_t robot = 1; robot <= 5; ++robot) {
      idl::WaypointMission mission;
      mission.robot_id(robot);
      const std::vector<std::uint8_t> bytes = serialized(mission);
      ASSERT_TRUE(writer->write(bytes.data(), bytes.size()));
    }
  }
  typed->start();
  std::unique_lock<std::mutex> lock(mutex);
  changed.wait_for(lock, std::chrono::seconds(10), [&] { return all.size() >= 5 && !filtered.empty(); });
  changed.wait_for(lock, std::chrono::milliseconds(500), [&] { return all.size() > 5; });  // any sixth would come now
  lock.unlock();
  typed->close_readers();
  EXPECT_EQ(std::multiset<std::uint32_t>(all.begin(), all.end()), (std::multiset<std::uint32_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(filtered, std::vector<std::uint32_t>{2}) << "the key filter decodes the raw payload as any other";
}

TEST(RawBus, WatchWritersSeesAWriterComeAndGo) {
  // Its own domain (174, not the other cases' 154): the count must see only this case's writer.
  DdsOptions reader_options = options_named("raw_watcher");
  reader_options.domain_id = 174;
  auto bus = make_raw_bus(reader_options);
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<int> counts;
  const std::string type = idl::type_name<idl::RobotState>();
  bus->reader("test/raw_watch", type, "monitor", [](const RawSample&) {}, nullptr);
  bus->watch_writers("test/raw_watch", [&](int n) {
    std::lock_guard<std::mutex> lock(mutex);
    counts.push_back(n);
    changed.notify_all();
  });
  EXPECT_THROW(bus->watch_writers("test/no_reader", [](int) {}), ConfigError);
  bus->start();
  EXPECT_THROW(bus->watch_writers("test/raw_watch", [](int) {}), ConfigError) << "after start()";
  DdsOptions writer_options = options_named("raw_watched");
  writer_options.domain_id = 174;
  auto writer_bus = make_raw_bus(writer_options);
  auto writer = writer_bus->writer("test/raw_watch", type, "state", 0);
  std::unique_lock<std::mutex> lock(mutex);
  ASSERT_TRUE(changed.wait_for(lock, std::chrono::seconds(10), [&] { return !counts.empty(); })) << "no match";
  EXPECT_EQ(counts.back(), 1);
  lock.unlock();
  writer.reset();
  writer_bus.reset();  // the participant goes: its writer is unmatched
  lock.lock();
  ASSERT_TRUE(changed.wait_for(lock, std::chrono::seconds(10), [&] { return counts.back() == 0; })) << "no unmatch";
  lock.unlock();
  bus->close_readers();
}

TEST(RawPayloadType, MirrorsTheRealTypesKeyAndSizeAndComputesTheSameKey) {
  const std::string name = idl::type_name<idl::UwbRanges>();
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real(make_type_support(name));
  RawPayloadType raw(name);
  EXPECT_EQ(raw.m_isGetKeyDefined, real->m_isGetKeyDefined);
  EXPECT_EQ(raw.m_typeSize, real->m_typeSize);
  idl::UwbRanges sample;
  sample.robot_id(3);
  sample.peer_id(7);
  InstanceHandle_t expected;
  ASSERT_TRUE(real->getKey(&sample, &expected, false));
  RawPayload payload{serialized(sample)};
  InstanceHandle_t got;
  ASSERT_TRUE(raw.getKey(&payload, &got, false));
  EXPECT_EQ(got, expected);
  EXPECT_TRUE(got.isDefined());

  RawPayload garbage{{0x7f, 0x7f, 0, 0, 1, 2}};
  ASSERT_TRUE(raw.getKey(&garbage, &got, false));
  EXPECT_FALSE(got.isDefined()) << "no key for a payload that does not decode";

  const std::string unkeyed = idl::type_name<idl::SimTick>();
  EXPECT_EQ(RawPayloadType(unkeyed).m_isGetKeyDefined, std::unique_ptr<eprosima::fastdds::dds::TopicDataType>(
                                                            make_type_support(unkeyed))->m_isGetKeyDefined);
}

TEST(RawPayloadType, RawReadersAskForTheKeyHashInline) {
  eprosima::fastdds::dds::DataReaderQos profile;
  EXPECT_FALSE(profile.expects_inline_qos());
  EXPECT_TRUE(raw_reader_qos(profile).expects_inline_qos());
}

TEST(RawPayloadType, AnUnknownTypeIsAConfigErrorNamingIt) {
  try {
    RawPayloadType raw("robodds::idl::NoSuchType");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("robodds::idl::NoSuchType"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace robodds
