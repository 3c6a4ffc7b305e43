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
#include <shared_mutex>
#include <sstream>

#include "runtime/base/log.hpp"

namespace robodds {
namespace rtps = eprosima::fastdds::rtps;
using eprosima::fastrtps::rtps::Locator_t;
using eprosima::fastrtps::rtps::octet;
using eprosima::fastrtps::rtps::SenderResource;

namespace {

constexpr octet kBatchMagic[4] = {'R', 'D', 'B', 'T'};
constexpr octet kRtpsMagic[4] = {'R', 'T', 'P', 'S'};
constexpr std::size_t kRtpsHeaderBytes = 20;  // the smallest RTPS message
constexpr std::size_t kLengthBytes = 4;
// A batch ends with a zero length and this many zero bytes. Why: Fast DDS' transports, built with
// statistics (Debian's is), cut a trailing statistics submessage (id 0x80, 60 bytes) off what they
// send, recognised only by its position from the end: the batch's last message carries one, and
// the cut shortened the batch by 60 bytes. Each message keeps its own (receivers skip it, as they
// do over UDP).
constexpr std::size_t kTrailerBytes = 64;
constexpr std::size_t kOverheadBytes = 4 + kLengthBytes + kLengthBytes + kTrailerBytes;  // magic, entry length, end
// A batch leaves once it would exceed this many bytes (or the transport's message limit, if
// smaller): the receiving process starts on a step's first samples while the writer still writes
// the rest, and over UDP a batch is 12 IP fragments on a 1,500-byte link, not 44 (one lost fragment
// loses the whole datagram). Measured against the 65,500-byte limit, 200 robots across processes:
// 12-24 KiB best, 6 KiB worse (docs/performance.md, "Batched sends").
constexpr std::size_t kBatchBytes = 16384;
// The blocking limit a held batch is sent with, a writer's own (1 s, the QoS profiles). Fast DDS
// 2.9.1's shared memory ignores it: a batch that does not fit in the sender's segment is dropped
// at once, silently, and repaired by the reliable protocol, which is why a lockstep host sizes its
// segment for its window (runtime/launch/transport_buffers.hpp).
constexpr std::chrono::milliseconds kFlushBlocking{1000};

std::atomic<std::uint64_t> g_batches_sent{0};
std::atomic<std::uint64_t> g_messages_batched{0};
std::atomic<std::uint64_t> g_messages_not_held{0};
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

// ---- the registry of robodds participants' locators (BatchingPeers) ----------------------------

std::mutex g_peers_mutex;
std::map<Locator_t, int>& peer_locators() {  // locator -> how many BatchingPeers register it
  static std::map<Locator_t, int> locators;
  return locators;
}
// Grows at every change of the registry: a held group remembers at which generation it checked
// its destinations, so that a batch checks them once, not per message.
std::atomic<std::uint64_t> g_peers_generation{1};

void register_locators(const std::vector<Locator_t>& locators, int delta) {
  if (locators.empty()) {
    return;
  }
  std::lock_guard<std::mutex> lock(g_peers_mutex);
  for (const Locator_t& locator : locators) {
    int& count = peer_locators()[locator];
    count += delta;
    if (count <= 0) {
      peer_locators().erase(locator);
    }
  }
  g_peers_generation.fetch_add(1, std::memory_order_release);
}

// ---- sending -------------------------------------------------------------------------------------

/// Messages held for one sender resource of one transport: one destination list, in send order.
/// Kept across batches (its buffers keep their capacity); dropped when its transport is gone.
struct HeldGroup {
  std::uint64_t transport = 0;  // BatchingTransport::id()
  SenderResource* sender = nullptr;
  std::vector<Locator_t> destinations;
  std::uint64_t checked_generation = 0;  // g_peers_generation when to_robodds was computed; 0: never
  bool to_robodds = false;               // every destination is a robodds participant's
  std::vector<octet> bytes;              // the batch: magic, then length-prefixed messages; empty: none held
  std::uint64_t messages = 0;            // messages in `bytes`
};

/// The calling thread's batch state.
struct ThreadBatch {
  int depth = 0;
  std::vector<HeldGroup> groups;
  std::vector<Locator_t> destinations;  // scratch: the destinations of the message being sent
};

thread_local ThreadBatch t_batch;

class BatchingTransport;

/// Live batching transports by id: a held group is sent only through a transport still alive.
/// Closing batches read it (shared), a transport shutting down removes itself (exclusive), so that
/// it never goes while a close sends through it.
std::shared_mutex g_live_mutex;
std::map<std::uint64_t, BatchingTransport*>& live_transports() {
  static std::map<std::uint64_t, BatchingTransport*> live;
  return live;
}
std::atomic<std::uint64_t> g_next_transport_id{1};

class BatchingTransport : public rtps::ChainingTransport {
 public:
  explicit BatchingTransport(const rtps::ChainingTransportDescriptor& descriptor)
      : rtps::ChainingTransport(descriptor), limit_(std::min<std::size_t>(kBatchBytes, descriptor.max_message_size())) {
    std::unique_lock<std::shared_mutex> lock(g_live_mutex);
    live_transports()[id_] = this;
  }

