// Send batching (send_batch.hpp): samples a thread writes inside a batch reach a robodds reader
// only at the close, in order, split below the transport's message limit; a reader that is no
// robodds participant gets them at once; what a receiver splits never reads outside the buffer and
// hostile batches are counted. Real Fast DDS participants in this process on domain 180, over
// shared memory (UDP for the hostile datagrams); each case its own topic (ctest may run the cases
// at the same time).
#include "runtime/dds/send_batch.hpp"

#include <arpa/inet.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/dds/component_announcement.hpp"
#include "runtime/dds/match_report.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/type_support.hpp"

namespace robodds {
namespace {

namespace dds = eprosima::fastdds::dds;
namespace fr = eprosima::fastrtps::rtps;
using Clock = std::chrono::steady_clock;

constexpr int kDomain = 180;

/// Every sample goes through a transport, as between processes (Fast DDS would hand a reader in the
/// same process the writer's change directly). Called before a case's first participant.
void over_the_wire() {
  eprosima::fastrtps::LibrarySettingsAttributes settings;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
}

enum class Transport { kShm, kUdp };

/// Shared memory only (with `max_message_size`) or UDPv4 only; `robodds`: announces a component in
/// its user data.
dds::DomainParticipantQos participant_qos(const std::string& name, bool robodds, std::uint32_t max_message_size,
                                          Transport transport) {
  dds::DomainParticipantQos qos;
  qos.name(name);
  qos.transport().use_builtin_transports = false;
  if (transport == Transport::kShm) {
    auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
    shm->max_message_size(max_message_size);
    qos.transport().user_transports = {shm};
  } else {
    qos.transport().user_transports = {std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>()};
  }
  if (robodds) {
    const std::vector<std::uint8_t> announcement = component_announcement({name});
    qos.user_data().data_vec(std::vector<fr::octet>(announcement.begin(), announcement.end()));
  }
  return qos;
}

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds limit = std::chrono::seconds(10)) {
  const auto end = Clock::now() + limit;
  while (!condition()) {
    if (Clock::now() > end) {
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

/// A writer participant (with the participant listener robodds uses: it registers the robodds
/// readers' locators) and a reader participant, one RobotState topic, best effort (a lost or
/// reordered message is not repaired: the order the reader sees is the order on the wire).
class Pair {
 public:
  Pair(const std::string& topic, bool reader_is_robodds, std::uint32_t max_message_size = 65500,
       Transport transport = Transport::kShm) {
    over_the_wire();
    writer_participant_ = create_participant(kDomain, participant_qos("writer", true, max_message_size, transport), &peers_,
                                             dds::StatusMask::none(), "test");
    reader_participant_ = create_participant(kDomain, participant_qos("reader", reader_is_robodds, max_message_size, transport),
                                             nullptr, dds::StatusMask::none(), "test");
    for (dds::DomainParticipant* participant : {writer_participant_.get(), reader_participant_.get()}) {
      dds::TypeSupport type(make_type_support("robodds::idl::RobotState"));
      EXPECT_EQ(type.register_type(participant), eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK);
    }
    dds::Topic* wtopic = writer_participant_->create_topic(topic, "robodds::idl::RobotState", dds::TOPIC_QOS_DEFAULT);
    dds::Topic* rtopic = reader_participant_->create_topic(topic, "robodds::idl::RobotState", dds::TOPIC_QOS_DEFAULT);
    dds::DataWriterQos wqos = dds::DATAWRITER_QOS_DEFAULT;
    wqos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
    wqos.history().kind = dds::KEEP_ALL_HISTORY_QOS;
    wqos.publish_mode().kind = dds::SYNCHRONOUS_PUBLISH_MODE;
    dds::DataReaderQos rqos = dds::DATAREADER_QOS_DEFAULT;
    rqos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
    rqos.history().kind = dds::KEEP_ALL_HISTORY_QOS;
    writer_ = writer_participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT)->create_datawriter(wtopic, wqos);
    reader_ = reader_participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT)->create_datareader(rtopic, rqos);
    EXPECT_NE(writer_, nullptr);
    EXPECT_NE(reader_, nullptr);
    matched_ = eventually([this] {
      dds::PublicationMatchedStatus published;
      dds::SubscriptionMatchedStatus subscribed;
      writer_->get_publication_matched_status(published);
      reader_->get_subscription_matched_status(subscribed);
      return published.current_count == 1 && subscribed.current_count == 1;
    });
  }

  bool matched() const { return matched_; }

  void write(double x) {
    idl::RobotState sample;
    sample.robot_id(1);  // one instance: take() returns its samples in arrival order
    sample.x(x);
    ASSERT_TRUE(writer_->write(&sample));
  }

  /// Appends the samples received so far to received().
  void take() {
    idl::RobotState sample;
    dds::SampleInfo info;
    while (reader_->take_next_sample(&sample, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        received_.push_back(sample.x());
      }
    }
  }
  bool received_at_least(std::size_t n) {
    return eventually([&] {
      take();
      return received_.size() >= n;
    });
  }
  const std::vector<double>& received() const { return received_; }

  void delete_writer_participant() { writer_participant_.reset(); }

 private:
  PeerDirectory peers_;  // outlives the participants
  ParticipantPtr writer_participant_;
  ParticipantPtr reader_participant_;
  dds::DataWriter* writer_ = nullptr;
  dds::DataReader* reader_ = nullptr;
  bool matched_ = false;
  std::vector<double> received_;
};

std::vector<double> zero_to(int n) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i) {
    values.push_back(i);
  }
  return values;
}

