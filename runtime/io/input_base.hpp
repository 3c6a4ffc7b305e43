#pragma once
// The type-free part of an Input (input.hpp): per stream, its progress and readiness in lockstep
// (the lockstep rule, docs/architecture.md), its producer (one producer per instance), lost-sample
// detection, freshness in real time, the counts of accepted and dropped samples, and whom to
// wake. The hot path (ready(), the checks of every sample) stays inline here; what runs once per
// instance, writer or error (labels, logs, hand-overs) is in input_base.cpp.

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/bus/bus.hpp"
#include "runtime/bus/key_index.hpp"
#include "runtime/bus/step_needs.hpp"
#include "runtime/io/input_counts.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/io/step_state.hpp"
#include "runtime/io/subscription.hpp"

namespace robodds {

/// Instance `key` of a topic keyed `key_names` (TopicInfo::key, e.g. "robot_id, peer_id") spelled
/// for messages: "robot_id=2 peer_id=3", "robot_id=2", "instance K" without key names.
std::string instance_key_text(const std::string& key_names, std::uint64_t key);

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
    std::sort(options_.known_robots.begin(), options_.known_robots.end());
    keyed_ = !options_.key_names.empty() && options_.key_names != "-";
    pair_keyed_ = options_.key_names.find(',') != std::string::npos;
  }
  virtual ~InputBase() = default;

  const std::string& topic() const { return topic_; }
  /// Lockstep: reads samples up to `delay_steps()` steps old, and waits for some streams (gated).
  std::uint64_t delay_steps() const { return options_.delay_steps; }
  bool gated() const { return !options_.ignore_step && !options_.expected.empty(); }
  /// Subscription::newest_only(): the component reads only the newest sample at its due steps.
  bool newest_only() const { return options_.newest_only && !options_.ignore_step; }
  /// Lockstep, newest_only(): the samples this input will read (its component's due and
  /// checkpoint steps, its delay), set by the host before the bus starts. The bus may then leave
  /// out the others (ReaderHandle::set_step_needs: the reader attach_reader() gave), and a
  /// sample skipping steps breaks the chain only when it skips one of these (check_chain()).
  void read_only(const StepNeeds& needs) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      read_steps_ = needs;
    }
    if (reader_ != nullptr) {
      reader_->set_step_needs(needs);
    }
  }
  /// The bus subscription that feeds this input (read_only() tells it what to send).
  void attach_reader(ReaderHandle* reader) { reader_ = reader; }
  /// The instances (by_robot(): robot ids) needed at every due step, in key order.
  const std::vector<std::uint64_t>& expected() const { return options_.expected; }
  /// Its streams are robots (Subscription::robot_streams): expected() holds robot ids.
  bool by_robot() const { return options_.by_robot; }
  /// The robot of expected key `key` (a robot id itself for robot streams).
  std::uint32_t robot_of(std::uint64_t key) const {
    return options_.by_robot ? static_cast<std::uint32_t>(key) : robot_of_instance(key);
  }
  /// The robot of instance key `key`: the key, its upper 32 bits for a (robot_id, X) key, 0 for
  /// an unkeyed topic's one instance.
  std::uint32_t robot_of_instance(std::uint64_t key) const {
    return !keyed_ ? 0u : static_cast<std::uint32_t>(pair_keyed_ ? key >> 32 : key);
  }
  std::uint64_t rejected_count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_.rejected_total();
  }
  InputCounts counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }
  /// Whether this input takes a sample of instance `key` at all: its key names a robot of the
  /// scenario (InputOptions::known_robots). Bus::KeyFilter::takes, so that the transport drops
  /// the others before it keeps state for them. Reads only what the constructor set: no lock.
  bool takes_key(std::uint64_t key) const { return known_key(key); }
  /// Whether takes_key() refuses any key: a keyed component input of a scenario run. Host-level
  /// and unkeyed inputs take every key.
  bool filters_keys() const { return !options_.known_robots.empty() && !options_.ignore_step && keyed_; }
  /// The transport dropped a sample of `key` (takes_key() false) from writer `writer_id`: counted
  /// as unknown_key, as store() counts one that reaches the input. Bus::KeyFilter::refused.
  void count_unknown_key(std::uint64_t key, std::uint64_t writer_id) {
    std::lock_guard<std::mutex> lock(mutex_);
    refuse_unknown_key(key, writer_id);
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
    // InputOptions::producer_assigned's last answers, so that a writer's samples ask it once.
    std::uint64_t assigned_writer = 0;
    std::uint64_t refused_writer = 0;
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
  /// With read_only(), a sample may skip steps whose samples were never needed (left out by
  /// the writer): only a skipped read step is a break.
  void check_chain(const Progress& p, const std::string& label, std::uint64_t step) {
    if (state_->mode == TimeMode::kLockstep && !options_.ignore_step && p.seen && step > p.next_step && lockstep_error_.empty() &&
        (!read_steps_ || read_steps_->first_read_step_from(p.next_step) < step)) {
      note_lost_samples(p, label, step);
    }
  }
  /// take_new() and its kin read every sample: refused on a newest_only() input (ConfigError
  /// naming the topic and the component), which may not get them.
  void require_every_sample(const char* read) const {
    if (options_.newest_only) {
      throw ConfigError(owner_ + ": " + read + "() on " + topic_ +
                        ", which it subscribed newest_only(): read it with latest(), or subscribe without newest_only()");
    }
  }
  /// check_chain() found a break: records and logs the error ready() throws. Call with mutex_ held.
  void note_lost_samples(const Progress& p, const std::string& label, std::uint64_t step);

  /// One producer per instance (docs/architecture.md, "One producer per instance and hot standby"):
  /// true if the sample of `writer_id` may be used. The first writer of an instance becomes its
  /// producer. Another writer is, with exclusive ownership, a hand-over (logged); in lockstep an
  /// error that ends the run (ready() throws it); in real time dropped and counted as
  /// second_producer (first writer wins) unless the producer was silent for kProducerSilenceNs.
  /// Call with mutex_ held.
  /// In a scenario run (InputOptions::producer_assigned) only a writer the scenario assigns to the
  /// instance may be its producer: any other is refused and counted as unknown_producer, whether
  /// it came first or not. A writer whose sample fails its checks (`sample_ok` false) claims
  /// nothing in real time and takes nothing over (the real producer may come later); lockstep
  /// claims anyway, its chain of steps must go on. Call with mutex_ held.
  bool accept_producer(Progress& p, const std::string& label, const SampleMeta& meta, std::uint64_t key, bool sample_ok) {
    if (meta.writer_id == 0 || options_.ignore_step || meta.writer_id == p.producer) {
      return true;  // the sample of nearly every call: its instance's producer
    }
    if (options_.producer_assigned && !assigned(p, meta.writer_id, key)) {
      count_rejection_lazily(detail::kRejectUnknownProducer, meta.writer_id, [&label] {
        return "(" + label + "): the scenario does not assign this instance to that writer's process (a foreign program, "
               "or another component)";
      });
      return false;
    }
    if (p.producer == 0) {
      if (sample_ok || state_->mode == TimeMode::kLockstep) {
        p.producer = meta.writer_id;
      }
      return true;
    }
    return accept_other_writer(p, label, meta, sample_ok);
  }
  /// accept_producer() of a writer that is not the instance's producer. Call with mutex_ held.
  bool accept_other_writer(Progress& p, const std::string& label, const SampleMeta& meta, bool sample_ok);
  /// InputOptions::producer_assigned for `writer_id`, asked once per writer and stream in a row.
  bool assigned(Progress& p, std::uint64_t writer_id, std::uint64_t key) {
    if (writer_id == p.assigned_writer) {
      return true;
    }
    if (writer_id == p.refused_writer) {
      return false;
    }
    const bool yes = options_.producer_assigned(writer_id, robot_of_instance(key));
    (yes ? p.assigned_writer : p.refused_writer) = writer_id;
    return yes;
  }
  /// The key names a robot of the scenario (InputOptions::known_robots; the first key part of a
  /// pair). Host-level and unkeyed inputs know every key.
  bool known_key(std::uint64_t key) const {
    if (!filters_keys()) {
      return true;
    }
    return std::binary_search(options_.known_robots.begin(), options_.known_robots.end(), robot_of_instance(key));
  }
  /// A sample of `key` (known_key() false) refused as unknown_key: counted, the first one of each
  /// writer logged, nothing kept for the key (a flood of keys grows no state). Call with mutex_ held.
  void refuse_unknown_key(std::uint64_t key, std::uint64_t writer_id) {
    count_rejection_lazily(detail::kRejectUnknownKey, writer_id,
                           [key] { return "(key " + std::to_string(key) + "): the scenario has no such robot"; });
  }
  /// The writer's name for messages (InputOptions::writer_name, else "writer <id>").
  std::string writer_label(std::uint64_t writer_id) const;

  /// Counts a dropped sample; the first of each (writer, reason) is logged, naming the writer:
  /// "rejected a sample on <topic> from <writer> <detail>; ...". Call with mutex_ held.
  void count_rejection(const std::string& reason, const std::string& detail, std::uint64_t writer_id) {
    count_rejection_lazily(reason, writer_id, [&detail] { return detail; });
  }
  /// count_rejection() whose detail (a string) is built only when it is logged: a flood of
  /// refused samples builds no text.
  template <class Detail>
  void count_rejection_lazily(const std::string& reason, std::uint64_t writer_id, Detail&& detail) {
    ++counts_.rejected[reason];
    if (logged_rejections_.insert({writer_id, reason}).second) {
      log_rejection(detail(), writer_id);
    }
  }
  /// Logs the first rejection of a writer and reason. Call with mutex_ held.
  void log_rejection(const std::string& detail, std::uint64_t writer_id) const;

  /// `key`: an instance, or with by_robot a robot id (then its current instance's label), spelled
  /// for messages. Call with mutex_ held.
  std::string label_of(std::uint64_t key) const;
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
  std::size_t add_instance(std::uint64_t key, std::size_t stream, std::string label);
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
  ReaderHandle* reader_ = nullptr;         // attach_reader(); owned by the component's context
  std::optional<StepNeeds> read_steps_;    // read_only(); guarded by mutex_
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
  bool keyed_ = false;       // the topic has a key (InputOptions::key_names, "-": none)
  bool pair_keyed_ = false;  // the topic's key is (robot_id, X): the robot is its upper 32 bits
};

}  // namespace robodds
