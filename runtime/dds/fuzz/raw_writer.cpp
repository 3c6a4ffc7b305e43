// robodds-fuzz: publishes random payloads under our topic and type names into a running system,
// to show that no robodds process crashes or acts on garbage (tests/integration/fuzz_test.sh,
// docs/interop.md "Hostile input").
//
//   robodds-fuzz --domain D --topics plant/cmd,sensor/position [--count N] [--rate HZ] [--seed S]
//                [--key ID] [--kinds random,body,header] [--qos FILE]... [--participant-profile P]
//                [--match-timeout S]
//
// For every topic it registers the runtime's raw type support (runtime/dds/raw_type.hpp: the
// "serialization" copies caller-given bytes; a payload that decodes is written as the instance
// it encodes, one that does not as no instance) under the topic's IDL type name (topic catalog),
// and writes with the topic's real-time QoS profile (so reliable, deadline and liveliness readers
// match). Payload kinds, in turn:
//   random      random length 0..2*max (max: the type's largest serialized size incl. the 4-byte
//               encapsulation) and random bytes: mostly not even a valid encapsulation header;
//   body        a valid XCDR1 little-endian encapsulation header and random bytes, exactly as long
//               as a default sample of the type (fixed-size types: any such payload decodes);
//   header      a valid encapsulation header and random bytes of random length 4..2*max.
// --key ID writes ID as the first key member (robot_id) of the `body` payloads, so they decode
// as samples of that robot; without it the key is random too (samples of unknown robots).
// --kinds: the kinds written, in turn (default all three); `--kinds body` without --key is a
// flood of decodable samples of distinct unknown robots (tests/integration/key_flood_test.sh).
// Prints written_until_ns=<wall clock ns after the last payload>, then one line per topic
// (payloads written per kind, write failures, matched readers).
// --self-check: a second participant in this process reads every topic with the runtime's type
// support (make_type_support) and the topic's profile, and prints per topic what it decoded,
// what the type support dropped as undecodable, and Fast DDS's own sample_lost/sample_rejected
// statuses (which stay 0: Fast DDS 2.9 does not count a payload that does not decode).
// Exit status: 0 ok, 2 bad arguments or QoS file, 3 a topic found no reader in time, 1 other.
// Test tool: built in the build tree, not installed (it exists to send garbage).

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "runtime/dds/dds_bus.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/qos_files.hpp"
#include "runtime/dds/raw_type.hpp"
#include "runtime/dds/type_support.hpp"
#include "runtime/dds/undecodable.hpp"
#include "runtime/base/error.hpp"
#include "runtime/config/share_dir.hpp"
#include "runtime/topics/topic_catalog.hpp"

#ifndef ROBODDS_SOURCE_DIR
#define ROBODDS_SOURCE_DIR "."
#endif

namespace {

namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

struct Options {
  int domain = -1;
  std::vector<std::string> topics;
  std::uint64_t count = 1000;
  double rate_hz = 1000.0;
  std::uint64_t seed = 1;
  std::int64_t key = -1;
  std::vector<std::string> kinds = {"random", "body", "header"};
  std::vector<std::string> qos_files;
  std::string participant_profile = robodds::kDefaultParticipantProfile;
  double match_timeout_s = 15.0;
  bool self_check = false;
};

/// Takes every sample of one topic with the runtime's type support; counts the decoded ones.
class CheckListener : public dds::DataReaderListener {
 public:
  explicit CheckListener(const std::string& type_name) : type_(robodds::make_type_support(type_name)) {
    buffer_ = type_->createData();
  }
  ~CheckListener() override { type_->deleteData(buffer_); }
  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(buffer_, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        ++decoded;
      }
    }
  }
  dds::TypeSupport& type() { return type_; }
  std::atomic<std::uint64_t> decoded{0};

 private:
  dds::TypeSupport type_;
  void* buffer_ = nullptr;
};

/// The --self-check reader side: its own participant, so the type name can be registered with
/// the real (decoding) type support next to the raw one.
class SelfCheck {
 public:
  SelfCheck(int domain, const dds::DomainParticipantQos& qos, const std::string& profile) {
    dds::DomainParticipantQos named = qos;
    named.name("robodds-fuzz-check");
    participant_ = robodds::create_participant(domain, named, nullptr, dds::StatusMask::none(), profile);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (subscriber_ == nullptr) {
      throw robodds::RunError("could not create a subscriber");
    }
  }
  ~SelfCheck() { participant_.reset(); }  // before the listeners (members die in reverse order)

  void add(const robodds::TopicInfo& topic) {
    auto listener = std::make_unique<CheckListener>(topic.type_name);
    if (listener->type().register_type(participant_.get()) != ReturnCode_t::RETCODE_OK) {
      throw robodds::RunError("self-check: could not register type " + topic.type_name);
    }
    dds::Topic* t = participant_->create_topic(topic.name, topic.type_name, dds::TOPIC_QOS_DEFAULT);
    const std::string profile = robodds::qos_profile_for(topic, robodds::TimeMode::kRealtime, false);
    dds::DataReader* reader = t == nullptr ? nullptr
                                           : subscriber_->create_datareader_with_profile(t, profile, listener.get(),
                                                                                         dds::StatusMask::data_available());
    if (reader == nullptr) {
      throw robodds::RunError("self-check: cannot create a reader on " + topic.name + " with QoS profile '" + profile + "'");
    }
    entries_.push_back({&topic, reader, std::move(listener)});
  }

