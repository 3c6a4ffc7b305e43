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
#include <optional>
#include <thread>
#include <vector>

#include <fastrtps/xmlparser/XMLProfileManager.h>

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

namespace robodds {
namespace {

/// Robot 1's RobotState of steps 0..99 (each announcing the next step) written on `topic` by one
/// bus and read by another bus's subscribers (domain 176; a topic per call, so that no reader of
/// an earlier call counts as matched), each with the step needs given (nullopt: every
/// sample). Returns the steps each subscriber got, once `expected` samples arrived in all (or 10 s)
/// and 0.3 s more, and the reader bus' samples_left_out_on_arrival().
struct StepsSeen {
  std::vector<std::vector<std::uint64_t>> by_subscriber;
  std::uint64_t left_out_on_arrival = 0;
};
StepsSeen steps_seen(const char* topic, const std::vector<std::optional<StepNeeds>>& subscribers, std::size_t expected) {
  // Through the transport, as between processes: Fast DDS filters writer-side only for a reader
  // of another process (DataWriterImpl: never between participants with intra-process delivery).
  eprosima::fastrtps::LibrarySettingsAttributes settings;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
  DdsOptions options;
  options.domain_id = 176;
  options.qos_files = {std::string(ROBODDS_SOURCE_DIR) + "/deploy/qos/robodds_qos.xml"};
  const std::string type_name = "robodds::idl::RobotState";
  struct Shared {
    std::mutex mutex;
    std::condition_variable changed;
    std::vector<std::vector<std::uint64_t>> steps;
    std::size_t samples = 0;
  };
  auto seen = std::make_shared<Shared>();
  seen->steps.resize(subscribers.size());
  options.participant_name = "steps_reader";
  auto reader_bus = make_dds_bus(options);
  for (std::size_t i = 0; i < subscribers.size(); ++i) {
    auto handle = reader_bus->reader(topic, type_name, "lockstep", [seen, i](const void* p, const SampleMeta&) {
      std::lock_guard<std::mutex> lock(seen->mutex);
      seen->steps[i].push_back(static_cast<const idl::RobotState*>(p)->header().step());
      ++seen->samples;
      seen->changed.notify_all();
    }, nullptr);
    if (subscribers[i]) {
      handle->set_step_needs(*subscribers[i]);
    }
  }
  reader_bus->start();
  options.participant_name = "steps_writer";
  auto writer_bus = make_dds_bus(options);
  auto writer = writer_bus->writer(topic, type_name, "lockstep");
  // Matched first, as a lockstep host is before its first step: a sample written before the
  // writer knows the reader carries no verdict for it (the reader's own filter judges it). Both
  // sides: a sample that reaches the reader before it knows the writer is dropped there, and the
  // repair sends only what the writer's history (48 samples) still holds.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!(writer->has_matched_readers() && reader_bus->match_report().empty()) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(writer->has_matched_readers()) << "the reader did not match within 10 s";
  EXPECT_EQ(reader_bus->match_report(), "") << "the writer did not match within 10 s";
  for (std::uint64_t step = 0; step < 100; ++step) {
    idl::RobotState sample;
    sample.robot_id(1);
    sample.header().step(step);
    sample.header().next_step(step + 1);
    writer->write(&sample);
  }
  std::unique_lock<std::mutex> lock(seen->mutex);
  seen->changed.wait_for(lock, std::chrono::seconds(10), [&] { return seen->samples >= expected; });
  lock.unlock();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // nothing more may come
  lock.lock();
  StepsSeen result{seen->steps, reader_bus->samples_left_out_on_arrival()};
  lock.unlock();
  reader_bus->close_readers();
  return result;
}

std::vector<std::uint64_t> steps_from_to(std::uint64_t first, std::uint64_t end, std::uint64_t stride) {
  std::vector<std::uint64_t> steps;
  for (std::uint64_t s = first; s < end; s += stride) {
    steps.push_back(s);
  }
  return steps;
}

TEST(FastDdsBus, TheWriterSendsANewestOnlyReaderOnlyTheStepsItReads) {
  const StepsSeen seen = steps_seen("plant/state", {StepNeeds::of_component(10, 0, 1)}, 10);
  ASSERT_EQ(seen.by_subscriber.size(), 1u);
  EXPECT_EQ(seen.by_subscriber[0], steps_from_to(9, 100, 10)) << "the states of steps 9, 19, ..., 99, in order";
  EXPECT_EQ(seen.left_out_on_arrival, 0u) << "a robodds writer leaves the other 90 out itself: none reached the reader";
}

TEST(FastDdsBus, AReaderGetsEverySampleAnyOfItsSubscribersReads) {
  StepNeeds ten = StepNeeds::of_component(10, 0, 0);
  StepNeeds four = StepNeeds::of_component(4, 0, 0);
  StepNeeds both = ten;
  both.add(four);
  std::vector<std::uint64_t> union_steps;
  for (std::uint64_t s = 0; s < 100; ++s) {
    if (both.needs(s, s + 1)) union_steps.push_back(s);
  }
  const StepsSeen two = steps_seen("test/steps_union", {ten, four}, 2 * union_steps.size());
  EXPECT_EQ(two.by_subscriber[0], union_steps) << "one DDS reader, one stream: the union of the needs";
  EXPECT_EQ(two.by_subscriber[1], union_steps);

  const StepsSeen with_all = steps_seen("test/steps_all", {ten, std::nullopt}, 200);
  EXPECT_EQ(with_all.by_subscriber[0], steps_from_to(0, 100, 1)) << "a subscriber that reads every sample gets every sample";
  EXPECT_EQ(with_all.by_subscriber[1], steps_from_to(0, 100, 1));
}

}  // namespace
}  // namespace robodds
