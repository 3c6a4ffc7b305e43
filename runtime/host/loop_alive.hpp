#pragma once
// run/alive (issue 24, finding 6: a host that stops reporting): every real-time host across
// processes publishes a beat from its loop every LoopSilence::kBeatPeriodS and reads the other
// groups' beats; LoopSilence names a group whose loop went silent while its participant lives.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/component/component.hpp"
#include "runtime/health/loop_silence.hpp"

namespace robodds {

class LoopAlive {
 public:
  /// Advertises run/alive and subscribes to it (beats of `run_id` only). Call before the bus
  /// starts. `others`: the groups to watch; `run` must outlive this object.
  LoopAlive(RunContext& run, std::string member, std::uint64_t run_id, std::vector<std::string> others);

  /// From the loop, every iteration: publishes a beat when the last one is kBeatPeriodS old
  /// (`elapsed_s`: s after step 0; `step`: the step the loop just ran).
  void beat(double elapsed_s, std::uint64_t step);

  /// From the loop, every iteration: takes the beats that arrived and returns the groups silent
  /// beyond the limit whose participant `participant_alive` says is alive (LoopSilence::check).
  std::vector<LoopSilence::Silent> silent(double elapsed_s, double end_s,
                                          const std::function<bool(const std::string&)>& participant_alive);

  /// The groups whose beats arrived at least once (as of the last silent()).
  std::vector<std::string> heard_groups() const { return silence_.heard_groups(); }

 private:
  RunContext& run_;
  std::string member_;
  std::uint64_t run_id_;
  StepState state_;
  LoopSilence silence_;
  double next_beat_s_ = 0.0;
  std::unique_ptr<Output<idl::HostAlive>> output_;
  std::unique_ptr<Input<idl::HostAlive>> input_;
  std::shared_ptr<ReaderHandle> reader_;
};

}  // namespace robodds