  void report(std::ostream& out) const {
    for (const Entry& e : entries_) {
      dds::SampleLostStatus lost;
      dds::SampleRejectedStatus rejected;
      e.reader->get_sample_lost_status(lost);
      e.reader->get_sample_rejected_status(rejected);
      out << "check " << e.topic->name << " decoded=" << e.listener->decoded.load()
          << " undecodable=" << robodds::undecodable_samples(e.topic->type_name) << " fastdds_sample_lost=" << lost.total_count
          << " fastdds_sample_rejected=" << rejected.total_count << std::endl;
    }
  }

 private:
  struct Entry {
    const robodds::TopicInfo* topic;
    dds::DataReader* reader;
    std::unique_ptr<CheckListener> listener;
  };
  std::vector<Entry> entries_;  // listeners: declared before the participant, outlive it
  robodds::ParticipantPtr participant_;
  dds::Subscriber* subscriber_ = nullptr;
};

struct Target {
  const robodds::TopicInfo* topic = nullptr;
  std::uint32_t max_size = 0;      // largest serialized size incl. encapsulation
  std::uint32_t default_size = 0;  // serialized size of a default sample incl. encapsulation
  dds::DataWriter* writer = nullptr;
  std::uint64_t written[3] = {0, 0, 0};
  std::uint64_t failed = 0;
};

constexpr const char* kKindNames[3] = {"random", "body", "header"};

/// Sizes of the real type: the largest serialized size and that of a default sample.
void measure(Target& target) {
  std::unique_ptr<dds::TopicDataType> real(robodds::make_type_support(target.topic->type_name));
  if (!real) {
    throw robodds::ConfigError("topic " + target.topic->name + ": no type support for " + target.topic->type_name);
  }
  target.max_size = real->m_typeSize;
  void* sample = real->createData();
  target.default_size = real->getSerializedSizeProvider(sample)();
  real->deleteData(sample);
}

robodds::RawPayload make_payload(int kind, const Target& target, std::int64_t key, std::mt19937_64& rng) {
  robodds::RawPayload s;
  std::uniform_int_distribution<int> byte(0, 255);
  std::size_t size = 0;
  if (kind == 0) {
    size = std::uniform_int_distribution<std::size_t>(0, 2 * std::size_t{target.max_size})(rng);
  } else if (kind == 1) {
    size = target.default_size;
  } else {
    size = std::uniform_int_distribution<std::size_t>(4, 2 * std::size_t{target.max_size})(rng);
  }
  s.bytes.resize(size);
  for (auto& b : s.bytes) {
    b = static_cast<unsigned char>(byte(rng));
  }
  if (kind != 0 && size >= 4) {
    // XCDR1 (PLAIN_CDR) little endian, options 0.
    s.bytes[0] = 0x00;
    s.bytes[1] = 0x01;
    s.bytes[2] = 0x00;
    s.bytes[3] = 0x00;
  }
  if (kind == 1 && key >= 0 && size >= 8) {
    for (int i = 0; i < 4; ++i) {
      s.bytes[4 + i] = static_cast<unsigned char>((static_cast<std::uint64_t>(key) >> (8 * i)) & 0xff);
    }
  }
  return s;
}

