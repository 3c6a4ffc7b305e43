#pragma once
// Typed inputs and outputs of components. Free of Fast DDS headers.
//
// Lockstep rule (docs/architecture.md): every sample carries its `step` and its producer's
// `next_step`. A consumer due at step m with input delay d waits, per expected instance,
// until the newest sample has next_step > m - d: then every sample with step <= m - d has
// arrived, whatever the delivery order across topics and processes. It then reads only
// samples with step <= m - d. The result is the same co-located, across processes or hosts.

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/key_index.hpp"
#include "runtime/base/log.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/io/sample_checks.hpp"
#include "runtime/io/sample_fields.hpp"

namespace robodds {

inline constexpr std::uint64_t kNeverAgain = std::numeric_limits<std::uint64_t>::max();

/// Where a component is in time; shared by its inputs and outputs.
struct StepState {
  std::uint64_t step = 0;          // the step being processed
  std::uint64_t period_steps = 1;  // the component runs every period_steps steps
  std::int64_t stamp_ns = 0;       // sim time (lockstep) or wall time (real-time) of `step`
  TimeMode mode = TimeMode::kLockstep;
};

/// What a component chooses when it subscribes: which instances it needs and how many steps
/// late it reads them, e.g.
///   ctx.subscribe<idl::VelocityCommand>("plant/cmd", Subscription::instances(ctx.robot_keys()).delayed(1))
class Subscription {
 public:
  /// Needs these instances (instance_key values, e.g. robot ids from ctx.robot_keys()) at every
  /// due step: in lockstep the component runs only once each has delivered up to the step it
  /// reads. Samples of other instances are ignored. An empty list is any_instance().
  static Subscription instances(std::vector<std::uint64_t> keys) {
    Subscription s;
    s.expected_ = std::move(keys);
    return s;
  }
  /// For topics keyed (robot_id, X) whose robot moves from one X to another (sensor/range and
  /// observer/range_rate: X is the target, which a mission event changes): these robot ids, and
  /// per robot ONE stream whatever its X. In lockstep the component waits, per robot, for the
  /// newest sample of any X, so a producer that switches a robot from (r, 1) to (r, 2) at step S
  /// is waited for at S without the consumer knowing the new X in advance. Read with
  /// Input::latest_of_robot() / take_new_of_robot(). A producer ends a robot's stream with
  /// publish_final() (e.g. the robot leaves the mission).
  static Subscription robot_streams(std::vector<std::uint64_t> robot_ids) {
    Subscription s = instances(std::move(robot_ids));
    s.by_robot_ = true;
    return s;
  }
  /// Takes every instance and waits for none: reads whatever has arrived, which is not
  /// deterministic across deployments (monitoring only).
  static Subscription any_instance() { return Subscription{}; }
  /// Reads samples of step <= m - steps at step m (1 closes a loop: the plant integrates the
  /// command of the previous step). Default 0.
  Subscription delayed(std::uint64_t steps) const {
    Subscription s = *this;
    s.delay_steps_ = steps;
    return s;
  }

  const std::vector<std::uint64_t>& expected() const { return expected_; }
  std::uint64_t delay_steps() const { return delay_steps_; }
  bool by_robot() const { return by_robot_; }

