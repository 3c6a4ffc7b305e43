// FastDdsBus::undecodable_samples(): the type support's per-type counts, credited to the topics
// this bus reads. A real participant on domain 83 (the counters helper's test domain); no reader
// is started, so nothing goes on the wire.
// FastDdsBus::expect_robots(): a lockstep topic's instances spread over several writers, seen by
// a reader of another participant (real DDS, in this process), each test case on its own domain
// (ctest runs the cases as separate processes, possibly at the same time).
// WriterHandle::end_instance(): once its samples are acknowledged the writer keeps nothing for
// late joiners (the history whose oldest samples made every heartbeat walk a growing gap).
#include "runtime/dds/dds_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "robodds/idl/robodds.h"
#include "runtime/dds/type_support.hpp"

namespace robodds {
namespace {

TEST(FastDdsBus, CreditsItsInputTopicsWithTheUndecodableSamplesOfTheirType) {
  DdsOptions options;
  options.domain_id = 83;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  auto bus = make_dds_bus(options);
  const std::string type_name = "robodds::idl::VelocityCommand";
  bus->reader("plant/cmd", type_name, "command", [](const void*, const SampleMeta&) {}, nullptr);
  EXPECT_EQ(bus->undecodable_samples().count("plant/cmd"), 0u) << "nothing dropped yet";

  // A payload with a bad encapsulation header, as the Fast DDS reader would hand it over.
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> type(make_type_support(type_name));
  eprosima::fastrtps::rtps::SerializedPayload_t payload(8);
  const unsigned char bytes[8] = {0x7f, 0x7f, 0, 0, 1, 2, 3, 4};
  std::memcpy(payload.data, bytes, sizeof bytes);
  payload.length = sizeof bytes;
  idl::VelocityCommand sample;
  EXPECT_FALSE(type->deserialize(&payload, &sample));
  EXPECT_FALSE(type->deserialize(&payload, &sample));

  const auto counts = bus->undecodable_samples();
  ASSERT_EQ(counts.count("plant/cmd"), 1u);
  EXPECT_EQ(counts.at("plant/cmd"), 2u);
  EXPECT_EQ(counts.size(), 1u) << "only the topics this bus reads";
}

/// Robot id -> the writer ids its samples came from, as a reader on another participant saw them.
struct WritersSeen {
  std::mutex mutex;
  std::condition_variable changed;
  std::map<std::uint32_t, std::set<std::uint64_t>> by_robot;
  std::size_t samples = 0;
};

/// `robots` robots' RobotState written `rounds` times on `topic` with `profile` through a bus on
/// `domain` that expects `expected` robots; returns what the reader saw (after all arrived, or 10 s).
std::map<std::uint32_t, std::set<std::uint64_t>> writers_seen(int domain, const char* topic, std::size_t expected,
                                                              std::uint32_t robots, int rounds, const char* profile) {
  DdsOptions options;
  options.domain_id = domain;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  const std::string type_name = "robodds::idl::RobotState";
  auto seen = std::make_shared<WritersSeen>();
  options.participant_name = "spread_reader";
  auto reader_bus = make_dds_bus(options);
  reader_bus->reader(topic, type_name, profile, [seen](const void* p, const SampleMeta& meta) {
    const auto* sample = static_cast<const idl::RobotState*>(p);
    std::lock_guard<std::mutex> lock(seen->mutex);
    seen->by_robot[sample->robot_id()].insert(meta.writer_id);
    ++seen->samples;
    seen->changed.notify_all();
  }, nullptr);
  reader_bus->start();
  options.participant_name = "spread_writer";
  auto writer_bus = make_dds_bus(options);
  writer_bus->expect_robots(expected);
  auto writer = writer_bus->writer(topic, type_name, profile);
  for (int round = 0; round < rounds; ++round) {
    for (std::uint32_t robot = 1; robot <= robots; ++robot) {
      idl::RobotState sample;
      sample.robot_id(robot);
      sample.x(round);
      writer->write(&sample);
    }
  }
  std::unique_lock<std::mutex> lock(seen->mutex);
  seen->changed.wait_for(lock, std::chrono::seconds(10), [&] { return seen->samples >= robots * static_cast<std::size_t>(rounds); });
  EXPECT_EQ(seen->samples, robots * static_cast<std::size_t>(rounds)) << "transient-local + reliable: every sample arrives";
  auto result = seen->by_robot;
  lock.unlock();
  reader_bus->close_readers();
  return result;
}

std::set<std::uint64_t> all_writers(const std::map<std::uint32_t, std::set<std::uint64_t>>& by_robot) {
  std::set<std::uint64_t> all;
  for (const auto& [robot, writers] : by_robot) {
    all.insert(writers.begin(), writers.end());
  }
  return all;
}

TEST(FastDdsBus, SpreadsALockstepTopicsInstancesOverWritersOf32AndKeepsEachOnOne) {
  const auto by_robot = writers_seen(85, "plant/state", 70, 70, 3, "lockstep");
  ASSERT_EQ(by_robot.size(), 70u);
  for (const auto& [robot, writers] : by_robot) {
    EXPECT_EQ(writers.size(), 1u) << "robot " << robot << ": one producer per instance, every round";
  }
  EXPECT_EQ(all_writers(by_robot).size(), 3u) << "70 robots, one writer per 32";
}

TEST(FastDdsBus, KeepsOneWriterForFewRobotsOtherProfilesAndTopicsNotKeyedByRobot) {
  EXPECT_EQ(all_writers(writers_seen(89, "plant/state", 3, 3, 2, "lockstep")).size(), 1u);
  EXPECT_EQ(all_writers(writers_seen(89, "estimate/pose", 70, 40, 1, "mission")).size(), 1u)
      << "only the deep lockstep history is spread";
  // A topic outside the catalog has no known key: one writer (sim/step_done, keyed by host member,
  // is left alone the same way, by its catalog key).
  EXPECT_EQ(all_writers(writers_seen(89, "test/not_in_catalog", 70, 40, 1, "lockstep")).size(), 1u);
}

/// Robot ids of the RobotState samples a transient-local reader that matches now gets from the
/// writers' histories on `domain` (within `wait`).
std::multiset<std::uint32_t> late_reader_gets(const DdsOptions& options, const char* profile, std::chrono::milliseconds wait) {
  auto seen = std::make_shared<WritersSeen>();
  auto bus = make_dds_bus(options);
  bus->reader("plant/state", "robodds::idl::RobotState", profile, [seen](const void* p, const SampleMeta&) {
    std::lock_guard<std::mutex> lock(seen->mutex);
    seen->by_robot[static_cast<const idl::RobotState*>(p)->robot_id()].insert(seen->samples++);
  }, nullptr);
  bus->start();
  std::this_thread::sleep_for(wait);
  bus->close_readers();
  std::lock_guard<std::mutex> lock(seen->mutex);
  std::multiset<std::uint32_t> robots;
  for (const auto& [robot, samples] : seen->by_robot) {
    for (std::size_t i = 0; i < samples.size(); ++i) {
      robots.insert(robot);
    }
  }
  return robots;
}

TEST(FastDdsBus, AnEndedInstanceEmptiesTheWritersHistoryOnceEveryReaderHasIt) {
  DdsOptions options;
  options.domain_id = 139;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  const std::string type_name = "robodds::idl::RobotState";
  // A matched reader first: the emptying must wait for its acknowledgements, and it loses nothing.
  auto seen = std::make_shared<WritersSeen>();
  options.participant_name = "forget_reader";
  auto reader_bus = make_dds_bus(options);
  reader_bus->reader("plant/state", type_name, "lockstep", [seen](const void*, const SampleMeta&) {
    std::lock_guard<std::mutex> lock(seen->mutex);
    ++seen->samples;
    seen->changed.notify_all();
  }, nullptr);
  reader_bus->start();
  options.participant_name = "forget_writer";
  auto writer_bus = make_dds_bus(options);
  auto writer = writer_bus->writer("plant/state", type_name, "lockstep");
  const auto write = [&](std::uint32_t robot) {
    idl::RobotState sample;
    sample.robot_id(robot);
    writer->write(&sample);
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!writer->has_matched_readers() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(writer->has_matched_readers()) << "the reader did not match within 10 s";
  for (int round = 0; round < 5; ++round) {
    write(1);
    write(2);
  }
  options.participant_name = "late_reader_before";
  const auto before = late_reader_gets(options, "lockstep", std::chrono::milliseconds(1500));
  EXPECT_EQ(before.count(1), 5u) << "transient local: a late reader gets the kept history";

  idl::RobotState ended;
  ended.robot_id(1);
  writer->end_instance(&ended);  // robot 1 ends; robot 2 goes on
  write(2);
  {
    std::unique_lock<std::mutex> lock(seen->mutex);
    seen->changed.wait_for(lock, std::chrono::seconds(10), [&] { return seen->samples >= 11; });
    EXPECT_EQ(seen->samples, 11u) << "the matched reader got every sample, also those written around the emptying";
  }
  options.participant_name = "late_reader_after";
  const auto after = late_reader_gets(options, "lockstep", std::chrono::milliseconds(1500));
  EXPECT_EQ(after.count(1), 0u) << "the ended instance's samples left the history";
  EXPECT_EQ(after.count(2), 1u) << "only robot 2's sample written after the emptying is kept";
  reader_bus->close_readers();
}

}  // namespace
}  // namespace robodds
