#include "runtime/bus/memory_bus.hpp"

#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/qos_profiles.hpp"
#include "runtime/bus/sample_key.hpp"

namespace robodds {
namespace {

// The one transient-local profile (deploy/qos/robodds_qos.xml): a reader that appears after
// the mission was written still gets it.
constexpr const char* kTransientLocalProfile = kMissionProfile;

/// What the bus needs to know about a sample it only sees as `const void*`.
struct TypeOps {
  std::shared_ptr<const void> (*copy)(const void* sample) = nullptr;
  std::uint64_t (*key)(const void* sample) = nullptr;
};

template <class T>
std::shared_ptr<const void> copy_sample(const void* sample) {
  return std::make_shared<const T>(*static_cast<const T*>(sample));
}

TypeOps type_ops(const std::string& topic, const std::string& type_name) {
  TypeOps ops;
  const bool known = idl::dispatch_type(type_name, [&ops](auto tag) {
    using T = typename decltype(tag)::type;
    ops.copy = &copy_sample<T>;
  });
  ops.key = sample_key_function(type_name);
  if (!known) {
    throw ConfigError("topic " + topic + ": unknown type " + type_name);
  }
  return ops;
}

using Callbacks = std::vector<SampleCallback>;

/// A transient-local sample kept for late readers, with the writer that wrote it.
struct Retained {
  std::shared_ptr<const void> sample;
  std::uint64_t writer_id = 0;
};

/// One sample on its way to the callbacks that were subscribed when it was written.
struct Delivery {
  std::shared_ptr<const Callbacks> callbacks;
  std::shared_ptr<const void> sample;
  SampleMeta meta;
};

/// The delivery running on this thread per bus: writes made from inside a callback join its
/// queue instead of overtaking the sample being delivered.
struct ActiveDelivery {
  const void* bus;
  std::deque<Delivery>* queue;
};
thread_local std::vector<ActiveDelivery> active_deliveries;

}  // namespace

struct MemoryBus::State {
  struct Subscriber {
    std::uint64_t id = 0;
    SampleCallback on_sample;
  };
  struct Topic {
    std::string type_name;
    std::vector<Subscriber> subscribers;
    std::shared_ptr<const Callbacks> callbacks = std::make_shared<Callbacks>();  // snapshot of subscribers
    std::map<std::uint64_t, Retained> retained;  // newest transient-local sample per instance
  };

  std::mutex mutex;
  std::map<std::string, Topic> topics;
  std::map<std::string, std::shared_ptr<WriterHandle>> writers;  // by "topic|profile"
  std::uint64_t next_subscriber = 1;
  std::uint64_t next_writer = 1;  // SampleMeta::writer_id of the next writer
  std::map<std::uint64_t, std::string> writer_topics;  // writer id -> "topic|profile"

  /// The topic, checking that every endpoint agrees on its type. Call with the mutex held.
  Topic& topic_of(const std::string& topic, const std::string& type_name) {
    Topic& entry = topics[topic];
    if (entry.type_name.empty()) {
      entry.type_name = type_name;
    } else if (entry.type_name != type_name) {
      throw ConfigError("topic " + topic + " carries " + entry.type_name + ", not " + type_name);
    }
    return entry;
  }

  static void rebuild_callbacks(Topic& topic) {
    auto callbacks = std::make_shared<Callbacks>();
    for (const Subscriber& s : topic.subscribers) {
      callbacks->push_back(s.on_sample);
    }
    topic.callbacks = std::move(callbacks);
  }

  void remove_subscriber(const std::string& topic, std::uint64_t id) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = topics.find(topic);
    if (it == topics.end()) {
      return;
    }
    auto& subscribers = it->second.subscribers;
    for (auto s = subscribers.begin(); s != subscribers.end(); ++s) {
      if (s->id == id) {
        subscribers.erase(s);
        break;
      }
    }
    rebuild_callbacks(it->second);
  }

  /// The queue of the delivery running on this thread for this bus, or nullptr.
  std::deque<Delivery>* active_queue() const {
    for (const ActiveDelivery& active : active_deliveries) {
      if (active.bus == this) {
        return active.queue;
      }
    }
    return nullptr;
  }

  /// Delivers `delivery` now, or queues it behind the delivery already running on this thread.
  void deliver(Delivery delivery) {
    if (std::deque<Delivery>* queue = active_queue()) {
      queue->push_back(std::move(delivery));
      return;
    }
    deliver_now(delivery.callbacks, delivery.sample.get(), delivery.meta);
  }

  /// Runs `callbacks` on `sample` now, then every delivery queued meanwhile on this thread.
  /// `sample` is only read while its own callbacks run, so the caller's sample needs no copy.
  /// Call only when no delivery runs on this thread for this bus (active_queue() is nullptr).
  void deliver_now(const std::shared_ptr<const Callbacks>& callbacks, const void* sample, const SampleMeta& meta) {
    std::deque<Delivery> queue;
    active_deliveries.push_back({this, &queue});
    struct Leave {
      ~Leave() { active_deliveries.pop_back(); }
    } leave;
    run_callbacks(*callbacks, sample, meta);
    while (!queue.empty()) {
      const Delivery next = std::move(queue.front());
      queue.pop_front();
      run_callbacks(*next.callbacks, next.sample.get(), next.meta);
    }
  }