 private:
  Subscription() = default;
  std::vector<std::uint64_t> expected_;
  std::uint64_t delay_steps_ = 0;
  bool by_robot_ = false;
};

namespace detail {

/// Runtime-internal (components use Subscription): how an Input is set up.
/// ComponentContext::subscribe() builds it from a Subscription and the topic catalog; the host
/// builds its tick/ack inputs directly.
struct InputOptions {
  /// Instances (instance_key values) needed at every due step; empty: every instance, gate on none.
  std::vector<std::uint64_t> expected;
  /// Read samples of step <= m - delay_steps.
  std::uint64_t delay_steps = 0;
  /// Host-level inputs (ticks, acks) see every sample regardless of the component's step.
  bool ignore_step = false;
  /// Subscription::robot_streams(): `expected` holds robot ids, and readiness and producers are
  /// tracked per robot id (the key's upper 32 bits), whatever the second key part.
  bool by_robot = false;
  /// The topic's key field names (from the topic catalog), used in error messages.
  std::string key_names;
  /// Labels for instances whose key cannot be spelled from key_names (e.g. hashed strings).
  std::map<std::uint64_t, std::string> labels;
  /// Spells SampleMeta::writer_id in log lines (Bus::writer_name); empty: "writer <id>".
  std::function<std::string(std::uint64_t)> writer_name;
  /// The topic's endpoints use DDS exclusive ownership (a hot standby writes it): the middleware
  /// picks the writer, and a change of writer is a logged hand-over, not a second producer.
  bool exclusive_ownership = false;
};

}  // namespace detail

/// What an input did with the samples it was handed: accepted, or dropped and counted per reason
/// (e.g. "non_finite"), for logs and summary.json.
struct InputCounts {
  std::uint64_t accepted = 0;
  std::map<std::string, std::uint64_t> rejected;  // reason -> samples dropped
  /// reason -> accepted samples the consumer had to correct before use (e.g. a command saturated
  /// to the plant's limits); counted by the component with InputBase::count_adjusted().
  std::map<std::string, std::uint64_t> adjusted;
  std::uint64_t rejected_total() const {
    std::uint64_t total = 0;
    for (const auto& [reason, count] : rejected) {
      total += count;
    }
    return total;
  }
};

namespace detail {
/// Rejection reason of a sample with a NaN or infinite number.
inline constexpr const char* kRejectNonFinite = "non_finite";
/// Rejection reason of a sample of an instance that already has another producer (real time,
/// shared ownership: the first writer wins; docs/architecture.md, "One producer per instance").
inline constexpr const char* kRejectSecondProducer = "second_producer";
/// Real time, shared ownership: a producer silent this long (the liveliness lease of the
/// real-time profiles) gives its instance up, so a restarted producer (new writer) takes over.
inline constexpr std::int64_t kProducerSilenceNs = 1000000000;

}  // namespace detail

class InputBase {
 public:
  InputBase(std::string topic, std::string owner, const StepState* state, Notifier* notifier, detail::InputOptions options)
      : topic_(std::move(topic)), owner_(std::move(owner)), state_(state), notifier_(notifier), options_(std::move(options)) {
    // Each stream once: the wake-up count of ready() counts streams (a key named twice would
    // never be counted down, and the executor would only notice at its 20 ms poll). The
    // expected streams are the first streams_, in key order: ready() walks them without lookups.
    std::sort(options_.expected.begin(), options_.expected.end());
    options_.expected.erase(std::unique(options_.expected.begin(), options_.expected.end()), options_.expected.end());
    for (std::uint64_t id : options_.expected) {
      add_stream(id);
    }
  }
  virtual ~InputBase() = default;