/// Writes 20 samples in a nested batch: nothing arrives before the outermost close, all of them in
/// order after it, in one batch per sender resource Fast DDS sends through (`senders`).
void only_at_the_close(Pair& pair, std::uint64_t senders) {
  const SendBatchCounters before = send_batch_counters();
  open_send_batch();
  open_send_batch();  // nested: only the outermost close sends
  for (int i = 0; i < 20; ++i) {
    pair.write(i);
  }
  close_send_batch();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  pair.take();
  EXPECT_TRUE(pair.received().empty()) << pair.received().size() << " samples arrived before the close";
  close_send_batch();
  ASSERT_TRUE(pair.received_at_least(20));
  EXPECT_EQ(pair.received(), zero_to(20));
  const SendBatchCounters after = send_batch_counters();
  EXPECT_EQ(after.batches_sent - before.batches_sent, senders);
  EXPECT_EQ(after.messages_batched - before.messages_batched, 20U * senders);
  EXPECT_EQ(after.malformed_received, before.malformed_received);
}

TEST(SendBatch, SamplesWrittenInABatchReachARoboddsReaderInOrderOnlyAtTheClose) {
  Pair pair("test/send_batch/at_close", true);
  ASSERT_TRUE(pair.matched());
  only_at_the_close(pair, 1);  // one: a second sender would send every message twice
}

// Over UDP (hosts on different machines): Debian's Fast DDS aborts on a send to a locator its UDP
// transport did not open a channel for (statistics bookkeeping). Its UDP transport has two senders
// here, the second one (bound to 127.0.0.1) for multicast only: it drops the unicast batch.
TEST(SendBatch, OverUdpToo) {
  Pair pair("test/send_batch/udp", true, 65500, Transport::kUdp);
  ASSERT_TRUE(pair.matched());
  only_at_the_close(pair, 2);
}

TEST(SendBatch, AReaderThatIsNoRoboddsParticipantGetsTheSamplesAtOnce) {
  Pair pair("test/send_batch/plain_reader", false);
  ASSERT_TRUE(pair.matched());
  const SendBatchCounters before = send_batch_counters();
  SendBatchScope batch;
  for (int i = 0; i < 5; ++i) {
    pair.write(i);
  }
  ASSERT_TRUE(pair.received_at_least(5)) << "a plain Fast DDS reader got nothing while the batch was open";
  EXPECT_EQ(pair.received(), zero_to(5));
  EXPECT_EQ(send_batch_counters().messages_batched, before.messages_batched);
}

TEST(SendBatch, ABatchLargerThanTheTransportsMessageLimitLeavesInSeveralMessages) {
  constexpr std::uint32_t kLimit = 2048;
  Pair pair("test/send_batch/split", true, kLimit);
  ASSERT_TRUE(pair.matched());
  const SendBatchCounters before = send_batch_counters();
  {
    SendBatchScope batch;
    for (int i = 0; i < 100; ++i) {
      pair.write(i);
    }
  }
  ASSERT_TRUE(pair.received_at_least(100)) << "received " << pair.received().size();
  EXPECT_EQ(pair.received(), zero_to(100));
  const SendBatchCounters after = send_batch_counters();
  EXPECT_LE(after.messages_batched - before.messages_batched, 100U);
  EXPECT_GE(after.messages_batched - before.messages_batched, 99U);  // (a last message alone leaves unwrapped)
  // Each message is over 100 bytes: 100 of them need more than 5 batches of 2 KiB.
  EXPECT_GT(after.batches_sent - before.batches_sent, 5U);
}