int run(const Options& o) {
  robodds::DdsOptions dds_options;
  dds_options.domain_id = o.domain;
  dds_options.qos_files = o.qos_files;
  if (dds_options.qos_files.empty()) {
    dds_options.qos_files.push_back(robodds::share_dir_of_this_process(ROBODDS_SOURCE_DIR) + "/" + robodds::kShareDirMarker);
  }
  dds_options.participant_profile = o.participant_profile;
  dds_options.participant_name = "robodds-fuzz";
  dds::DomainParticipantQos participant_qos = robodds::checked_participant_qos(dds_options);
  participant_qos.name("robodds-fuzz");

  std::vector<Target> targets;
  for (const std::string& name : o.topics) {
    Target t;
    t.topic = &robodds::topic_info(name);
    measure(t);
    targets.push_back(t);
  }

  std::unique_ptr<SelfCheck> check;
  if (o.self_check) {
    check = std::make_unique<SelfCheck>(o.domain, participant_qos, o.participant_profile);
    for (const Target& t : targets) {
      check->add(*t.topic);
    }
  }
  robodds::ParticipantPtr participant = robodds::create_participant(o.domain, participant_qos, nullptr, dds::StatusMask::none(),
                                                                    o.participant_profile);
  dds::Publisher* publisher = participant->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  if (publisher == nullptr) {
    throw robodds::RunError("could not create a publisher");
  }
  for (Target& t : targets) {
    dds::TypeSupport support(new robodds::RawPayloadType(t.topic->type_name, 2 * t.max_size + 8));
    if (support.register_type(participant.get()) != ReturnCode_t::RETCODE_OK) {
      throw robodds::RunError("could not register type " + t.topic->type_name);
    }
    dds::Topic* topic = participant->create_topic(t.topic->name, t.topic->type_name, dds::TOPIC_QOS_DEFAULT);
    if (topic == nullptr) {
      throw robodds::RunError("could not create topic " + t.topic->name);
    }
    const std::string profile = robodds::qos_profile_for(*t.topic, robodds::TimeMode::kRealtime, false);
    t.writer = publisher->create_datawriter_with_profile(topic, profile);
    if (t.writer == nullptr) {
      throw robodds::ConfigError("cannot create a writer on " + t.topic->name + " with QoS profile '" + profile + "'");
    }
  }

  // Wait (bounded) until every writer has a reader (besides the self-check one).
  const int wanted_readers = o.self_check ? 2 : 1;
  const auto match_deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.match_timeout_s);
  for (const Target& t : targets) {
    for (;;) {
      dds::PublicationMatchedStatus status;
      t.writer->get_publication_matched_status(status);
      if (status.current_count >= wanted_readers) {
        break;
      }
      if (std::chrono::steady_clock::now() > match_deadline) {
        std::cerr << "error: robodds-fuzz: no reader of " << t.topic->name << (o.self_check ? " (besides the self-check one)" : "") << " matched on domain " << o.domain << " within "
                  << o.match_timeout_s << " s\n";
        return 3;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

  std::vector<int> kinds;
  for (const std::string& name : o.kinds) {
    kinds.push_back(static_cast<int>(std::find(std::begin(kKindNames), std::end(kKindNames), name) - std::begin(kKindNames)));
  }
  std::mt19937_64 rng(o.seed);
  const auto period = std::chrono::duration<double>(1.0 / o.rate_hz);
  auto next = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < o.count; ++i) {
    const int kind = kinds[i % kinds.size()];
    for (Target& t : targets) {
      robodds::RawPayload sample = make_payload(kind, t, o.key, rng);
      if (t.writer->write(&sample)) {  // DataWriter::write(void*) returns bool in 2.9
        ++t.written[kind];
      } else {
        ++t.failed;
      }
    }
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
    std::this_thread::sleep_until(next);
  }
  const auto written_until = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch());
  std::cout << "written_until_ns=" << written_until.count() << std::endl;  // wall clock, as plant/state stamps
  for (const Target& t : targets) {
    dds::PublicationMatchedStatus status;
    t.writer->get_publication_matched_status(status);
    std::ostringstream line;
    line << "fuzz " << t.topic->name << " type=" << t.topic->type_name << " max_size=" << t.max_size
         << " default_size=" << t.default_size;
    for (int k = 0; k < 3; ++k) {
      line << " " << kKindNames[k] << "=" << t.written[k];
    }
    line << " write_failed=" << t.failed << " matched_readers=" << status.current_count;
    std::cout << line.str() << std::endl;
  }
  // Reliable writers: give readers a moment to acknowledge before the participant goes.
  for (const Target& t : targets) {
    t.writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(1, 0));
  }
  if (check) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // best-effort samples in flight
    check->report(std::cout);
  }
  // Empty the histories first: with thousands of random keys a KEEP_LAST writer holds one sample
  // per key, and Fast DDS 2.9's periodic heartbeat (GAPs for the holes in that history) kept the
  // writer's mutex busy enough to stall deleting it (seen with --self-check: > 60 s).
  for (const Target& t : targets) {
    std::size_t removed = 0;
    t.writer->clear_history(&removed);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"robodds-fuzz: random payloads under robodds topic and type names (a test tool)"};
  app.add_option("--domain", o.domain, "DDS domain id")->required()->check(CLI::Range(0, 232));
  app.add_option("--topics", o.topics, "topics to fuzz (catalog names)")->required()->delimiter(',');
  app.add_option("--count", o.count, "payloads per topic");
  app.add_option("--rate", o.rate_hz, "payloads per topic per second")->check(CLI::Range(1.0, 1e6));
  app.add_option("--seed", o.seed, "random seed");
  app.add_option("--key", o.key, "robot_id written into the `body` payloads (default: random)")->check(CLI::Range(std::int64_t{0}, std::int64_t{0xffffffff}));
  app.add_option("--kinds", o.kinds, "payload kinds written in turn: random, body, header (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"random", "body", "header"}));
  app.add_option("--qos", o.qos_files, "QoS XML file(s) (default: the share dir's deploy/qos/robodds_qos.xml)");
  app.add_option("--participant-profile", o.participant_profile, "participant profile");
  app.add_option("--match-timeout", o.match_timeout_s, "s, max wait for a reader of every topic")->check(CLI::Range(0.0, 3600.0));
  app.add_flag("--self-check", o.self_check, "also read every topic in this process and report what was decoded, "
                                             "dropped as undecodable, and Fast DDS's sample_lost/sample_rejected");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run(o);
  } catch (const robodds::ConfigError& e) {
    std::cerr << "error: robodds-fuzz: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: robodds-fuzz: " << e.what() << "\n";
    return 1;
  }
}