  std::uint64_t id() const { return id_; }

  /// A participant being deleted shuts its transports down first (RTPSParticipantImpl::disable(),
  /// NetworkFactory::Shutdown()) and destroys its sender resources later: held groups must not be
  /// sent through this transport from then on. ChainingTransport does not pass shutdown() on to
  /// the wrapped transport; we do, as Fast DDS would without the wrapper.
  void shutdown() override {
    retire();
    low_level_transport_->shutdown();
  }

  /// Fast DDS asks each transport for a sender resource per destination locator, and the shared-
  /// memory and UDP transports add one only when none of theirs is in the list (and UDP registers
  /// the locator for its statistics, asserting at each send that it did). Inside wrappers they
  /// cannot recognise theirs: every locator added a sender and each message was sent once per
  /// sender (ChainingTransport's own wrapping), and skipping the call when one of ours was there
  /// left UDP's locators unregistered (an assertion in Debian's Fast DDS aborted the process).
  /// So the wrapped transport sees a list of its own senders, which this transport keeps, and
  /// Fast DDS gets a BatchingSender for each one it adds.
  bool OpenOutputChannel(rtps::SendResourceList& sender_resource_list, const Locator_t& locator) override;
  ~BatchingTransport() override;

  rtps::TransportDescriptorInterface* get_configuration() override { return low_level_transport_->get_configuration(); }

  bool send(SenderResource* low_sender_resource, const octet* send_buffer, uint32_t send_buffer_size,
            rtps::LocatorsIterator* destination_locators_begin,
            rtps::LocatorsIterator* destination_locators_end,
            const std::chrono::steady_clock::time_point& timeout) override {
    ThreadBatch& batch = t_batch;
    if (batch.depth == 0 || retired_.load(std::memory_order_relaxed)) {
      std::lock_guard<std::mutex> lock(send_mutex_);
      return low_sender_resource->send(send_buffer, send_buffer_size, destination_locators_begin, destination_locators_end,
                                       timeout);
    }
    std::vector<Locator_t>& destinations = batch.destinations;  // (walking the iterator consumes it)
    destinations.clear();
    for (auto& it = *destination_locators_begin; it != *destination_locators_end; ++it) {
      destinations.push_back(*it);
    }
    HeldGroup& group = group_of(batch, low_sender_resource);
    if (group.destinations != destinations) {
      send_held(group);  // what this sender held leaves first: order per sender is kept
      group.destinations.assign(destinations.begin(), destinations.end());
      group.checked_generation = 0;
    }
    const std::uint64_t generation = g_peers_generation.load(std::memory_order_acquire);
    if (group.checked_generation != generation) {
      group.to_robodds = detail::all_batching_peers(group.destinations);
      group.checked_generation = generation;
    }
    if (!group.to_robodds || kOverheadBytes + padded(send_buffer_size) > limit_) {
      g_messages_not_held.fetch_add(1, std::memory_order_relaxed);
      send_held(group);
      VectorLocators begin(group.destinations.cbegin());
      VectorLocators end(group.destinations.cend());
      std::lock_guard<std::mutex> lock(send_mutex_);
      return low_sender_resource->send(send_buffer, send_buffer_size, &begin, &end, timeout);
    }
    if (group.bytes.size() + kLengthBytes + padded(send_buffer_size) + kLengthBytes + kTrailerBytes > limit_) {
      send_held(group);  // full: a batch never exceeds the transport's message limit
    }
    if (group.bytes.empty()) {
      group.bytes.insert(group.bytes.end(), std::begin(kBatchMagic), std::end(kBatchMagic));
    }
    put_length(group.bytes, send_buffer_size);
    group.bytes.insert(group.bytes.end(), send_buffer, send_buffer + send_buffer_size);
    group.bytes.resize(group.bytes.size() + padded(send_buffer_size) - send_buffer_size, 0);
    ++group.messages;
    return true;
  }