TEST(SendBatch, MessagesHeldForAParticipantDeletedBeforeTheCloseAreDropped) {
  Pair pair("test/send_batch/deleted", true);
  ASSERT_TRUE(pair.matched());
  const SendBatchCounters before = send_batch_counters();
  std::mutex mutex;
  std::condition_variable changed;
  int stage = 0;  // 1: the batch holds samples; 2: their participant is deleted
  auto wait_for = [&](int wanted) {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return stage >= wanted; });
  };
  auto advance = [&](int to) {
    std::lock_guard<std::mutex> lock(mutex);
    stage = to;
    changed.notify_all();
  };
  std::thread batching([&] {
    open_send_batch();
    for (int i = 0; i < 5; ++i) {
      pair.write(i);
    }
    advance(1);
    wait_for(2);
    close_send_batch();  // must not send through the deleted participant's transport
  });
  wait_for(1);
  pair.delete_writer_participant();
  advance(2);
  batching.join();
  EXPECT_EQ(send_batch_counters().batches_sent, before.batches_sent);
  pair.take();
  EXPECT_TRUE(pair.received().empty());
}

// ---- the receive splitter --------------------------------------------------------------------

/// An RTPS-looking message of `length` bytes (>= 20) filled with `fill` after the magic.
std::vector<std::uint8_t> rtps_message(std::size_t length, std::uint8_t fill) {
  std::vector<std::uint8_t> message(length, fill);
  std::memcpy(message.data(), "RTPS", 4);
  return message;
}

void put_length(std::vector<std::uint8_t>& out, std::uint32_t n) {
  for (int i = 0; i < 4; ++i) {
    out.push_back(static_cast<std::uint8_t>(n >> (8 * i)));
  }
}

/// A batch of `messages` as BatchingTransport sends it (end marker and trailer included).
std::vector<std::uint8_t> batch_of(const std::vector<std::vector<std::uint8_t>>& messages) {
  std::vector<std::uint8_t> batch = {'R', 'D', 'B', 'T'};
  for (const auto& message : messages) {
    put_length(batch, static_cast<std::uint32_t>(message.size()));
    batch.insert(batch.end(), message.begin(), message.end());
    batch.resize((batch.size() + 3) / 4 * 4, 0);
  }
  put_length(batch, 0);
  batch.resize(batch.size() + 64, 0);
  return batch;
}

struct Split {
  detail::BatchSplit result;
  std::vector<std::vector<std::uint8_t>> messages;
};

/// split_batch() over a copy of `buffer` in a heap block of exactly its size, every delivered
/// message checked to lie inside it.
Split split(const std::vector<std::uint8_t>& buffer) {
  const std::unique_ptr<std::uint8_t[]> exact(new std::uint8_t[buffer.size()]);
  std::copy(buffer.begin(), buffer.end(), exact.get());
  Split out;
  out.result = detail::split_batch(exact.get(), buffer.size(), [&](const std::uint8_t* message, std::uint32_t length) {
    EXPECT_GE(message, exact.get());
    EXPECT_LE(message + length, exact.get() + buffer.size());
    out.messages.emplace_back(message, message + length);
  });
  return out;
}

TEST(SendBatchSplit, AWellFormedBatchGivesItsMessagesInOrder) {
  const std::vector<std::vector<std::uint8_t>> messages = {rtps_message(21, 1), rtps_message(40, 2), rtps_message(23, 3)};
  const Split result = split(batch_of(messages));
  EXPECT_EQ(result.result, detail::BatchSplit::kWhole);
  EXPECT_EQ(result.messages, messages);
}

TEST(SendBatchSplit, AnythingElseIsNoBatch) {
  for (const std::vector<std::uint8_t>& other :
       {std::vector<std::uint8_t>{}, std::vector<std::uint8_t>{'R', 'D', 'B'}, rtps_message(60, 0)}) {
    const Split result = split(other);
    EXPECT_EQ(result.result, detail::BatchSplit::kNotABatch);
    EXPECT_TRUE(result.messages.empty());
  }
}

TEST(SendBatchSplit, InconsistentBatchesAreMalformedAfterTheirGoodPart) {
  const std::vector<std::uint8_t> good = batch_of({rtps_message(24, 1)});
  const std::size_t after_first = 4 + 4 + 24;  // magic, length, message
  auto with_length_at_second = [&](std::uint32_t length) {
    std::vector<std::uint8_t> batch(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(after_first));
    put_length(batch, length);
    batch.insert(batch.end(), 30, 0x55);
    return batch;
  };
  std::vector<std::vector<std::uint8_t>> hostile = {
      with_length_at_second(0xFFFFFFFFU),  // far beyond the buffer
      with_length_at_second(31),           // one beyond the buffer
      with_length_at_second(30),           // fits, but no "RTPS"
      with_length_at_second(3),            // shorter than any RTPS message
      std::vector<std::uint8_t>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(after_first)),  // no end marker
      std::vector<std::uint8_t>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(after_first) + 2),  // cut length
  };
  for (std::size_t i = 0; i < hostile.size(); ++i) {
    const Split result = split(hostile[i]);
    EXPECT_EQ(result.result, detail::BatchSplit::kMalformed) << "case " << i;
    ASSERT_EQ(result.messages.size(), 1U) << "case " << i;
    EXPECT_EQ(result.messages[0], rtps_message(24, 1)) << "case " << i;
  }
  const Split first_bad = split({'R', 'D', 'B', 'T', 0xFF, 0xFF, 0xFF, 0x7F, 'R', 'T', 'P', 'S'});
  EXPECT_EQ(first_bad.result, detail::BatchSplit::kMalformed);
  EXPECT_TRUE(first_bad.messages.empty());
}

