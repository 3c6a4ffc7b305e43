#include "runtime/lockstep/lockstep_host.hpp"

#include <algorithm>
#include <optional>
#include <thread>

#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/qos_profiles.hpp"
#include "runtime/base/log.hpp"
#include "runtime/lockstep/history_checkpoints.hpp"

namespace robodds {

using host_detail::Clock;
using host_detail::dds_report;
using host_detail::fmt_s;
using host_detail::finish_run;
using host_detail::samples_of_run;
using host_detail::seconds_since;
using host_detail::sim_stamp_ns;

namespace {

/// Lockstep across processes: per slot, every how many steps its host must wait for its gated
/// inputs besides its due steps (0: the due steps suffice), so that no producer's `lockstep`
/// writer history (KEEP_LAST depth) can drop a sample the component still needs
/// (history_checkpoints.hpp). ConfigError, naming the component, topic and figures, when no wait
/// can keep the bound (window + delay > depth). All 0 when the bus has no such history (in memory).
std::vector<std::uint64_t> history_checkpoints(const RunContext& run, const HostOptions& options,
                                               const LockstepHost::Slots& slots) {
  std::vector<std::uint64_t> every(slots.size(), 0);
  const std::optional<std::size_t> depth = run.bus->writer_history_depth(kLockstepProfile);
  if (!depth) {
    return every;
  }
  const std::uint64_t window = std::max<std::uint64_t>(1, options.lockstep_window);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const auto& slot = slots[i];
    for (const auto& input : slot->context->inputs()) {
      if (!input->gated()) {
        continue;
      }
      const std::optional<std::uint64_t> steps =
          history_checkpoint_steps(window, slot->state.period_steps, input->delay_steps(), *depth);
      if (!steps) {
        throw ConfigError("lockstep: component '" + slot->spec->name + "' reads " + input->topic() + " " +
                          std::to_string(input->delay_steps()) + " step(s) late: with --lockstep-window " +
                          std::to_string(window) + " its producers may write " +
                          std::to_string(window + input->delay_steps()) +
                          " samples of an instance before it reads them even if its host waits for them at every step, "
                          "more than the '" + kLockstepProfile + "' QoS profile's writer history keeps (KEEP_LAST " +
                          std::to_string(*depth) + "): lower --lockstep-window or raise that depth in the QoS file");
      }
      if (*steps > 0 && (every[i] == 0 || *steps < every[i])) {
        every[i] = *steps;
      }
    }
    if (every[i] > 0) {
      log::info(options.member, "lockstep: component '" + slot->spec->name + "' runs every " +
                                    std::to_string(slot->state.period_steps) + " steps; its host also waits for its inputs every " +
                                    std::to_string(every[i]) + " steps (the producers' writer history keeps " +
                                    std::to_string(*depth) + " samples)");
    }
  }
  return every;
}

/// Lockstep: ConfigError when a component's gated input waits for an instance no component of the
/// scenario publishes (RunContext::assigned_producers), or, for a topic whose producers declare
/// its instances (RunContext::produced_instances, e.g. pairs of robots), for an instance none of
/// them declares: it would wait at step 0 until the step timeout and then fail; say so before the
/// first tick, naming the component, topic and robot or instance.
void check_inputs_have_producers(const RunContext& run, const LockstepHost::Slots& slots) {
  if (!run.assigned_producers) {
    return;  // a component without a scenario: its producers are not known
  }
  for (const auto& slot : slots) {
    for (const auto& input : slot->context->inputs()) {
      if (!input->gated()) {
        continue;
      }
      const auto topic = run.assigned_producers->find(input->topic());
      const std::vector<std::uint64_t>* declared = nullptr;  // ascending (produced_instances())
      if (run.produced_instances && !input->by_robot()) {
        const auto it = run.produced_instances->find(input->topic());
        if (it != run.produced_instances->end() && !it->second.empty()) declared = &it->second;
      }
      for (std::uint64_t key : input->expected()) {
        const std::uint32_t robot = input->robot_of(key);
        if (topic == run.assigned_producers->end() || topic->second.count(robot) == 0) {
          throw ConfigError(located(run.scenario->file, "components",
                                    "lockstep: component '" + slot->spec->name + "' waits at every step for " + input->topic() +
                                        " of robot " + std::to_string(robot) +
                                        ", which no component of the scenario publishes (add its producer for that robot, "
                                        "or take the robot out of '" + slot->spec->name + "')"));
        }
        if (declared != nullptr && !std::binary_search(declared->begin(), declared->end(), key)) {
          const std::string& names = topic_info(input->topic()).key;
          std::string listed;
          for (const std::uint64_t k : *declared) listed += (listed.empty() ? "" : ", ") + instance_key_text(names, k);
          const std::string& component = slot->spec->name;
          throw ConfigError(located(run.scenario->file, "components",
                                    "lockstep: component '" + component + "' waits at every step for " + input->topic() + " (" +
                                        instance_key_text(names, key) + "), an instance its producer '" +
                                        topic->second.at(robot).front() + "' does not publish (the scenario's producers " +
                                        "declare " + listed + "); give the producer that instance, or take it out of '" +
                                        component + "'"));
        }
      }
    }
  }
}

}  // namespace