  void receive(rtps::TransportReceiverInterface* next_receiver, const octet* receive_buffer, uint32_t receive_buffer_size,
               const Locator_t& local_locator, const Locator_t& remote_locator) override {
    struct Target {
      rtps::TransportReceiverInterface* receiver;
      const Locator_t* local;
      const Locator_t* remote;
    } target{next_receiver, &local_locator, &remote_locator};
    // (one pointer captured: std::function keeps it without allocating)
    const detail::BatchSplit split = detail::split_batch(
        receive_buffer, receive_buffer_size, [t = &target](const std::uint8_t* message, std::uint32_t length) {
          t->receiver->OnDataReceived(message, length, *t->local, *t->remote);
        });
    if (split == detail::BatchSplit::kNotABatch) {
      next_receiver->OnDataReceived(receive_buffer, receive_buffer_size, local_locator, remote_locator);
    } else if (split == detail::BatchSplit::kMalformed && g_malformed.fetch_add(1, std::memory_order_relaxed) == 0) {
      std::ostringstream from;
      from << remote_locator;
      log::warn("dds", "dropped the rest of a malformed batch of RTPS messages from " + from.str() +
                           " (runtime/dds/send_batch.hpp; later ones are only counted)");
    }
  }

  /// Sends `group`'s batch, if any, and empties it (keeping its capacity); a single message leaves
  /// as it is (no envelope to add and split). The caller made sure that this transport and the
  /// group's sender are alive.
  void send_held(HeldGroup& group) {
    if (group.bytes.empty()) {
      return;
    }
    const octet* data = group.bytes.data();
    std::size_t size = group.bytes.size();
    if (group.messages == 1) {
      data += sizeof(kBatchMagic) + kLengthBytes;
      size = get_length(group.bytes.data() + sizeof(kBatchMagic));
    } else {
      put_length(group.bytes, 0);
      group.bytes.resize(group.bytes.size() + kTrailerBytes, 0);
      data = group.bytes.data();
      size = group.bytes.size();
      g_batches_sent.fetch_add(1, std::memory_order_relaxed);
      g_messages_batched.fetch_add(group.messages, std::memory_order_relaxed);
    }
    VectorLocators begin(group.destinations.cbegin());
    VectorLocators end(group.destinations.cend());
    {
      std::lock_guard<std::mutex> lock(send_mutex_);
      group.sender->send(data, static_cast<uint32_t>(size), &begin, &end, std::chrono::steady_clock::now() + kFlushBlocking);
    }
    group.bytes.clear();
    group.messages = 0;
  }

 private:
  HeldGroup& group_of(ThreadBatch& batch, SenderResource* sender) {
    for (HeldGroup& held : batch.groups) {
      if (held.transport == id_ && held.sender == sender) {
        return held;
      }
    }
    batch.groups.emplace_back();
    batch.groups.back().transport = id_;
    batch.groups.back().sender = sender;
    return batch.groups.back();
  }

  void retire() {
    std::unique_lock<std::shared_mutex> lock(g_live_mutex);  // waits for a close sending through us
    live_transports().erase(id_);
    retired_ = true;
  }

  const std::uint64_t id_ = g_next_transport_id.fetch_add(1);
  std::size_t limit_;
  std::atomic<bool> retired_{false};
  rtps::SendResourceList low_senders_;  // the wrapped transport's senders (Fast DDS holds a BatchingSender of each)
  // The low-level transport's send() is not thread-safe (Fast DDS calls it under the participant's
  // send mutex, which a held batch sent later cannot take): every send through it takes this one.
  std::mutex send_mutex_;
};

/// What Fast DDS holds for one sender resource of the wrapped transport: its sends go through
/// BatchingTransport::send(), as through ChainingTransport's own wrapper.
class BatchingSender : public SenderResource {
 public:
  BatchingSender(BatchingTransport& transport, SenderResource* low) : SenderResource(transport.kind()), low_(low) {
    send_lambda_ = [&transport, low](const octet* data, uint32_t size, rtps::LocatorsIterator* begin,
                                     rtps::LocatorsIterator* end, const std::chrono::steady_clock::time_point& timeout) {
      return transport.send(low, data, size, begin, end, timeout);
    };
  }
  void add_locators_to_list(eprosima::fastrtps::rtps::LocatorList_t& locators) const override {
    low_->add_locators_to_list(locators);
  }

