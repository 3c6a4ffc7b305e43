#include "runtime/lockstep/lockstep_coordinator.hpp"

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace {

std::uint64_t member_key(const std::string& member) {
  idl::StepDone probe;
  probe.member(member);
  return idl::instance_key(probe);
}

}  // namespace

using host_detail::Clock;
using host_detail::dds_report;
using host_detail::fmt_s;
using host_detail::seconds_since;
using host_detail::sim_stamp_ns;

LockstepCoordinator::LockstepCoordinator(const RunContext& run, const HostOptions& options, Bus& protocol_bus)
    : run_(run), options_(options), digests_(options.digest, options.run_id) {
  state_.mode = run.mode;
  const TopicInfo& clock = topic_info("sim/clock");
  const TopicInfo& done = topic_info("sim/step_done");
  const std::string profile = qos_profile_for(clock, run.mode, run.single_process);
  detail::InputOptions ack_options;
  ack_options.ignore_step = true;
  for (const std::string& member : options.members) {
    ack_options.expected.push_back(member_key(member));
    ack_options.labels[member_key(member)] = "'" + member + "'";
  }
  ack_input_ = std::make_unique<Input<idl::StepDone>>(done.name, "coordinator", &state_, run.notifier, ack_options);
  // A stale host of another run must not count: samples_of_run() passes this run's acks only.
  ack_reader_ = protocol_bus.reader(done.name, done.type_name, profile, host_detail::samples_of_run(ack_input_.get(), options.run_id),
                                [](const std::string& e) { log::warn("coordinator", "sim/step_done: " + e); });
  tick_output_ = std::make_unique<Output<idl::SimTick>>(protocol_bus.writer(clock.name, clock.type_name, profile), &state_);
}

void LockstepCoordinator::begin(Clock::time_point start) { ack_progress_at_ = start; }

bool LockstepCoordinator::poll() {
  // Before a member's failure report: a host that loaded other files fails because of it, and
  // the difference is the reason to give.
  digests_.fail_on_difference(*run_.bus, "coordinator");
  for (std::uint64_t key : ack_input_->instances()) {
    for (const idl::StepDone& ack : ack_input_->take_new(key)) {
      if (ack.run_id() == options_.run_id) {  // by instance key: no string per acknowledgement
        NewestAck& newest = newest_ack_[key];
        newest.step = std::max(newest.step, ack.header().step());
        newest.covers_to = std::max({newest.covers_to, ack.header().step() + 1, ack.header().next_step()});
      }
      if (ack.run_id() == options_.run_id && ack.failed()) {
        // A host that stopped because another loaded other files: that difference is the reason
        // (its report can overtake the announcement of the host it names).
        check_digests_once_discovered();
        const std::string report = ack.error().to_string();
        if (report.find(DigestCheck::kAdvice) != std::string::npos) {  // it saw a host this one never did
          throw RunConfigError("group '" + ack.member().to_string() + "' failed at step " + std::to_string(ack.header().step()) +
                               ": " + report);
        }
        throw RunError("group '" + ack.member().to_string() + "' failed at step " + std::to_string(ack.header().step()) +
                       ": " + ack.error().to_string());
      }
    }
  }
  const std::uint64_t last = run_.scenario->last_step();
  // At most `lockstep_window` ticks are outstanding: 1 is the strict rule (the next tick waits
  // for all acknowledgements). A wider window lets the groups of a pipeline work on
  // consecutive steps at once; results are unchanged, because an input at step m only ever
  // reads samples with step <= m - delay, however early later samples arrive.
  const std::uint64_t window = std::max<std::uint64_t>(1, options_.lockstep_window);
  std::string missing;
  bool progressed = false;
  while (acked_steps_ < next_tick_ && ack_input_->ready(acked_steps_, &missing)) {
    if (acked_steps_ == 0) {
      check_digests_once_discovered();
    }
    if (options_.progress) {
      options_.progress(acked_steps_, last);
    }
    ++acked_steps_;
    ack_progress_at_ = Clock::now();
    progressed = true;
  }
  if (acked_steps_ > last) {
    done_ = true;
  }
  while (next_tick_ <= last && next_tick_ < acked_steps_ + window) {
    publish_tick(next_tick_, next_tick_ == last);
    if (next_tick_ == acked_steps_) {
      ack_progress_at_ = Clock::now();  // the oldest outstanding tick starts its wait now
    }
    ++next_tick_;
    progressed = true;
  }
  if (!done_ && !progressed) {
    const double limit = acked_steps_ == 0 ? options_.start_timeout_s : options_.tick_timeout_s;
    if (seconds_since(ack_progress_at_) > limit) {
      throw RunError("lockstep: no acknowledgement of step " + std::to_string(acked_steps_) + " within " + fmt_s(limit) +
                     " s from " + missing_members(missing) + " on sim/step_done" + dds_report(*run_.bus));
    }
  }
  return progressed;
}

std::string LockstepCoordinator::missing_members(const std::string& first_missing) const {
  std::vector<std::string> missing;  // in the order of options.members
  for (const std::string& member : options_.members) {
    const auto newest = newest_ack_.find(member_key(member));
    if (newest == newest_ack_.end()) {
      missing.push_back("'" + member + "' (nothing received yet)");
    } else if (newest->second.covers_to <= acked_steps_) {
      missing.push_back("'" + member + "' (newest sample: step " + std::to_string(newest->second.step) + ")");
    }
  }
  if (missing.size() <= 1) {
    return "group " + first_missing;  // the input's own words (as before several were named)
  }
  std::string text = "groups ";
  for (std::size_t i = 0; i < missing.size(); ++i) {
    text += (i == 0 ? "" : ", ") + missing[i];
  }
  return text;
}

void LockstepCoordinator::check_digests_once_discovered() {
  if (options_.digest.empty()) {
    return;
  }
  const Clock::time_point since = Clock::now();
  while (seconds_since(since) < 0.5) {  // s: PeerDirectory::kParticipantWaitMs
    const std::vector<std::string> found = run_.bus->discovered_participants().value_or(std::vector<std::string>{});
    const bool all = std::all_of(options_.members.begin(), options_.members.end(), [&found](const std::string& m) {
      return std::find(found.begin(), found.end(), "robodds-" + m) != found.end();
    });
    if (all) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  digests_.fail_on_difference(*run_.bus, "coordinator");
}

void LockstepCoordinator::publish_tick(std::uint64_t step, bool final_tick) {
  idl::SimTick tick;
  tick.run_id(options_.run_id);
  tick.step_s(run_.scenario->step_s);
  tick.final_tick(final_tick);
  state_.step = step;
  state_.stamp_ns = sim_stamp_ns(step, run_.scenario->step_s);
  if (final_tick) {
    tick_output_->publish_final(tick);
  } else {
    tick_output_->publish(tick);
  }
}

}  // namespace robodds
