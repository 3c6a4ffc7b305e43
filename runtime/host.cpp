#include "runtime/host.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <deque>
#include <thread>

#include "robodds/idl/robodds.h"
#include "runtime/log.hpp"

namespace robodds {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::int64_t wall_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

std::uint64_t member_key(const std::string& member) {
  idl::StepDone probe;
  probe.member(member);
  return idl::instance_key(probe);
}

std::string fmt_s(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", seconds);
  return buf;
}

}  // namespace

struct Host::Impl {
  struct Slot {
    const ComponentSpec* spec = nullptr;
    std::unique_ptr<Component> component;
    std::unique_ptr<ComponentContext> context;
    StepState state;
    bool pending = false;
    bool has_run = false;
    std::uint64_t last_run_step = 0;
    Clock::time_point last_run_wall;
  };

  const ComponentRegistry& registry;
  RunContext run;
  std::uint64_t current_step = 0;  // the tick being processed (for failure reports)
  HostOptions options;
  std::vector<std::unique_ptr<Slot>> slots;

  // Host side of the lockstep protocol.
  StepState host_state;
  std::unique_ptr<Input<idl::SimTick>> tick_input;
  std::shared_ptr<ReaderHandle> tick_reader;
  std::unique_ptr<Output<idl::StepDone>> ack_output;

  // Coordinator side.
  StepState coordinator_state;
  std::unique_ptr<Output<idl::SimTick>> tick_output;
  std::unique_ptr<Input<idl::StepDone>> ack_input;
  std::shared_ptr<ReaderHandle> ack_reader;

  Impl(const ComponentRegistry& r, RunContext rc, HostOptions o) : registry(r), run(std::move(rc)), options(std::move(o)) {}

  void check_stop() const {
    if (options.stop != nullptr && options.stop->load()) {
      throw RunError(options.member + ": interrupted by a signal");
    }
  }

  void configure() {
    for (const std::string& name : options.components) {
      const ComponentSpec& spec = run.scenario->component(name);
      const ComponentType& type = registry.get(spec.type);
      const FlatParams defaults = load_param_file(run.share_dir + "/" + type.defaults_file);
      auto slot = std::make_unique<Slot>();
      slot->spec = &spec;
      slot->state.mode = run.mode;
      slot->component = type.create();
      slot->context = std::make_unique<ComponentContext>(run, spec, ParamReader(spec.name, merge_params(defaults, spec.overrides)),
                                                         &slot->state);
      slot->component->configure(*slot->context);
      slot->context->params().check_all_read();
      slots.push_back(std::move(slot));
    }
    if (run.mode != TimeMode::kLockstep) {
      return;
    }
    host_state.mode = run.mode;
    coordinator_state.mode = run.mode;
    const TopicInfo& clock = topic_info("sim/clock");
    const TopicInfo& done = topic_info("sim/step_done");
    const std::string profile = qos_profile_for(clock, run.mode, run.single_process);
    if (!options.components.empty()) {
      InputOptions tick_options;
      tick_options.ignore_step = true;
      tick_input = std::make_unique<Input<idl::SimTick>>(clock.name, options.member, &host_state, run.notifier, tick_options);
      auto* raw = tick_input.get();
      const std::uint64_t run_id = options.run_id;
      tick_reader = run.bus->reader(clock.name, clock.type_name, profile,
                                    [raw, run_id](const void* s) {
                                      const auto& tick = *static_cast<const idl::SimTick*>(s);
                                      if (tick.run_id() == run_id) {  // ignore ticks of other runs
                                        raw->on_sample(tick);
                                      }
                                    },
                                    [this](const std::string& e) { log::warn(options.member, "sim/clock: " + e); });
      ack_output = std::make_unique<Output<idl::StepDone>>(run.bus->writer(done.name, done.type_name, profile), &host_state);
    }
    if (options.coordinator) {
      InputOptions ack_options;
      ack_options.ignore_step = true;
      for (const std::string& member : options.members) {
        ack_options.expected.push_back(member_key(member));
        ack_options.labels[member_key(member)] = "'" + member + "'";
      }
      ack_input = std::make_unique<Input<idl::StepDone>>(done.name, "coordinator", &coordinator_state, run.notifier, ack_options);
      auto* raw = ack_input.get();
      const std::uint64_t run_id = options.run_id;
      ack_reader = run.bus->reader(done.name, done.type_name, profile,
                                   [raw, run_id](const void* s) {
                                     const auto& ack = *static_cast<const idl::StepDone*>(s);
                                     if (ack.run_id() == run_id) {  // a stale host of another run must not count
                                       raw->on_sample(ack);
                                     }
                                   },
                                   [](const std::string& e) { log::warn("coordinator", "sim/step_done: " + e); });
      tick_output = std::make_unique<Output<idl::SimTick>>(run.bus->writer(clock.name, clock.type_name, profile), &coordinator_state);
    }
  }