  const std::string& topic() const { return topic_; }
  /// Lockstep: reads samples up to `delay_steps()` steps old, and waits for some streams (gated).
  std::uint64_t delay_steps() const { return options_.delay_steps; }
  bool gated() const { return !options_.ignore_step && !options_.expected.empty(); }
  std::uint64_t rejected_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_.rejected_total();
  }
  InputCounts counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }
  /// Counts an accepted sample the component corrected before use, under `reason`.
  void count_adjusted(const std::string& reason) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.adjusted[reason];
  }
  /// Seconds between the receipt of the newest accepted sample of `key` (SampleMeta::received_ns,
  /// this process's monotonic clock) and `now_ns` (same clock); nullopt if none was accepted or
  /// its receive time is unknown. Judges freshness by the receiver's clock, not the sender's stamp.
  std::optional<double> age_s(std::uint64_t key, std::int64_t now_ns = monotonic_now_ns()) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t s = stream_index_.find(key);
    if (s == KeyIndex::kNone || streams_[s].progress.received_ns == 0) {
      return std::nullopt;
    }
    return static_cast<double>(now_ns - streams_[s].progress.received_ns) * 1e-9;
  }

  /// Real time: the newest accepted sample of `key` was received at most `max_age_s` before
  /// `now_ns` (age_s()); false if none was. The freshness rule of every consumer that acts on it.
  bool fresh(std::uint64_t key, double max_age_s, std::int64_t now_ns = monotonic_now_ns()) const {
    const std::optional<double> age = age_s(key, now_ns);
    return age && *age <= max_age_s;
  }

  /// Lockstep: the error that ends the run, if one was seen (empty: none): the first second
  /// producer of an instance, or the first lost sample of a stream.
  std::string lockstep_error() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lockstep_error_;
  }

  /// Lockstep: true when every expected instance has delivered all samples with
  /// step <= step - delay. Otherwise names the first missing instance (in key order) in *missing.
  /// Throws RunError once a second producer or a lost sample was seen in lockstep (lockstep_error()).
  bool ready(std::uint64_t step, std::string* missing) const {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!lockstep_error_.empty()) {
        throw RunError(lockstep_error_);
      }
    }
    if (state_->mode == TimeMode::kRealtime || step < options_.delay_steps) {
      return true;  // real time reads whatever is there; before `delay` steps nothing is due
    }
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t missing_streams = 0;
    // The expected streams are the first streams_, in key order (constructor): one walk over
    // an array, no lookup per key.
    for (std::size_t i = 0; i < options_.expected.size(); ++i) {
      const Stream& s = streams_[i];
      if (!covers(s.progress, step)) {
        if (missing_streams++ == 0 && missing != nullptr) {
          *missing = !s.progress.seen ? label_of(s.id) + " (nothing received yet)"
                                      : label_of(s.id) + " (newest sample: step " + std::to_string(s.progress.step) + ")";
        }
      }
    }
    // Not ready: the executor will wait, and this input wakes it once, when the last missing
    // stream arrives (on_sample), not at every sample: across processes a wake-up per sample
    // was a context switch per robot and topic (docs/performance.md, "Cost per robot-tick").
    armed_step_ = step;
    armed_missing_ = missing_streams;
    return missing_streams == 0;
  }

 protected:
  struct Progress {
    std::uint64_t step = 0;
    std::uint64_t next_step = 0;
    std::int64_t received_ns = 0;  // SampleMeta::received_ns of the newest accepted sample
    std::uint64_t producer = 0;    // the writer that owns this instance (0: none seen yet)
    bool seen = false;             // a sample of this stream arrived
  };
  /// The unit of readiness and producer tracking (stream_of()): an instance, or a robot id.
  struct Stream {
    std::uint64_t id = 0;
    Progress progress;
    std::uint64_t current_key = 0;  // by_robot: the robot's newest instance key, for "waiting for" messages
    bool has_current = false;
  };
  /// An instance that sent a sample this input wants, numbered in arrival order (instance_index_).
  struct Instance {
    std::uint64_t key = 0;
    std::string label;       // spelled once, for messages only
    std::size_t stream = 0;  // in streams_
  };

  /// Lockstep: a stream's samples form a chain, each announcing the step of the next
  /// (SampleHeader::next_step); a sample beyond the announced step means one was lost on the way
  /// (e.g. dropped, and gone from a writer history too short to resend it). That would change the
  /// results silently, so it ends the run (ready() throws), naming the stream and the steps.
  /// Call with mutex_ held, before `p` takes the sample's step.
  void check_chain(const Progress& p, const std::string& label, std::uint64_t step) {
    if (state_->mode != TimeMode::kLockstep || options_.ignore_step || !p.seen || step <= p.next_step ||
        !lockstep_error_.empty()) {
      return;
    }
    lockstep_error_ = "lockstep: topic " + topic_ + " (" + label + ") lost samples: after step " + std::to_string(p.step) +
                      ", whose sample announced the next at step " + std::to_string(p.next_step) + ", came step " +
                      std::to_string(step) + " (a sample dropped and no longer in the writer's history, or one that "
                      "could not be decoded: see summary.json hosts.*.undecodable)";
    log::error(owner_, lockstep_error_);
  }

  /// One producer per instance (docs/architecture.md, "One producer per instance and hot standby"):
  /// true if the sample of `writer_id` may be used. The first writer of an instance becomes its
  /// producer. Another writer is, with exclusive ownership, a hand-over (logged); in lockstep an
  /// error that ends the run (ready() throws it); in real time dropped and counted as
  /// second_producer (first writer wins) unless the producer was silent for kProducerSilenceNs.
  /// Call with mutex_ held.
  bool accept_producer(Progress& p, const std::string& label, const SampleMeta& meta) {
    if (meta.writer_id == 0 || options_.ignore_step || meta.writer_id == p.producer) {
      return true;
    }
    if (p.producer == 0) {
      p.producer = meta.writer_id;
      return true;
    }
    const std::string old_writer = writer_label(p.producer);
    const std::string new_writer = writer_label(meta.writer_id);
    const bool silent = meta.received_ns != 0 && p.received_ns != 0 && meta.received_ns - p.received_ns > detail::kProducerSilenceNs;
    if (options_.exclusive_ownership || (state_->mode == TimeMode::kRealtime && silent)) {
      log::warn(owner_, topic_ + " (" + label + "): hand-over from " + old_writer + " to " + new_writer +
                            (options_.exclusive_ownership ? " (exclusive ownership)" : " (the old producer fell silent)"));
      p.producer = meta.writer_id;
      return true;
    }
    if (state_->mode == TimeMode::kLockstep) {
      if (lockstep_error_.empty()) {
        lockstep_error_ = "lockstep: topic " + topic_ + " (" + label + ") has two producers: " + old_writer + " and " +
                             new_writer + " (a second component or a restarted process publishes this instance; one "
                             "producer per topic instance)";
        log::error(owner_, lockstep_error_);
      }
      ++counts_.rejected[detail::kRejectSecondProducer];
      return false;
    }
    count_rejection(detail::kRejectSecondProducer,
                    "(" + label + "): this instance's producer is " + old_writer + "; first writer wins", meta.writer_id);
    return false;
  }
  std::string writer_label(std::uint64_t writer_id) const {
    return options_.writer_name ? options_.writer_name(writer_id) : "writer " + std::to_string(writer_id);
  }

  /// Counts a dropped sample; the first of each (writer, reason) is logged, naming the writer:
  /// "rejected a sample on <topic> from <writer> <detail>; ...". Call with mutex_ held.
  void count_rejection(const std::string& reason, const std::string& detail, std::uint64_t writer_id) {
    ++counts_.rejected[reason];
    if (logged_rejections_.insert({writer_id, reason}).second) {
      const std::string writer = writer_label(writer_id);
      log::warn(owner_, "rejected a sample on " + topic_ + " from " + writer + " " + detail +
                            "; such samples are counted and dropped (logged once per writer and reason)");
    }
  }

  /// `key`: an instance, or with by_robot a robot id (then its current instance's label).
  std::string label_of(std::uint64_t key) const {
    if (options_.by_robot) {
      const std::size_t s = stream_index_.find(key);
      if (s != KeyIndex::kNone && streams_[s].has_current) {
        key = streams_[s].current_key;
      }
    }
    const std::size_t i = instance_index_.find(key);
    if (i != KeyIndex::kNone) {
      return instances_[i].label;
    }
    auto preset = options_.labels.find(key);
    if (preset != options_.labels.end()) {
      return preset->second;
    }
    // Not seen yet: spell the key with the topic's key field names ("robot_id, target_id").
    const std::string& names = options_.key_names;
    const std::size_t comma = names.find(',');
    if (options_.by_robot) {
      return names.substr(0, comma) + "=" + std::to_string(key) + " (any " + names.substr(comma + 2) + ")";
    }
    if (names.empty()) {
      return "instance " + std::to_string(key);
    }
    if (comma == std::string::npos) {
      return names + "=" + std::to_string(key);
    }
    std::string second = names.substr(comma + 1);
    second.erase(0, second.find_first_not_of(' '));
    return names.substr(0, comma) + "=" + std::to_string(key >> 32) + " " + second + "=" + std::to_string(key & 0xffffffffULL);
  }
  /// The unit of readiness and producer tracking: the instance, or its robot id (by_robot).
  std::uint64_t stream_of(std::uint64_t key) const { return options_.by_robot ? key >> 32 : key; }
  /// Lockstep: the stream has delivered every sample with step <= `step` - delay, i.e. its next
  /// sample's step is beyond it (next_step > step - delay, written without unsigned underflow).
  bool covers(const Progress& p, std::uint64_t step) const { return p.next_step + options_.delay_steps > step; }
  /// Whether a sample must wake the executor: always, unless this is a gated lockstep input
  /// whose waiting executor (counted by ready()) still misses other streams. Call with mutex_ held,
  /// `was_covering`: covers(p, armed_step_) before the sample was applied.
  bool wakes_executor(const Progress& p, bool was_covering) {
    if (!gated() || state_->mode == TimeMode::kRealtime) {
      return true;
    }
    if (armed_missing_ == 0 || was_covering || !covers(p, armed_step_)) {
      return false;  // nobody waits, or this stream was not among the missing
    }
    return --armed_missing_ == 0;
  }
  std::size_t add_stream(std::uint64_t id) {
    stream_index_.insert(id);
    Stream s;
    s.id = id;
    streams_.push_back(std::move(s));
    return streams_.size() - 1;
  }
  /// The number of stream `id` in streams_, added at its first sample when the input takes every
  /// instance; KeyIndex::kNone when the input does not want it. Call with mutex_ held.
  std::size_t wanted_stream(std::uint64_t id) {
    const std::size_t s = stream_index_.find(id);
    if (s == KeyIndex::kNone && options_.expected.empty()) {
      return add_stream(id);
    }
    return s;
  }
  /// Numbers a new instance of stream `stream` (an index in streams_), labelled with the preset
  /// label of InputOptions::labels or else `label`. Call with mutex_ held.
  std::size_t add_instance(std::uint64_t key, std::size_t stream, std::string label) {
    const std::size_t i = instance_index_.insert(key).first;
    auto preset = options_.labels.find(key);
    instances_.push_back(Instance{key, preset != options_.labels.end() ? preset->second : std::move(label), stream});
    // The robot's instances in key order (the *_of_robot() reads go through them in that order).
    const auto [r, added] = robot_index_.insert(key >> 32);
    if (added) {
      robot_instances_.emplace_back();
    }
    std::vector<std::size_t>& of_robot = robot_instances_[r];
    of_robot.insert(std::upper_bound(of_robot.begin(), of_robot.end(), key,
                                     [this](std::uint64_t k, std::size_t n) { return k < instances_[n].key; }),
                    i);
    return i;
  }
  /// The numbers of robot `robot_id`'s instances (keys robot_id << 32 | X), in key order, or
  /// nullptr. Call with mutex_ held.
  const std::vector<std::size_t>* instances_of_robot(std::uint32_t robot_id) const {
    const std::size_t r = robot_index_.find(robot_id);
    return r == KeyIndex::kNone ? nullptr : &robot_instances_[r];
  }
  /// Highest step a consumer may read now.
  std::uint64_t readable_limit() const {
    if (options_.ignore_step || state_->mode == TimeMode::kRealtime) {
      return kNeverAgain;
    }
    return state_->step >= options_.delay_steps ? state_->step - options_.delay_steps : 0;
  }
  bool nothing_readable() const {
    return !options_.ignore_step && state_->mode == TimeMode::kLockstep && state_->step < options_.delay_steps;
  }

  std::string topic_;
  std::string owner_;
  const StepState* state_;
  Notifier* notifier_;
  detail::InputOptions options_;
  mutable std::mutex mutex_;
  // Per sample, one O(1) lookup (key_index.hpp), whatever the number of instances: ordered maps
  // here made the cost per robot-tick grow with the robots (docs/performance.md).
  std::vector<Stream> streams_;  // the expected streams first, in key order, then others as they come
  KeyIndex stream_index_;        // stream id -> index in streams_
  std::vector<Instance> instances_;
  KeyIndex instance_index_;  // instance key -> index in instances_
  KeyIndex robot_index_;     // robot id (key >> 32) -> index in robot_instances_
  std::vector<std::vector<std::size_t>> robot_instances_;  // indices in instances_, in key order
  InputCounts counts_;
  std::set<std::pair<std::uint64_t, std::string>> logged_rejections_;  // (writer_id, reason)
  std::string lockstep_error_;  // lockstep: the first second producer or lost sample, thrown by ready()
  // Set by ready(), under mutex_: the step it was asked about and how many expected streams
  // it still missed then, counted down by wakes_executor() (0: nobody waits). Mutable: ready() is
  // a query for its callers; this is only whom to wake.
  mutable std::uint64_t armed_step_ = 0;
  mutable std::size_t armed_missing_ = 0;
};

