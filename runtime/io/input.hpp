#pragma once
// Input<Msg>: a component's typed input. It stores the samples of the instances it wants, runs
// every sample's checks (non-finite numbers, then runtime/io/sample_checks.hpp) and hands the
// component what the lockstep rule lets it read (take_new, latest, the *_of_robot reads). The
// type-free bookkeeping is InputBase (input_base.hpp).

#include <algorithm>
#include <cstdint>
#include <deque>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/io/input_base.hpp"
#include "runtime/io/sample_verdict.hpp"

namespace robodds {

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
    require_every_sample("take_new");
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
    require_every_sample("take_new");
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
    require_every_sample("take_new_of_robots");
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
      if (!known_key(key)) {
        refuse_unknown_key(key, meta.writer_id);
        return false;
      }
      const std::size_t stream = wanted_stream(stream_of(key));
      if (stream == KeyIndex::kNone) {
        return false;
      }
      // Spelled once per instance, for messages only: no string is built for an ordinary sample.
      i = add_instance(key, stream, idl::instance_label(sample));
      slots_.emplace_back();
    }
    const CheckResult failed = delivery_check(sample, meta, state_->mode);
    const std::string& label = instances_[i].label;
    Stream& s = streams_[instances_[i].stream];
    Progress& p = s.progress;
    if (!accept_producer(p, label, meta, key, !failed)) {
      return !lockstep_error_.empty();  // in lockstep a second producer ends the run: let ready() throw it now
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

}  // namespace robodds