  /// Every reader of one sample, sharing one SampleMeta::checks_passed flag.
  static void run_callbacks(const Callbacks& callbacks, const void* sample, const SampleMeta& meta) {
    bool checks_passed = false;
    SampleMeta shared = meta;
    shared.checks_passed = &checks_passed;
    for (const SampleCallback& callback : callbacks) {
      callback(sample, shared);
    }
  }
};

namespace {

class MemoryWriter : public WriterHandle {
 public:
  MemoryWriter(std::weak_ptr<MemoryBus::State> state, std::string topic, std::string profile, TypeOps ops, std::uint64_t id)
      : state_(std::move(state)), topic_(std::move(topic)), ops_(std::move(ops)),
        transient_local_(profile == kTransientLocalProfile), id_(id) {}

  void write(const void* sample) override {
    std::shared_ptr<MemoryBus::State> state = state_.lock();
    if (!state) {
      throw RunError("write on " + topic_ + " after the in-memory bus was destroyed");
    }
    Delivery delivery;
    delivery.meta = SampleMeta{id_, monotonic_now_ns()};
    std::deque<Delivery>* queue = state->active_queue();
    if (queue != nullptr || transient_local_) {
      delivery.sample = ops_.copy(sample);  // a queued or retained sample outlives the caller's
    }
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      MemoryBus::State::Topic& topic = state->topics.at(topic_);
      if (transient_local_) {
        topic.retained[ops_.key(sample)] = Retained{delivery.sample, id_};
      }
      delivery.callbacks = topic.callbacks;
    }
    if (queue != nullptr) {
      queue->push_back(std::move(delivery));
    } else {
      state->deliver_now(delivery.callbacks, sample, delivery.meta);
    }
  }

  const std::string& topic() const override { return topic_; }

 private:
  std::weak_ptr<MemoryBus::State> state_;
  std::string topic_;
  TypeOps ops_;
  bool transient_local_;
  std::uint64_t id_;
};

class MemoryReader : public ReaderHandle {
 public:
  MemoryReader(std::weak_ptr<MemoryBus::State> state, std::string topic, std::uint64_t id)
      : state_(std::move(state)), topic_(std::move(topic)), id_(id) {}
  ~MemoryReader() override {
    if (std::shared_ptr<MemoryBus::State> state = state_.lock()) {
      state->remove_subscriber(topic_, id_);
    }
  }

 private:
  std::weak_ptr<MemoryBus::State> state_;
  std::string topic_;
  std::uint64_t id_;
};

}  // namespace

MemoryBus::MemoryBus() : state_(std::make_shared<State>()) {}

MemoryBus::~MemoryBus() = default;

std::shared_ptr<WriterHandle> MemoryBus::writer(const std::string& topic, const std::string& type_name,
                                                const std::string& profile) {
  TypeOps ops = type_ops(topic, type_name);
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->topic_of(topic, type_name);
  std::shared_ptr<WriterHandle>& writer = state_->writers[topic + "|" + profile];
  if (!writer) {
    const std::uint64_t id = state_->next_writer++;
    state_->writer_topics[id] = topic + "|" + profile;
    writer = std::make_shared<MemoryWriter>(state_, topic, profile, std::move(ops), id);
  }
  return writer;
}

std::shared_ptr<ReaderHandle> MemoryBus::reader(const std::string& topic, const std::string& type_name,
                                                const std::string& profile, SampleCallback on_sample,
                                                ReaderEventCallback /*on_event: no QoS events in memory*/) {
  type_ops(topic, type_name);
  std::vector<Retained> history;
  std::uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    State::Topic& entry = state_->topic_of(topic, type_name);
    id = state_->next_subscriber++;
    entry.subscribers.push_back(State::Subscriber{id, on_sample});
    State::rebuild_callbacks(entry);
    if (profile == kTransientLocalProfile) {
      for (const auto& [key, retained] : entry.retained) {
        history.push_back(retained);
      }
    }
  }
  // A late joiner gets the retained samples at once, outside the lock (it may write).
  for (const Retained& retained : history) {
    state_->deliver(Delivery{std::make_shared<const Callbacks>(Callbacks{on_sample}), retained.sample,
                             SampleMeta{retained.writer_id, monotonic_now_ns()}});
  }
  return std::make_shared<MemoryReader>(state_, topic, id);
}

void MemoryBus::flush(std::chrono::milliseconds /*timeout*/) {}

std::string MemoryBus::writer_name(std::uint64_t writer_id) const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  auto it = state_->writer_topics.find(writer_id);
  return it == state_->writer_topics.end() ? Bus::writer_name(writer_id)
                                           : "in-memory writer " + std::to_string(writer_id) + " (" + it->second + ")";
}

bool MemoryBus::has_writer(std::uint64_t writer_id) const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->writer_topics.count(writer_id) != 0;
}

}  // namespace robodds