TEST(SendBatchSplit, RandomBytesAfterTheMagicNeverReadOutsideTheBuffer) {
  std::mt19937 random(29);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> size(4, 200);
  for (int round = 0; round < 20000; ++round) {
    std::vector<std::uint8_t> buffer = {'R', 'D', 'B', 'T'};
    buffer.resize(size(random));
    for (std::size_t i = 4; i < buffer.size(); ++i) {
      buffer[i] = static_cast<std::uint8_t>(byte(random));
    }
    if (round % 2 == 0 && buffer.size() >= 12) {  // a small length and "RTPS" often enough to deliver
      buffer[4] = static_cast<std::uint8_t>(20 + byte(random) % 40);
      buffer[5] = buffer[6] = buffer[7] = 0;
      std::memcpy(buffer.data() + 8, "RTPS", 4);
    }
    split(buffer);  // the bounds are checked inside
  }
}

// ---- the registry ----------------------------------------------------------------------------

fr::Locator_t shm_locator(std::uint32_t port) {
  fr::Locator_t locator;
  locator.kind = LOCATOR_KIND_SHM;
  locator.port = port;
  return locator;
}

TEST(BatchingPeers, ALocatorCountsWhileAnyListenerRegistersIt) {
  const fr::Locator_t a = shm_locator(1'000'001);
  const fr::Locator_t b = shm_locator(1'000'002);
  EXPECT_FALSE(detail::all_batching_peers({a}));
  EXPECT_FALSE(detail::all_batching_peers({}));
  {
    BatchingPeers first;
    first.set("p", {a, b});
    EXPECT_TRUE(detail::all_batching_peers({a, b}));
    {
      BatchingPeers second;
      second.set("p", {a});
      first.erase("p");
      EXPECT_TRUE(detail::all_batching_peers({a}));
      EXPECT_FALSE(detail::all_batching_peers({a, b}));
      first.set("p", {b});
      first.set("p", {b});  // replaces, never counts twice
    }
    EXPECT_FALSE(detail::all_batching_peers({a}));
    EXPECT_TRUE(detail::all_batching_peers({b}));
  }
  EXPECT_FALSE(detail::all_batching_peers({b}));
}

// ---- hostile datagrams through a real transport -----------------------------------------------

/// A UDP port free now (the kernel's choice).
std::uint16_t free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  socklen_t length = sizeof(address);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

TEST(SendBatch, HostileBatchesReachingAParticipantAreCountedAndDropped) {
  over_the_wire();
  const std::uint16_t port = free_udp_port();
  dds::DomainParticipantQos qos;
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports = {std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>()};
  fr::Locator_t unicast;
  eprosima::fastrtps::rtps::IPLocator::setIPv4(unicast, 127, 0, 0, 1);
  unicast.port = port;
  qos.wire_protocol().default_unicast_locator_list.push_back(unicast);
  ParticipantPtr participant = create_participant(kDomain, qos, nullptr, dds::StatusMask::none(), "test");

  const std::vector<std::uint8_t> good_then_cut = {'R', 'D', 'B', 'T', 0xFF, 0xFF, 0xFF, 0xFF, 'R', 'T', 'P', 'S'};
  std::vector<std::uint8_t> garbage = {'R', 'D', 'B', 'T'};
  garbage.resize(300, 0xA5);
  const SendBatchCounters before = send_batch_counters();
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(port);
  for (const auto& datagram : {good_then_cut, garbage}) {
    ASSERT_EQ(::sendto(fd, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to)),
              static_cast<ssize_t>(datagram.size()));
  }
  ::close(fd);
  EXPECT_TRUE(eventually([&] { return send_batch_counters().malformed_received == before.malformed_received + 2; },
                         std::chrono::seconds(5)))
      << "counted " << send_batch_counters().malformed_received - before.malformed_received;
}

}  // namespace
}  // namespace robodds