template <class Msg>
class Input : public InputBase {
 public:
  /// Throws ConfigError naming the topic if Msg has no content check (require_content_check()).
  Input(std::string topic, std::string owner, const StepState* state, Notifier* notifier, detail::InputOptions options)
      : InputBase(std::move(topic), std::move(owner), state, notifier, std::move(options)) {
    require_content_check<Msg>(this->topic());
  }

  /// Stores a sample; called by the bus (listener thread or inside a local writer's write()).
  void on_sample(const Msg& sample, const SampleMeta& meta = SampleMeta{}) {
    if (store(sample, meta)) {
      notifier_->notify();  // outside the lock: the executor takes it at once
    }
  }

  /// Readable samples of `key` not taken before, in step order.
  std::vector<Msg> take_new(std::uint64_t key) {
    std::vector<Msg> out;
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t i = instance_index_.find(key);
    if (i != KeyIndex::kNone && !nothing_readable()) {
      take_readable(slots_[i], out);
    }
    return out;
  }

  /// take_new() of each of `keys` in turn, appended to `out`: one lock for all (a recorder's step).
  void take_new(const std::vector<std::uint64_t>& keys, std::vector<Msg>& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (nothing_readable()) {
      return;
    }
    for (std::uint64_t key : keys) {
      const std::size_t i = instance_index_.find(key);
      if (i != KeyIndex::kNone) {
        take_readable(slots_[i], out);
      }
    }
  }

