#include "runtime/host/loop_alive.hpp"

#include "runtime/base/log.hpp"
#include "runtime/host/host_slot.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {

LoopAlive::LoopAlive(RunContext& run, std::string member, std::uint64_t run_id, std::vector<std::string> others)
    : run_(run), member_(std::move(member)), run_id_(run_id), silence_(others) {
  state_.mode = run.mode;
  const TopicInfo& topic = topic_info("run/alive");
  const std::string profile = qos_profile_for(topic, run.mode, run.single_process);
  output_ = std::make_unique<Output<idl::HostAlive>>(run.bus->writer(topic.name, topic.type_name, profile), &state_);
  detail::InputOptions options;
  options.ignore_step = true;
  options.key_names = topic.key;
  input_ = std::make_unique<Input<idl::HostAlive>>(topic.name, member_, &state_, run.notifier, options);
  reader_ = run.bus->reader(topic.name, topic.type_name, profile, host_detail::samples_of_run(input_.get(), run_id_),
                            [this](const std::string& e) { log::warn(member_, "run/alive: " + e); });
}

void LoopAlive::beat(double elapsed_s, std::uint64_t step) {
  if (elapsed_s < next_beat_s_) {
    return;
  }
  next_beat_s_ = elapsed_s + LoopSilence::kBeatPeriodS;
  idl::HostAlive alive;
  alive.member(member_.substr(0, 64));  // string<64> of the IDL
  alive.run_id(run_id_);
  state_.step = step;
  state_.stamp_ns = wall_clock_now_ns();
  output_->publish(alive);
}

std::vector<LoopSilence::Silent> LoopAlive::silent(double elapsed_s, double end_s,
                                                   const std::function<bool(const std::string&)>& participant_alive) {
  for (std::uint64_t key : input_->instances()) {
    for (const idl::HostAlive& alive : input_->take_new(key)) {
      silence_.heard(alive.member().to_string(), elapsed_s);
    }
  }
  return silence_.check(elapsed_s, end_s, participant_alive);
}

}  // namespace robodds