  /// "; DDS: ..." naming unmatched topics and incompatible QoS, so a wait that timed out
  /// because peers never matched says so (empty when everything matched).
  std::string dds_report() const {
    const std::string report = run.bus->match_report();
    return report.empty() ? "" : "; " + report;
  }

  std::int64_t sim_stamp_ns(std::uint64_t step) const {
    return static_cast<std::int64_t>(std::llround(static_cast<double>(step) * run.scenario->step_s * 1e9));
  }

  void run_component(Slot& slot, std::uint64_t step, double time_s, double dt_s) {
    try {
      slot.component->on_step(StepInfo{step, time_s, dt_s, slot.state.stamp_ns});
    } catch (const std::exception& e) {
      throw RunError("component '" + slot.spec->name + "' failed at step " + std::to_string(step) + ": " + e.what());
    }
    slot.has_run = true;
    slot.last_run_step = step;
  }

  void finish_components(std::uint64_t step, double time_s) {
    for (auto& slot : slots) {
      try {
        slot->component->on_finish(StepInfo{step, time_s, 0.0, slot->state.stamp_ns});
      } catch (const std::exception& e) {
        throw RunError("component '" + slot->spec->name + "' failed while finishing: " + e.what());
      }
    }
  }

  void publish_ack(std::uint64_t step, std::uint64_t components_run, const std::string& error) {
    if (!ack_output) {
      return;
    }
    idl::StepDone ack;
    ack.member(options.member);
    ack.run_id(options.run_id);
    ack.components_run(static_cast<std::uint32_t>(components_run));
    ack.failed(!error.empty());
    ack.error(error.substr(0, 500));
    host_state.step = step;
    host_state.period_steps = 1;
    host_state.stamp_ns = sim_stamp_ns(step);
    ack_output->publish(ack);
  }

  void publish_tick(std::uint64_t step, bool final_tick) {
    idl::SimTick tick;
    tick.run_id(options.run_id);
    tick.step_s(run.scenario->step_s);
    tick.final_tick(final_tick);
    coordinator_state.step = step;
    coordinator_state.stamp_ns = sim_stamp_ns(step);
    if (final_tick) {
      tick_output->publish_final(tick);
    } else {
      tick_output->publish(tick);
    }
  }