  /// The newest readable sample of `key` (older unread ones are skipped), or nullptr.
  const Msg* latest(std::uint64_t key) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t i = instance_index_.find(key);
    if (i == KeyIndex::kNone || nothing_readable()) {
      return nullptr;
    }
    return newest_readable(slots_[i]);
  }

  /// Subscription::robot_streams(): the readable samples of robot `robot_id` not taken before,
  /// whatever their second key part, in step order.
  std::vector<Msg> take_new_of_robot(std::uint32_t robot_id) {
    std::vector<Msg> out;
    take_new_of_robots(std::vector<std::uint64_t>{robot_id}, out);
    return out;
  }

  /// take_new_of_robot() of each of `robot_ids` in turn, appended to `out`: one lock for all.
  void take_new_of_robots(const std::vector<std::uint64_t>& robot_ids, std::vector<Msg>& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (nothing_readable()) {
      return;
    }
    for (std::uint64_t robot_id : robot_ids) {
      const std::vector<std::size_t>* numbers = instances_of_robot(static_cast<std::uint32_t>(robot_id));
      if (numbers == nullptr) {
        continue;
      }
      const std::size_t first = out.size();
      for (std::size_t i : *numbers) {
        take_readable(slots_[i], out);
      }
      std::stable_sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                       [](const Msg& a, const Msg& b) { return a.header().step() < b.header().step(); });
    }
  }

  /// Subscription::robot_streams(): the newest readable sample of robot `robot_id` over all its
  /// second key parts (older unread ones are skipped), or nullptr.
  const Msg* latest_of_robot(std::uint32_t robot_id) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::vector<std::size_t>* numbers = instances_of_robot(robot_id);
    if (numbers == nullptr || nothing_readable()) {
      return nullptr;
    }
    const Msg* newest = nullptr;
    for (std::size_t i : *numbers) {
      const Msg* m = newest_readable(slots_[i]);
      if (m != nullptr && (newest == nullptr || m->header().step() >= newest->header().step())) {
        newest = m;
      }
    }
    return newest;
  }

  /// Instances that have delivered at least one valid sample, in key order.
  std::vector<std::uint64_t> instances() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::uint64_t> keys;
    for (std::size_t i = 0; i < instances_.size(); ++i) {
      if (slots_[i].valid) {
        keys.push_back(instances_[i].key);
      }
    }
    std::sort(keys.begin(), keys.end());
    return keys;
  }

 private:
  /// Applies `sample` to its stream's progress and, if it passed its checks, queues it for the
  /// component; true when the executor must be woken (wakes_executor()). A sample of a stream
  /// this input does not want is dropped: false.
  bool store(const Msg& sample, const SampleMeta& meta) {
    const std::uint64_t key = idl::instance_key(sample);
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t i = instance_index_.find(key);
    if (i == KeyIndex::kNone) {
      const std::size_t stream = wanted_stream(stream_of(key));
      if (stream == KeyIndex::kNone) {
        return false;
      }
      // Spelled once per instance, for messages only: no string is built for an ordinary sample.
      i = add_instance(key, stream, idl::instance_label(sample));
      slots_.emplace_back();
    }
    const std::optional<SampleCheckFailure> failed = first_failed_check(sample);
    const std::string& label = instances_[i].label;
    Stream& s = streams_[instances_[i].stream];
    Progress& p = s.progress;
    if (!accept_producer(p, label, meta)) {
      return true;  // in lockstep a second producer ends the run: let ready() throw it now
    }
    check_chain(p, label, sample.header().step());
    const bool was_covering = armed_missing_ != 0 && covers(p, armed_step_);
    p.seen = true;
    p.step = sample.header().step();
    p.next_step = sample.header().next_step();
    const bool wake = wakes_executor(p, was_covering) || !lockstep_error_.empty();
    if (options_.by_robot) {
      s.current_key = key;  // the robot's current instance, for "waiting for" messages
      s.has_current = true;
    }
    if (!failed) {
      p.received_ns = meta.received_ns;
      ++counts_.accepted;
      Slot& slot = slots_[i];
      slot.pending.push_back(sample);
      slot.valid = true;
    } else {
      count_rejection(failed->reason,
                      "(" + label + ", step " + std::to_string(sample.header().step()) + "): field '" + failed->field +
                          "' " + failed->detail,
                      meta.writer_id);
    }
    return wake;
  }

  /// Why `sample` is refused: a non-finite number first, then the plausibility checks of its
  /// message type (runtime/io/sample_checks.hpp); nullopt when it passes.
  std::optional<SampleCheckFailure> first_failed_check(const Msg& sample) const {
    const std::string bad_field = first_non_finite_field(sample);
    if (!bad_field.empty()) {
      return SampleCheckFailure{detail::kRejectNonFinite, bad_field, "is not finite"};
    }
    if (std::optional<SampleCheckFailure> failed =
            check_sample(sample, state_->mode, state_->mode == TimeMode::kRealtime ? wall_clock_now_ns() : 0)) {
      failed->detail += " [" + failed->reason + "]";
      return failed;
    }
    return std::nullopt;
  }

  /// One instance's samples. pending[head..] are not taken yet, in arrival order: a vector whose
  /// storage is reused step after step (a deque allocated and freed a block every few samples).
  struct Slot {
    std::vector<Msg> pending;
    std::size_t head = 0;
    std::optional<Msg> latest;
    bool valid = false;  // a valid sample arrived (instances())

    bool has_readable(std::uint64_t limit) const { return head < pending.size() && pending[head].header().step() <= limit; }
    /// Forgets the taken samples at the front: all of them at once when nothing is left.
    void drop_taken() {
      if (head == pending.size()) {
        pending.clear();
        head = 0;
      } else if (head >= 64) {
        pending.erase(pending.begin(), pending.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
    }
  };
  /// Moves the slot's readable pending samples to `out`, in step order; the last becomes its
  /// latest. Call with mutex_ held.
  void take_readable(Slot& slot, std::vector<Msg>& out) const {
    const std::uint64_t limit = readable_limit();
    const std::size_t first = out.size();
    while (slot.has_readable(limit)) {
      out.push_back(std::move(slot.pending[slot.head++]));
    }
    slot.drop_taken();
    if (out.size() > first) {
      slot.latest = out.back();
    }
  }
  /// Skips the slot's readable pending samples to the newest; that one, or the last kept, or
  /// nullptr. Call with mutex_ held.
  const Msg* newest_readable(Slot& slot) const {
    const std::uint64_t limit = readable_limit();
    while (slot.has_readable(limit)) {
      slot.latest = std::move(slot.pending[slot.head++]);
    }
    slot.drop_taken();
    return slot.latest ? &*slot.latest : nullptr;
  }

  // slots_[i] belongs to instances_[i]. A deque: latest() hands out pointers into it that stay
  // valid while samples of new instances arrive (and add slots) on a listener thread.
  std::deque<Slot> slots_;
};

/// Whether an Output tells its writer which instances ended (WriterHandle::end_instance).
enum class InstanceEnds {
  /// The last sample of every instance stays with the transport for readers that join later
  /// (missions, run/health) or the writer is the host's own (ticks, acknowledgements).
  kKept,
  /// A component's stream topics: an instance ends with a sample whose next_step is kNeverAgain,
  /// or when a due step it announced passes without a sample (its producer moved the robot to
  /// another key, e.g. a new target: Subscription::robot_streams()). In real time the due step
  /// may pass by kRealtimeEndGracePeriods of the component's periods first (a late loop is not an
  /// ended stream).
  kForgotten,
};

/// Real time: periods past its announced due step after which an instance without a sample ends.
inline constexpr std::uint64_t kRealtimeEndGracePeriods = 50;

template <class Msg>
class Output {
 public:
  Output(std::shared_ptr<WriterHandle> writer, const StepState* state, InstanceEnds ends = InstanceEnds::kKept)
      : writer_(std::move(writer)), state_(state), ends_(ends) {}

  /// Stamps the header (step, next_step = the component's next due step, time) and writes.
  void publish(Msg& sample) { publish_with_next(sample, state_->step + state_->period_steps); }
  /// For samples that will not be followed by another (e.g. a mission): next_step = never.
  void publish_final(Msg& sample) { publish_with_next(sample, kNeverAgain); }
  /// For a producer that publishes an instance only when it changes (e.g. a mission with events):
  /// the next sample of this instance comes at `next_step` (> the current step), or kNeverAgain.
  void publish_next_at(Msg& sample, std::uint64_t next_step) { publish_with_next(sample, next_step); }
  const std::string& topic() const { return writer_->topic(); }
  /// Instances this output has ended so far (InstanceEnds::kForgotten), for tests and logs.
  std::uint64_t ended_instances() const { return ended_; }

 private:
  void publish_with_next(Msg& sample, std::uint64_t next_step) {
    sample.header().step(state_->step);
    sample.header().next_step(next_step);
    sample.header().stamp_ns(state_->stamp_ns);
    if (ends_ == InstanceEnds::kForgotten) {
      end_missed_instances();
    }
    writer_->write(&sample);
    if (ends_ == InstanceEnds::kForgotten) {
      note_written(sample, next_step);
    }
  }

  /// An instance this output wrote: its key members and the step its last sample announced.
  struct Written {
    Msg key_sample;
    std::uint64_t due = 0;
    bool live = false;
  };

  /// At the first sample of a new step: every live instance that was due at or before the
  /// previous step this output published at, and got no sample there, has ended. One pass over
  /// this output's instances per step (each is written about once a step: O(1) per sample).
  void end_missed_instances() {
    const std::uint64_t step = state_->step;
    if (publishing_step_ == kNeverAgain || step <= publishing_step_) {
      publishing_step_ = step;  // the first step, or another sample of the step
      return;
    }
    const std::uint64_t previous = publishing_step_;
    publishing_step_ = step;
    const std::uint64_t grace = state_->mode == TimeMode::kRealtime ? kRealtimeEndGracePeriods * state_->period_steps : 0;
    if (live_ == 0 || previous < grace) {
      return;
    }
    for (Written& w : written_) {
      if (w.live && w.due <= previous - grace) {
        end(w);
      }
    }
  }

  void note_written(const Msg& sample, std::uint64_t next_step) {
    const auto [i, added] = index_.insert(idl::instance_key(sample));
    if (added) {
      written_.push_back(Written{idl::key_sample(sample), 0, false});
    }
    Written& w = written_[i];
    if (!w.live) {
      w.live = true;
      ++live_;
    }
    w.due = next_step;
    if (next_step == kNeverAgain) {
      end(w);
    }
  }

  void end(Written& w) {
    writer_->end_instance(&w.key_sample);
    w.live = false;
    --live_;
    ++ended_;
  }

  std::shared_ptr<WriterHandle> writer_;
  const StepState* state_;
  InstanceEnds ends_;
  // Instances written (kForgotten): bounded by the keys this component writes, which it chooses.
  KeyIndex index_;
  std::vector<Written> written_;
  std::size_t live_ = 0;
  std::uint64_t publishing_step_ = kNeverAgain;  // the step of the last sample; kNeverAgain: none yet
  std::uint64_t ended_ = 0;
};

}  // namespace robodds
