#include "runtime/dds/send_batch.hpp"

#include <fastdds/rtps/transport/ChainingTransport.h>
#include <fastdds/rtps/network/SenderResource.h>
#include <fastdds/rtps/transport/ChainingTransportDescriptor.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <mutex>
#include <set>
#include <cstdlib>

namespace robodds {
namespace rtps = eprosima::fastdds::rtps;
using eprosima::fastrtps::rtps::Locator_t;
using eprosima::fastrtps::rtps::octet;
using eprosima::fastrtps::rtps::SenderResource;

namespace {

constexpr octet kBatchMagic[4] = {'R', 'D', 'B', 'T'};
constexpr octet kRtpsMagic[4] = {'R', 'T', 'P', 'S'};
constexpr std::size_t kLengthBytes = 4;
// A batch ends with a zero length and this many zero bytes. Why: Fast DDS' transports, built with
// statistics (Debian's is), cut a trailing statistics submessage (id 0x80, 60 bytes) off what they
// send, recognised only by its position from the end: the batch's last message carries one, and
// the cut shortened the batch by 60 bytes. Each message keeps its own (receivers skip it, as they
// do over UDP).
constexpr std::size_t kTrailerBytes = 64;
constexpr std::size_t kOverheadBytes = 4 + kLengthBytes + kLengthBytes + kTrailerBytes;  // magic, entry length, end
// A held batch is sent within this time even when the shared-memory segment is full (Fast DDS
// waits up to it for free space); a writer's own blocking limit is 1 s (the QoS profiles).
constexpr std::chrono::milliseconds kFlushBlocking{1000};

std::atomic<std::uint64_t> g_malformed{0};

std::size_t padded(std::size_t n) { return (n + 3U) & ~std::size_t{3}; }

void put_length(std::vector<octet>& out, std::uint32_t n) {
  for (int i = 0; i < 4; ++i) {
    out.push_back(static_cast<octet>((n >> (8 * i)) & 0xFFU));
  }
}

std::uint32_t get_length(const octet* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

/// A LocatorsIterator over a vector (Fast DDS' senders take their destinations through it).
class VectorLocators : public rtps::LocatorsIterator {
 public:
  explicit VectorLocators(std::vector<Locator_t>::const_iterator it) : it_(it) {}
  LocatorsIterator& operator++() override {
    ++it_;
    return *this;
  }
  bool operator==(const LocatorsIterator& other) const override {
    return it_ == static_cast<const VectorLocators&>(other).it_;
  }
  bool operator!=(const LocatorsIterator& other) const override { return !(*this == other); }
  const Locator_t& operator*() const override { return *it_; }

 private:
  std::vector<Locator_t>::const_iterator it_;
};

class BatchingTransport;

/// Messages held for one sender resource of one transport: one destination list, in send order.
struct HeldGroup {
  BatchingTransport* transport = nullptr;
  SenderResource* sender = nullptr;
  std::vector<Locator_t> destinations;
  std::vector<octet> bytes;  // the batch: magic, then length-prefixed messages
};

/// The calling thread's open batch.
struct ThreadBatch {
  int depth = 0;
  std::vector<HeldGroup> groups;
};

thread_local ThreadBatch t_batch;

/// Live batching transports: a held group is sent only through a transport still alive.
std::mutex g_live_mutex;
std::set<const BatchingTransport*>& live_transports() {
  static std::set<const BatchingTransport*> live;
  return live;
}

class BatchingTransport : public rtps::ChainingTransport {
 public:
  explicit BatchingTransport(const rtps::ChainingTransportDescriptor& descriptor)
      : rtps::ChainingTransport(descriptor), limit_(descriptor.max_message_size()) {
    std::lock_guard<std::mutex> lock(g_live_mutex);
    live_transports().insert(this);
  }
  ~BatchingTransport() override {
    std::lock_guard<std::mutex> lock(g_live_mutex);
    live_transports().erase(this);
  }

  /// Fast DDS asks each transport for a sender resource per destination locator, and the shared-
  /// memory and UDP transports add one only when none of theirs is in the list; they cannot
  /// recognise theirs inside our wrappers, so without this every locator added a sender and each
  /// message was sent once per sender.
  bool OpenOutputChannel(rtps::SendResourceList& sender_resource_list, const Locator_t& locator) override {
    if (!IsLocatorSupported(locator)) {
      return false;
    }
    for (const auto& sender : sender_resource_list) {
      if (own_senders_.count(sender.get()) > 0) {
        return true;
      }
    }
    const std::size_t before = sender_resource_list.size();
    const bool opened = rtps::ChainingTransport::OpenOutputChannel(sender_resource_list, locator);
    for (std::size_t i = before; i < sender_resource_list.size(); ++i) {
      own_senders_.insert(sender_resource_list[i].get());
    }
    return opened;
  }

  rtps::TransportDescriptorInterface* get_configuration() override { return low_level_transport_->get_configuration(); }

  bool send(SenderResource* low_sender_resource, const octet* send_buffer, uint32_t send_buffer_size,
            rtps::LocatorsIterator* destination_locators_begin,
            rtps::LocatorsIterator* destination_locators_end,
            const std::chrono::steady_clock::time_point& timeout) override {
    if (t_batch.depth == 0 || kOverheadBytes + padded(send_buffer_size) > limit_) {
      std::lock_guard<std::mutex> lock(send_mutex_);
      return low_sender_resource->send(send_buffer, send_buffer_size, destination_locators_begin, destination_locators_end,
                                       timeout);
    }
    std::vector<Locator_t> destinations;
    for (auto& it = *destination_locators_begin; it != *destination_locators_end; ++it) {
      destinations.push_back(*it);
    }
    HeldGroup* group = nullptr;
    for (HeldGroup& held : t_batch.groups) {
      if (held.transport == this && held.sender == low_sender_resource) {
        group = &held;
        break;
      }
    }
    if (group == nullptr) {
      t_batch.groups.push_back(HeldGroup{this, low_sender_resource, {}, {}});
      group = &t_batch.groups.back();
    }
    if (!group->bytes.empty() &&
        (group->destinations != destinations || group->bytes.size() + kLengthBytes + padded(send_buffer_size) + kLengthBytes + kTrailerBytes > limit_)) {
      send_held(*group);
    }
    if (group->bytes.empty()) {
      group->destinations = std::move(destinations);
      group->bytes.insert(group->bytes.end(), std::begin(kBatchMagic), std::end(kBatchMagic));
    }
    put_length(group->bytes, send_buffer_size);
    group->bytes.insert(group->bytes.end(), send_buffer, send_buffer + send_buffer_size);
    group->bytes.resize(group->bytes.size() + padded(send_buffer_size) - send_buffer_size, 0);
    return true;
  }

  void receive(rtps::TransportReceiverInterface* next_receiver, const octet* receive_buffer, uint32_t receive_buffer_size,
               const Locator_t& local_locator, const Locator_t& remote_locator) override {
    if (receive_buffer_size < sizeof(kBatchMagic) ||
        std::memcmp(receive_buffer, kBatchMagic, sizeof(kBatchMagic)) != 0) {
      next_receiver->OnDataReceived(receive_buffer, receive_buffer_size, local_locator, remote_locator);
      return;
    }
    std::size_t at = sizeof(kBatchMagic);
    while (at < receive_buffer_size) {
      if (receive_buffer_size - at < kLengthBytes) {
        g_malformed.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      const std::uint32_t length = get_length(receive_buffer + at);
      at += kLengthBytes;
      if (length == 0) {
        return;  // the end (the trailer follows)
      }
      if (length < sizeof(kRtpsMagic) || length > receive_buffer_size - at ||
          std::memcmp(receive_buffer + at, kRtpsMagic, sizeof(kRtpsMagic)) != 0) {
        g_malformed.fetch_add(1, std::memory_order_relaxed);
        return;
      }
      next_receiver->OnDataReceived(receive_buffer + at, length, local_locator, remote_locator);
      at += std::min<std::size_t>(padded(length), receive_buffer_size - at);
    }
  }

  /// Sends `group`'s batch and empties it (the caller checked that this transport is alive).
  void send_held(HeldGroup& group) {
    if (group.bytes.empty()) {
      return;
    }
    put_length(group.bytes, 0);
    group.bytes.resize(group.bytes.size() + kTrailerBytes, 0);
    VectorLocators begin(group.destinations.cbegin());
    VectorLocators end(group.destinations.cend());
    {
      std::lock_guard<std::mutex> lock(send_mutex_);
      group.sender->send(group.bytes.data(), static_cast<uint32_t>(group.bytes.size()), &begin, &end,
                         std::chrono::steady_clock::now() + kFlushBlocking);
    }
    group.bytes.clear();
  }

 private:
  std::size_t limit_;
  std::set<const SenderResource*> own_senders_;  // the wrappers this transport added (Fast DDS owns them)
  // The low-level transport's send() is not thread-safe (Fast DDS calls it under the participant's
  // send mutex, which a held batch sent later cannot take): every send through it takes this one.
  std::mutex send_mutex_;
};

/// What ChainingTransport's constructor takes: the transport it wraps.
struct WrappedDescriptor : rtps::ChainingTransportDescriptor {
  using rtps::ChainingTransportDescriptor::ChainingTransportDescriptor;
  rtps::TransportInterface* create_transport() const override { return nullptr; }  // never asked
};

template <typename Descriptor>
struct BatchingDescriptor : Descriptor {
  explicit BatchingDescriptor(const Descriptor& plain) : Descriptor(plain) {}
  rtps::TransportInterface* create_transport() const override {
    const WrappedDescriptor chain(std::make_shared<Descriptor>(static_cast<const Descriptor&>(*this)));
    return new BatchingTransport(chain);
  }
};

}  // namespace

void open_send_batch() { static const bool off = std::getenv("ROBODDS_NO_BATCH") != nullptr; if (!off) ++t_batch.depth; }

void close_send_batch() {
  if (t_batch.depth == 0 || --t_batch.depth > 0) {
    return;
  }
  std::lock_guard<std::mutex> lock(g_live_mutex);
  for (HeldGroup& group : t_batch.groups) {
    if (live_transports().count(group.transport) > 0) {
      group.transport->send_held(group);
    }
  }
  t_batch.groups.clear();
}

std::vector<std::shared_ptr<rtps::TransportDescriptorInterface>> batching_transports(
    const std::vector<std::shared_ptr<rtps::TransportDescriptorInterface>>& transports) {
  std::vector<std::shared_ptr<rtps::TransportDescriptorInterface>> out;
  out.reserve(transports.size());
  for (const auto& transport : transports) {
    if (const auto* shm = dynamic_cast<const rtps::SharedMemTransportDescriptor*>(transport.get())) {
      out.push_back(std::make_shared<BatchingDescriptor<rtps::SharedMemTransportDescriptor>>(*shm));
    } else if (const auto* udp = dynamic_cast<const rtps::UDPv4TransportDescriptor*>(transport.get())) {
      out.push_back(std::make_shared<BatchingDescriptor<rtps::UDPv4TransportDescriptor>>(*udp));
    } else {
      out.push_back(transport);
    }
  }
  return out;
}

std::uint64_t malformed_batches() { return g_malformed.load(std::memory_order_relaxed); }

}  // namespace robodds