  RunStats run_lockstep() {
    const std::uint64_t last = run.scenario->last_step();
    const Clock::time_point start = Clock::now();
    RunStats stats;

    // Host state.
    const bool hosting = tick_input != nullptr;
    bool host_done = !hosting;
    bool tick_active = false;
    bool tick_is_final = false;
    std::uint64_t tick_step = 0;
    std::uint64_t components_run = 0;
    std::deque<idl::SimTick> tick_queue;
    Clock::time_point waiting_since = start;  // for the next tick, or for inputs during a tick
    bool first_tick = true;

    // Coordinator state.
    const bool coordinating = tick_output != nullptr;
    bool coordinator_done = !coordinating;
    // Steps [0, acked_steps) are acknowledged by every member; ticks [0, next_tick) are sent.
    // At most `lockstep_window` ticks are outstanding: 1 is the strict rule (the next tick
    // waits for all acknowledgements). A wider window lets the groups of a pipeline work on
    // consecutive steps at once; results are unchanged, because an input at step m only ever
    // reads samples with step <= m - delay, however early later samples arrive.
    const std::uint64_t window = std::max<std::uint64_t>(1, options.lockstep_window);
    std::uint64_t acked_steps = 0;
    std::uint64_t next_tick = 0;
    Clock::time_point ack_progress_at = start;

    while (!(host_done && coordinator_done)) {
      check_stop();
      if (options.poll) {
        options.poll();
      }
      const std::uint64_t seen = run.notifier->generation();
      bool progressed = false;

      if (hosting && !host_done) {
        if (!tick_active) {
          for (idl::SimTick& tick : tick_input->take_new(0)) {
            if (tick.run_id() == options.run_id) {
              tick_queue.push_back(std::move(tick));
            }
          }
          if (!tick_queue.empty()) {
            const idl::SimTick tick = tick_queue.front();
            tick_queue.pop_front();
            tick_active = true;
            tick_step = tick.header().step();
            current_step = tick_step;
            tick_is_final = tick.final_tick();
            components_run = 0;
            first_tick = false;
            for (auto& slot : slots) {
              slot->pending = tick_step % slot->state.period_steps == 0;
              slot->state.step = tick_step;
              slot->state.stamp_ns = sim_stamp_ns(tick_step);
            }
            waiting_since = Clock::now();
            progressed = true;
          } else {
            const double limit = first_tick ? options.start_timeout_s : options.tick_timeout_s;
            if (seconds_since(waiting_since) > limit) {
              throw RunError(options.member + ": no tick on sim/clock for " + fmt_s(limit) + " s " +
                             (first_tick ? "after start" : "after step " + std::to_string(tick_step)) +
                             ": is the coordinator (robodds run) alive and on the same domain?" + dds_report());
            }
          }
        }
        if (tick_active) {
          bool all_done = true;
          for (auto& slot : slots) {
            if (!slot->pending) {
              continue;
            }
            std::string missing;
            const InputBase* blocking = nullptr;
            for (const auto& input : slot->context->inputs()) {
              if (!input->ready(tick_step, &missing)) {
                blocking = input.get();
                break;
              }
            }
            if (blocking != nullptr) {
              all_done = false;
              if (seconds_since(waiting_since) > options.input_timeout_s) {
                throw RunError("lockstep: component '" + slot->spec->name + "' waited " + fmt_s(options.input_timeout_s) +
                               " s at step " + std::to_string(tick_step) + " for topic " + blocking->topic() + ", " +
                               missing + dds_report());
              }
              continue;
            }
            const double time_s = static_cast<double>(tick_step) * run.scenario->step_s;
            const double dt_s = slot->has_run ? static_cast<double>(tick_step - slot->last_run_step) * run.scenario->step_s : 0.0;
            run_component(*slot, tick_step, time_s, dt_s);
            slot->pending = false;
            ++components_run;
            progressed = true;
          }
          if (all_done) {
            if (tick_is_final) {
              run.figures = RunFigures{tick_step + 1, seconds_since(start)};
              finish_components(tick_step, static_cast<double>(tick_step) * run.scenario->step_s);
              host_done = true;
            }
            publish_ack(tick_step, components_run, "");
            tick_active = false;
            stats.steps = tick_step + 1;
            waiting_since = Clock::now();
            progressed = true;
          }
        }
      }

      if (coordinating && !coordinator_done) {
        for (std::uint64_t key : ack_input->instances()) {
          for (const idl::StepDone& ack : ack_input->take_new(key)) {
            if (ack.run_id() == options.run_id && ack.failed()) {
              throw RunError("group '" + ack.member().to_string() + "' failed at step " +
                             std::to_string(ack.header().step()) + ": " + ack.error().to_string());
            }
          }
        }
        std::string missing;
        bool coordinator_progressed = false;  // the timeout below is about acks, not host work
        while (acked_steps < next_tick && ack_input->ready(acked_steps, &missing)) {
          if (options.progress) {
            options.progress(acked_steps, last);
          }
          ++acked_steps;
          stats.steps = acked_steps;
          ack_progress_at = Clock::now();
          coordinator_progressed = true;
        }
        if (acked_steps > last) {
          coordinator_done = true;
        }
        while (next_tick <= last && next_tick < acked_steps + window) {
          publish_tick(next_tick, next_tick == last);
          if (next_tick == acked_steps) {
            ack_progress_at = Clock::now();  // the oldest outstanding tick starts its wait now
          }
          ++next_tick;
          coordinator_progressed = true;
        }
        progressed = progressed || coordinator_progressed;
        if (!coordinator_done && !coordinator_progressed) {
          const double limit = acked_steps == 0 ? options.start_timeout_s : options.tick_timeout_s;
          if (seconds_since(ack_progress_at) > limit) {
            throw RunError("lockstep: no acknowledgement of step " + std::to_string(acked_steps) + " within " +
                           fmt_s(limit) + " s from group " + missing + " on sim/step_done" + dds_report());
          }
        }
      }

      if (!progressed) {
        run.notifier->wait(seen, std::chrono::milliseconds(20));
      }
    }
    stats.wall_s = seconds_since(start);
    return stats;
  }