LockstepHost::LockstepHost(RunContext& run, const HostOptions& options, Slots& slots, Bus& protocol_bus,
                           HealthExchange* health)
    : run_(run), options_(options), slots_(slots), health_(health), digests_(options.digest, options.run_id) {
  state_.mode = run.mode;
  const TopicInfo& clock = topic_info("sim/clock");
  const TopicInfo& done = topic_info("sim/step_done");
  const std::string profile = qos_profile_for(clock, run.mode, run.single_process);
  detail::InputOptions tick_options;
  tick_options.ignore_step = true;
  tick_input_ = std::make_unique<Input<idl::SimTick>>(clock.name, options.member, &state_, run.notifier, tick_options);
  auto* raw = tick_input_.get();
  tick_reader_ = protocol_bus.reader(clock.name, clock.type_name, profile, samples_of_run(raw, options.run_id),
                                 [this](const std::string& e) { log::warn(options_.member, "sim/clock: " + e); });
  ack_writer_ = protocol_bus.writer(done.name, done.type_name, profile);
  ack_ahead_ = !options.digest.empty();
  ack_output_ = std::make_unique<Output<idl::StepDone>>(ack_writer_, &state_);
  check_inputs_have_producers(run, slots);
  checkpoint_steps_ = run.mode == TimeMode::kLockstep && !run.single_process ? history_checkpoints(run, options, slots)
                                                                              : std::vector<std::uint64_t>(slots.size(), 0);
  checkpoint_pending_.assign(slots.size(), false);
  // Newest-only inputs read at their component's due and checkpoint steps only: across processes
  // the writers leave the other samples out (before the bus starts: the readers' filters).
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const StepNeeds busy = StepNeeds::of_component(slots[i]->state.period_steps, checkpoint_steps_[i], 0);
    if (busy_steps_) {
      busy_steps_->add(busy);
    } else {
      busy_steps_ = busy;
    }
    for (const auto& input : slots[i]->context->inputs()) {
      if (input->newest_only()) {
        input->read_only(StepNeeds::of_component(slots[i]->state.period_steps, checkpoint_steps_[i], input->delay_steps()));
      }
    }
  }
}

void LockstepHost::begin(Clock::time_point start) {
  start_ = start;
  waiting_since_ = start;
}

bool LockstepHost::step() {
  digests_.fail_on_difference(*run_.bus, options_.member);
  bool progressed = false;
  if (!tick_active_) {
    progressed = take_tick();
  }
  if (tick_active_) {
    const Bus::WriteBatch batch(*run_.bus);
    progressed = run_due_components() || progressed;
  }
  return progressed;
}

bool LockstepHost::take_tick() {
  for (idl::SimTick& tick : tick_input_->take_new(0)) {
    if (tick.run_id() == options_.run_id) {
      tick_queue_.push_back(std::move(tick));
    }
  }
  if (tick_queue_.empty()) {
    const double limit = first_tick_ ? options_.start_timeout_s : options_.tick_timeout_s;
    if (seconds_since(waiting_since_) > limit) {
      const std::string advice = !options_.no_tick_advice.empty()
                                     ? options_.no_tick_advice
                                     : std::string("is the coordinator (robodds run) alive and on the same domain?");
      throw RunError(options_.member + ": no tick on sim/clock for " + fmt_s(limit) + " s " +
                     (first_tick_ ? "after start" : "after step " + std::to_string(tick_step_)) + ": " + advice +
                     dds_report(*run_.bus));
    }
    return false;
  }
  const idl::SimTick tick = tick_queue_.front();
  tick_queue_.pop_front();
  if (tick.step_s() != run_.scenario->step_s) {
    // A host that does not load the coordinator's scenario (a component executable with its
    // own --step) would otherwise integrate and stamp with the wrong dt, silently.
    throw RunError(options_.member + ": the coordinator's step is " + shortest_text(tick.step_s()) + " s, this host's " +
                   shortest_text(run_.scenario->step_s) + " s (--step or the scenario's step_s must agree)");
  }
  tick_active_ = true;
  tick_step_ = tick.header().step();
  tick_is_final_ = tick.final_tick();
  components_run_ = 0;
  if (first_tick_ && run_.figures.thirds_done_at_s.empty()) {
    run_.figures.thirds_done_at_s.push_back(seconds_since(start_));  // the thirds count from the first tick
  }
  first_tick_ = false;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    auto& slot = slots_[i];
    slot->pending = tick_step_ % slot->state.period_steps == 0;
    slot->state.step = tick_step_;
    slot->state.stamp_ns = sim_stamp_ns(tick_step_, run_.scenario->step_s);
    checkpoint_pending_[i] = !slot->pending && checkpoint_steps_[i] > 0 && tick_step_ % checkpoint_steps_[i] == 0;
  }
  waiting_since_ = Clock::now();
  return true;
}