 private:
  SenderResource* low_;  // owned by the transport, which outlives this (Fast DDS deletes its senders first)
};

bool BatchingTransport::OpenOutputChannel(rtps::SendResourceList& sender_resource_list, const Locator_t& locator) {
  if (!IsLocatorSupported(locator)) {
    return false;
  }
  const std::size_t before = low_senders_.size();
  const bool opened = low_level_transport_->OpenOutputChannel(low_senders_, locator);
  for (std::size_t i = before; i < low_senders_.size(); ++i) {
    sender_resource_list.emplace_back(new BatchingSender(*this, low_senders_[i].get()));
  }
  return opened;
}

BatchingTransport::~BatchingTransport() {
  retire();
  low_senders_.clear();  // (closing their sockets needs the wrapped transport, a member of the base)
}

/// What ChainingTransport's constructor takes: the transport it wraps.
struct WrappedDescriptor : rtps::ChainingTransportDescriptor {
  using rtps::ChainingTransportDescriptor::ChainingTransportDescriptor;
  rtps::TransportInterface* create_transport() const override { return nullptr; }  // never asked
};

/// A descriptor of the wrapped kind (Fast DDS' participant recognises shared memory by
/// dynamic_cast to SharedMemTransportDescriptor: has_shm_transport_) that creates the batching
/// transport around the plain one.
template <typename Descriptor>
struct BatchingDescriptor : Descriptor {
  explicit BatchingDescriptor(const Descriptor& plain) : Descriptor(plain) {}
  rtps::TransportInterface* create_transport() const override {
    const WrappedDescriptor chain(std::make_shared<Descriptor>(static_cast<const Descriptor&>(*this)));
    return new BatchingTransport(chain);
  }
};

}  // namespace

void open_send_batch() { ++t_batch.depth; }

void close_send_batch() {
  ThreadBatch& batch = t_batch;
  if (batch.depth == 0 || --batch.depth > 0) {
    return;
  }
  if (std::none_of(batch.groups.begin(), batch.groups.end(), [](const HeldGroup& group) { return !group.bytes.empty(); })) {
    return;  // nothing held (a co-located run): groups of dead transports go at the next close that sends
  }
  std::shared_lock<std::shared_mutex> lock(g_live_mutex);
  const auto& live = live_transports();
  batch.groups.erase(std::remove_if(batch.groups.begin(), batch.groups.end(),
                                    [&live](HeldGroup& group) {
                                      const auto transport = live.find(group.transport);
                                      if (transport == live.end()) {
                                        return true;  // its participant is gone: so are its messages
                                      }
                                      transport->second->send_held(group);
                                      return false;
                                    }),
                     batch.groups.end());
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

BatchingPeers::~BatchingPeers() {
  for (const auto& entry : registered_) {
    register_locators(entry.second, -1);
  }
}

void BatchingPeers::set(const std::string& participant, std::vector<Locator_t> locators) {
  std::sort(locators.begin(), locators.end());
  locators.erase(std::unique(locators.begin(), locators.end()), locators.end());
  erase(participant);
  register_locators(locators, +1);
  registered_[participant] = std::move(locators);
}

void BatchingPeers::erase(const std::string& participant) {
  const auto found = registered_.find(participant);
  if (found != registered_.end()) {
    register_locators(found->second, -1);
    registered_.erase(found);
  }
}

SendBatchCounters send_batch_counters() {
  SendBatchCounters counters;
  counters.batches_sent = g_batches_sent.load(std::memory_order_relaxed);
  counters.messages_batched = g_messages_batched.load(std::memory_order_relaxed);
  counters.messages_not_held = g_messages_not_held.load(std::memory_order_relaxed);
  counters.malformed_received = g_malformed.load(std::memory_order_relaxed);
  return counters;
}

namespace detail {

BatchSplit split_batch(const std::uint8_t* buffer, std::size_t size,
                       const std::function<void(const std::uint8_t* message, std::uint32_t length)>& deliver) {
  if (size < sizeof(kBatchMagic) || std::memcmp(buffer, kBatchMagic, sizeof(kBatchMagic)) != 0) {
    return BatchSplit::kNotABatch;
  }
  std::size_t at = sizeof(kBatchMagic);
  while (size - at >= kLengthBytes) {
    const std::uint32_t length = get_length(buffer + at);
    at += kLengthBytes;
    if (length == 0) {
      return BatchSplit::kWhole;  // the end (the trailer follows)
    }
    if (length < kRtpsHeaderBytes || length > size - at || std::memcmp(buffer + at, kRtpsMagic, sizeof(kRtpsMagic)) != 0) {
      return BatchSplit::kMalformed;
    }
    deliver(buffer + at, length);
    at += std::min<std::size_t>(padded(length), size - at);
  }
  return BatchSplit::kMalformed;  // no end marker: cut short
}

bool all_batching_peers(const std::vector<Locator_t>& locators) {
  if (locators.empty()) {
    return false;
  }
  std::lock_guard<std::mutex> lock(g_peers_mutex);
  const auto& known = peer_locators();
  return std::all_of(locators.begin(), locators.end(), [&known](const Locator_t& locator) { return known.count(locator) > 0; });
}

}  // namespace detail
}  // namespace robodds