  RunStats run_realtime() {
    const std::uint64_t last = run.scenario->last_step();
    const double step_s = run.scenario->step_s;
    const std::int64_t epoch_ns = options.realtime_epoch_ns != 0 ? options.realtime_epoch_ns : wall_ns();
    const Clock::time_point start = Clock::now();
    std::vector<std::uint64_t> next_due(slots.size(), 0);
    std::uint64_t reported = 0;
    while (true) {
      check_stop();
      if (options.poll) {
        options.poll();
      }
      const std::int64_t now_ns = wall_ns();
      const double elapsed_s = static_cast<double>(now_ns - epoch_ns) * 1e-9;
      if (elapsed_s < 0.0) {
        std::this_thread::sleep_for(std::chrono::nanoseconds(-(now_ns - epoch_ns)));
        continue;
      }
      const auto current = static_cast<std::uint64_t>(elapsed_s / step_s);
      if (current > last) {
        break;
      }
      std::uint64_t soonest = last + 1;
      for (std::size_t i = 0; i < slots.size(); ++i) {
        Slot& slot = *slots[i];
        if (next_due[i] <= current) {
          slot.state.step = current;
          slot.state.stamp_ns = now_ns;
          const double dt_s = slot.has_run ? seconds_since(slot.last_run_wall) : 0.0;
          run_component(slot, current, elapsed_s, dt_s);
          slot.last_run_wall = Clock::now();
          next_due[i] = current - current % slot.state.period_steps + slot.state.period_steps;
        }
        soonest = std::min(soonest, next_due[i]);
      }
      if (options.progress && current >= reported + 100) {
        options.progress(current, last);
        reported = current;
      }
      const std::int64_t due_ns = epoch_ns + static_cast<std::int64_t>(static_cast<double>(soonest) * step_s * 1e9);
      const std::int64_t sleep_ns = due_ns - wall_ns();
      if (sleep_ns > 0) {
        std::this_thread::sleep_for(std::chrono::nanoseconds(std::min<std::int64_t>(sleep_ns, 50000000)));
      }
    }
    run.figures = RunFigures{last + 1, seconds_since(start)};
    finish_components(last, static_cast<double>(last) * step_s);
    return RunStats{last + 1, seconds_since(start)};
  }
};

Host::Host(const ComponentRegistry& registry, RunContext run, HostOptions options)
    : impl_(std::make_unique<Impl>(registry, std::move(run), std::move(options))) {}

Host::~Host() = default;

void Host::configure() { impl_->configure(); }

RunStats Host::run() {
  try {
    return impl_->run.mode == TimeMode::kLockstep ? impl_->run_lockstep() : impl_->run_realtime();
  } catch (const RunError& e) {
    // Tell the coordinator why this host stops, so it can report it at once.
    try {
      impl_->publish_ack(impl_->current_step, 0, e.what());
    } catch (...) {
    }
    throw;
  }
}

}  // namespace robodds