bool LockstepHost::run_due_components() {
  const double step_s = run_.scenario->step_s;
  bool progressed = false;
  bool all_done = true;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    auto& slot = slots_[i];
    const bool checkpoint = checkpoint_pending_[i];
    if (!slot->pending && !checkpoint) {
      continue;
    }
    const InputBase* blocking = nullptr;
    for (const auto& input : slot->context->inputs()) {
      if (!input->ready(tick_step_, nullptr)) {  // no message built at every wake-up
        blocking = input.get();
        break;
      }
    }
    if (blocking != nullptr) {
      all_done = false;
      if (seconds_since(waiting_since_) > options_.input_timeout_s) {
        std::string missing;
        if (blocking->ready(tick_step_, &missing)) {
          continue;  // it arrived meanwhile
        }
        throw RunError("lockstep: component '" + slot->spec->name + "' waited " + fmt_s(options_.input_timeout_s) +
                       " s at step " + std::to_string(tick_step_) + (checkpoint ? " (a history checkpoint)" : "") +
                       " for topic " + blocking->topic() + ", " + missing + dds_report(*run_.bus));
      }
      continue;
    }
    if (checkpoint) {
      checkpoint_pending_[i] = false;  // its inputs are in: the step may be acknowledged without running it
      progressed = true;
      continue;
    }
    const double time_s = static_cast<double>(tick_step_) * step_s;
    const double dt_s = slot->has_run ? static_cast<double>(tick_step_ - slot->last_run_step) * step_s : 0.0;
    slot->run(tick_step_, time_s, dt_s);
    slot->pending = false;
    ++components_run_;
    progressed = true;
  }
  if (!all_done) {
    return progressed;
  }
  if (tick_is_final_) {
    OverrunFigures lockstep_figures;  // lockstep waits for every step: none is missed or late
    lockstep_figures.ticks = tick_step_ + 1;
    finish_run(run_, options_.member, lockstep_figures, slots_, health_, tick_step_, seconds_since(start_));
    done_ = true;
  }
  // A step before the one the last acknowledgement announced had no work here (next_busy_step):
  // the coordinator counts it done already, and an acknowledgement would wake it for nothing.
  if (!ack_ahead_ || tick_is_final_ || tick_step_ >= next_ack_step_) {
    next_ack_step_ = ack_ahead_ && !tick_is_final_ ? next_busy_step(tick_step_) : tick_step_ + 1;
    publish_ack(tick_step_, components_run_, "", next_ack_step_);
  }
  tick_active_ = false;
  steps_done_ = tick_step_ + 1;
  note_thirds();
  waiting_since_ = Clock::now();
  return true;
}

void LockstepHost::note_thirds() {
  const std::uint64_t steps = run_.scenario->last_step() + 1;
  const std::size_t noted = run_.figures.thirds_done_at_s.size();  // 1: the first tick's time
  if (steps >= 3 && noted >= 1 && noted < 3 && steps_done_ == steps * noted / 3) {
    run_.figures.thirds_done_at_s.push_back(seconds_since(start_));
  }
}

void LockstepHost::publish_failure(const std::string& error, bool await_coordinator) {
  const Clock::time_point asked = Clock::now();
  while (await_coordinator && !ack_writer_->has_matched_readers() && seconds_since(asked) < options_.start_timeout_s) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  publish_ack(tick_step_, 0, error, tick_step_ + 1);
  // The process exits next, and its participant's goodbye can overtake the report: the
  // coordinator then drops it with the writer and waits for this group until its own timeout
  // (docs/deployment.md, "A failing host's last word"). So wait until the report is acknowledged.
  const Clock::time_point since = Clock::now();
  if (ack_writer_->wait_acknowledged(kFailureReportWait)) {
    log::debug(options_.member, "failure report acknowledged after " + std::to_string(seconds_since(since)) + " s");
  } else {
    log::warn(options_.member, "the coordinator did not acknowledge this host's failure report within " +
                                   fmt_s(std::chrono::duration<double>(kFailureReportWait).count()) + " s (is it gone?)");
  }
}

std::uint64_t LockstepHost::next_busy_step(std::uint64_t step) const {
  const std::uint64_t last_or_next = std::max(run_.scenario->last_step(), step + 1);
  return busy_steps_ ? std::min(last_or_next, busy_steps_->first_read_step_from(step + 1)) : last_or_next;
}

void LockstepHost::publish_ack(std::uint64_t step, std::uint64_t components_run, const std::string& error,
                               std::uint64_t next_ack) {
  idl::StepDone ack;
  ack.member(options_.member);
  ack.run_id(options_.run_id);
  ack.components_run(static_cast<std::uint32_t>(components_run));
  ack.failed(!error.empty());
  ack.error(error.substr(0, 500));
  state_.step = step;
  state_.period_steps = 1;
  state_.stamp_ns = sim_stamp_ns(step, run_.scenario->step_s);
  ack_output_->publish_next_at(ack, next_ack);
}

}  // namespace robodds
