#pragma once
// Output<Msg>: a component's typed output. It stamps each sample's header (step, next_step,
// time) and, for stream topics, tells the writer which instances ended.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/bus/bus.hpp"
#include "runtime/bus/key_index.hpp"
#include "runtime/io/step_state.hpp"

namespace robodds {

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
