#include "runtime/host/host.hpp"

#include <algorithm>
#include <chrono>
#include <set>
#include <thread>

#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/realtime_priority.hpp"
#include "runtime/host/digest_check.hpp"
#include "runtime/host/health_exchange.hpp"
#include "runtime/host/host_slot.hpp"
#include "runtime/host/loop_alive.hpp"
#include "runtime/base/log.hpp"
#include "runtime/lockstep/lockstep_coordinator.hpp"
#include "runtime/lockstep/lockstep_host.hpp"
#include "runtime/bus/memory_bus.hpp"
#include "runtime/health/overrun_counter.hpp"
#include "runtime/health/peer_watch.hpp"
#include "runtime/host/peer_loss_watch.hpp"
#include "runtime/host/producer_check.hpp"

namespace robodds {
namespace {

using host_detail::Clock;
using host_detail::ComponentSlot;
using host_detail::seconds_since;

}  // namespace

struct Host::Impl {
  const ComponentRegistry& registry;
  RunContext run;
  HostOptions options;
  std::vector<std::unique_ptr<ComponentSlot>> slots;
  std::unique_ptr<MemoryBus> lockstep_bus;                    // ticks and acks, with options.lockstep_in_memory
  std::unique_ptr<LockstepHost> lockstep_host;                // lockstep, when this host runs components
  std::unique_ptr<LockstepCoordinator> lockstep_coordinator;  // lockstep, when it publishes the ticks
  std::unique_ptr<HealthExchange> health;                     // across processes: run/health
  std::unique_ptr<PeerLossWatch> peer_losses;                 // across processes: hosts that went away
  std::unique_ptr<LoopAlive> loop_alive;                      // real time across processes: run/alive

  Impl(const ComponentRegistry& r, RunContext rc, HostOptions o) : registry(r), run(std::move(rc)), options(std::move(o)) {}

  /// The groups whose run/health reports this host collects: every other group of the scenario
  /// when one of its components asked for the run's health, else none.
  std::vector<std::string> health_sources() const {
    const bool wanted =
        std::any_of(slots.begin(), slots.end(), [](const auto& slot) { return slot->context->records_run(); });
    std::vector<std::string> others;
    for (const GroupSpec& group : run.scenario->groups) {
      if (wanted && group.name != options.member) {
        others.push_back(group.name);
      }
    }
    return others;
  }

  /// Real time across processes: the scenario's other groups this host exchanges a topic with
  /// (one of them reads what it writes or writes what it reads, run/health included), which it
  /// must discover within the start timeout (PeerWatch); not run/alive, which every real-time host
  /// shares with every other (LoopAlive judges a group only once it heard it). Only those: a
  /// Discovery Server tells a client about the participants it shares a topic with, no others.
  /// None co-located, alone (a component executable) or on a bus that discovers nothing.
  PeerWatch peer_watch() const {
    std::vector<std::string> others;
    if (run.single_process || !run.bus->discovered_participants() || run.scenario->groups.size() < 2) {
      return PeerWatch(others, options.start_timeout_s);
    }
    const auto topics = scenario_component_topics(registry, *run.scenario, run.mode);
    const auto topics_of = [&topics](const std::vector<std::string>& components) {
      ComponentTopics all;
      all.publishes.insert("run/health");  // every host reports its health (HealthExchange)
      for (const std::string& name : components) {
        const ComponentTopics& one = topics.at(name);
        all.publishes.insert(one.publishes.begin(), one.publishes.end());
        all.subscribes.insert(one.subscribes.begin(), one.subscribes.end());
        if (one.wants_run_health) {
          all.subscribes.insert("run/health");
        }
      }
      return all;
    };
    const auto shares = [](const std::set<std::string>& a, const std::set<std::string>& b) {
      return std::any_of(a.begin(), a.end(), [&b](const std::string& topic) { return b.count(topic) != 0; });
    };
    const ComponentTopics mine = topics_of(options.components);
    for (const GroupSpec& group : run.scenario->groups) {
      if (group.name == options.member) {
        continue;
      }
      const ComponentTopics theirs = topics_of(group.components);
      if (shares(mine.subscribes, theirs.publishes) || shares(mine.publishes, theirs.subscribes)) {
        others.push_back(group.name);
      }
    }
    return PeerWatch(std::move(others), options.start_timeout_s);
  }

  /// Checks the peers at most every 0.5 s, and at the run's end (`run_ended`: a run shorter than
  /// the start timeout is judged then); logs a degraded run once.
  void watch_peers(PeerWatch& watch, double elapsed_s, double& next_check_s, bool run_ended = false) const {
    if (elapsed_s < next_check_s && !run_ended) {
      return;
    }
    next_check_s = elapsed_s + 0.5;
    // run/alive's beats tell a group that was discovered from one that can also be heard.
    const std::vector<std::string> heard = loop_alive ? loop_alive->heard_groups() : std::vector<std::string>{};
    if (watch.check(elapsed_s, run.bus->discovered_participants().value_or(std::vector<std::string>{}), run_ended,
                    loop_alive ? &heard : nullptr)) {
      log::warn(options.member, "degraded: " + watch.degraded() + (run_ended ? "" : "; the run goes on without them"));
    }
  }

  /// Real time: the step a graceful stop ends the run after (HostOptions::graceful_stop: the step
  /// the loop is at, `at_step`; stop_at_step: the runner's), or `end` when none was asked for.
  std::uint64_t graceful_end(std::uint64_t end, std::uint64_t at_step) const {
    if (options.stop_at_step != nullptr) {
      end = std::min(end, std::max(options.stop_at_step->load(), at_step));
    }
    if (options.graceful_stop != nullptr && options.graceful_stop->load()) {
      end = std::min(end, at_step);
    }
    return end;
  }

  void check_stop() const {
    if (options.stop != nullptr && options.stop->load()) {
      throw RunError(options.member + ": interrupted by a signal");
    }
  }

  void configure() {
    for (const std::string& name : options.components) {
      const ComponentSpec& spec = run.scenario->component(name);
      const ComponentType& type = registry.get(spec.type);
      auto slot = std::make_unique<ComponentSlot>();
      slot->spec = &spec;
      slot->state.mode = run.mode;
      slot->component = type.create();
      slot->context = std::make_unique<ComponentContext>(run, spec, scenario_component_params(type, spec), &slot->state);
      slot->component->configure(*slot->context);
      slot->context->params().check_all_read();
      slots.push_back(std::move(slot));
    }
    if (!run.single_process && !slots.empty()) {
      health = std::make_unique<HealthExchange>(run, options.member, options.run_id, health_sources());
    }
    // Null source: a bus that discovers no peers (in memory, co-located).
    peer_losses = std::make_unique<PeerLossWatch>(run.single_process ? nullptr : dynamic_cast<const PeerLossSource*>(run.bus),
                                                  *run.scenario, options.member, options.members);
    if (run.mode != TimeMode::kLockstep) {
      if (!run.single_process && !slots.empty()) {
        std::vector<std::string> others;
        for (const GroupSpec& group : run.scenario->groups) {
          if (group.name != options.member) {
            others.push_back(group.name);
          }
        }
        loop_alive = std::make_unique<LoopAlive>(run, options.member, options.run_id, std::move(others));
      }
      return;
    }
    // Both halves of the protocol on this host's one thread: a round trip through DDS per step
    // (write, intra-process delivery, take, on each side) was ~12 % of a co-located run.
    if (options.lockstep_in_memory && options.coordinator && !options.components.empty()) {
      lockstep_bus = std::make_unique<MemoryBus>();
    }
    Bus& protocol_bus = lockstep_bus ? static_cast<Bus&>(*lockstep_bus) : *run.bus;
    if (!options.components.empty()) {
      lockstep_host = std::make_unique<LockstepHost>(run, options, slots, protocol_bus, health.get());
    }
    if (options.coordinator) {
      lockstep_coordinator = std::make_unique<LockstepCoordinator>(run, options, protocol_bus);
    }
  }

  /// One loop drives both sides of the protocol on this thread: the host part runs the
  /// components of each tick, the coordinator part publishes ticks and collects acknowledgements.
  /// Every component's on_start(), once, before the run's first step.
  void start_components() {
    for (auto& slot : slots) {
      slot->start();
    }
  }

  RunStats run_lockstep() {
    start_components();
    const Clock::time_point start = Clock::now();
    if (lockstep_host) {
      lockstep_host->begin(start);
    }
    if (lockstep_coordinator) {
      lockstep_coordinator->begin(start);
    }
    const auto host_done = [this] { return !lockstep_host || lockstep_host->done(); };
    const auto coordinator_done = [this] { return !lockstep_coordinator || lockstep_coordinator->done(); };
    RunStats stats;
    while (!(host_done() && coordinator_done())) {
      check_stop();
      if (options.poll) {
        options.poll();
      }
      peer_losses->check_lockstep(stats.steps, !host_done(), !coordinator_done());
      const std::uint64_t seen = run.notifier->generation();
      bool progressed = false;
      if (!host_done()) {
        progressed = lockstep_host->step();
        stats.steps = lockstep_host->steps_done();
      }
      if (!coordinator_done()) {
        progressed = lockstep_coordinator->poll() || progressed;
        stats.steps = lockstep_coordinator->acknowledged_steps();
      }
      if (!progressed) {
        run.notifier->wait(seen, std::chrono::milliseconds(20));
      }
    }
    if (lockstep_coordinator) {
      stats.steps = lockstep_coordinator->acknowledged_steps();
    }
    stats.wall_s = seconds_since(start);
    return stats;
  }
  RunStats run_realtime() {
    const std::uint64_t last = run.scenario->last_step();
    const double step_s = run.scenario->step_s;
    // Before the clock: what a component does once at the start must not make step 0 late.
    start_components();
    raise_loop_thread();  // --rt-priority: this loop above the process's Fast DDS threads
    const std::int64_t epoch_ns = options.realtime_epoch_ns != 0 ? options.realtime_epoch_ns : wall_clock_now_ns();
    const Clock::time_point start = Clock::now();
    std::vector<std::uint64_t> next_due(slots.size(), 0);
    std::vector<std::uint64_t> periods;
    for (const auto& slot : slots) {
      periods.push_back(slot->state.period_steps);
    }
    OverrunCounter overruns(step_s, options.max_missed_steps.value_or(default_max_missed_steps(last + 1)));
    std::uint64_t reported = 0;
    std::uint64_t last_run = 0;  // the last step the components ran at
    PeerWatch peers = peer_watch();
    double next_peer_check_s = 0.0;
    DigestCheck digests(options.digest, options.run_id);
    std::set<std::string> told_other_files;  // hosts of this run named as having loaded other files
    std::string other_files;                  // degraded: what was said of them, "; "-joined
    bool stopped = false;
    std::uint64_t end = last;  // the run's last step: earlier after a graceful stop (graceful_end)
    while (true) {
      if (options.stop_ends_run && options.stop != nullptr && options.stop->load()) {
        log::info(options.member, "stopped by a signal after step " + std::to_string(last_run) + ": finishing");
        stopped = true;
        break;
      }
      check_stop();
      if (options.poll) {
        options.poll();
      }
      const std::int64_t now_ns = wall_clock_now_ns();
      const double elapsed_s = static_cast<double>(now_ns - epoch_ns) * 1e-9;
      if (elapsed_s < 0.0) {
        std::this_thread::sleep_for(std::chrono::nanoseconds(-(now_ns - epoch_ns)));
        continue;
      }
      const auto current = static_cast<std::uint64_t>(elapsed_s / step_s);
      const std::uint64_t asked_end = graceful_end(end, last_run);
      if (asked_end < end) {
        end = asked_end;
        log::info(options.member, "stopping on a signal: the run ends cleanly after step " + std::to_string(end) + " (t = " +
                                      shortest_text(static_cast<double>(end) * step_s) + " s of " +
                                      shortest_text(static_cast<double>(last) * step_s) + " s)");
      }
      if (current > end) {
        last_run = end;
        break;
      }
      last_run = current;
      watch_peers(peers, seconds_since(start), next_peer_check_s);
      const double remaining_s = static_cast<double>(end + 1) * step_s - elapsed_s;  // s to the run's end
      peer_losses->check_realtime(peers, elapsed_s, remaining_s);
      if (loop_alive) {
        loop_alive->beat(elapsed_s, current);
        peer_losses->check_silent_loops(peers, *loop_alive, elapsed_s, remaining_s);
      }
      watch_digests(digests, seconds_since(start), told_other_files, other_files);
      const std::uint64_t first_due = next_due.empty() ? current : *std::min_element(next_due.begin(), next_due.end());
      if (first_due <= current) {
        count_overrun(overruns, first_due, current, due_steps_between(periods, first_due, current), elapsed_s);
      }
      std::uint64_t soonest = end + 1;
      for (std::size_t i = 0; i < slots.size(); ++i) {
        ComponentSlot& slot = *slots[i];
        if (next_due[i] <= current) {
          slot.state.step = current;
          slot.state.stamp_ns = now_ns;
          const double dt_s = slot.has_run ? seconds_since(slot.last_run_wall) : 0.0;
          slot.run(current, elapsed_s, dt_s);
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
      const std::int64_t sleep_ns = due_ns - wall_clock_now_ns();
      if (sleep_ns > 0) {
        std::this_thread::sleep_for(std::chrono::nanoseconds(std::min<std::int64_t>(sleep_ns, 50000000)));
      }
    }
    if (!stopped && !next_due.empty()) {
      // Due steps after the last one the loop ran that it never got to before the end.
      const std::uint64_t first_due = *std::min_element(next_due.begin(), next_due.end());
      overruns.missed_at_end(due_steps_between(periods, std::min(first_due, end + 1), end + 1));
      check_overrun_limit(overruns);
    }
    if (overruns.figures().missed_steps > 0 || overruns.figures().late_steps > 0) {
      log::warn(options.member, "real-time overruns over the run: " + overruns.totals_text());
    }
    if (!peers.checked()) {  // a run shorter than the start timeout: judged at its end
      watch_peers(peers, seconds_since(start), next_peer_check_s, true);
    }
    const std::string degraded = peers.degraded() + (peers.degraded().empty() || other_files.empty() ? "" : "; ") + other_files;
    if (end < last) {
      run.figures.stopped_by = "signal";
      run.figures.stopped_at_s = static_cast<double>(end) * step_s;
      run.figures.stopped_at_wall_ns = wall_clock_now_ns();
    }
    host_detail::finish_run(run, options.member, overruns.figures(), slots, health.get(), last_run, seconds_since(start), degraded);
    return RunStats{last_run + 1, seconds_since(start), degraded, run.figures.stopped_by};
  }

  /// Real time: hosts of this run that loaded other files (DigestCheck). Within the start timeout, a
  /// host outnumbered by hosts that agree on another digest refuses to start (RunConfigError, exit
  /// 2): it is the odd one. Otherwise the run goes on degraded, naming each such host once; their
  /// writers are no producer of the scenario here (refused and counted as unknown_producer).
  void watch_digests(DigestCheck& digests, double elapsed_s, std::set<std::string>& told, std::string& other_files) const {
    const DigestVerdict& v = digests.verdict(*run.bus);
    if (v.difference.empty()) {
      return;
    }
    if (v.outnumbered() && elapsed_s < options.start_timeout_s) {
      throw RunConfigError(DigestCheck::message(options.member + ": refuses to start", v.difference) + " (" +
                           std::to_string(v.largest_other) + " host(s) agree on other files, " + std::to_string(v.agreeing) +
                           " on this host's)");
    }
    for (const std::string& host : v.differing_hosts) {
      if (!told.insert(host).second) {
        continue;
      }
      const std::string line = "host " + host + " loaded other files than this host";
      other_files += (other_files.empty() ? "" : "; ") + line;
      log::warn(options.member, "degraded: " + (host == v.differing_hosts.front() ? v.difference : line) +
                                    "; its samples are refused (unknown_producer), the run goes on without it");
    }
  }

  /// Books one iteration of the real-time loop; warns (rate-limited) and fails past the limit.
  void count_overrun(OverrunCounter& overruns, std::uint64_t first_due, std::uint64_t current, std::uint64_t missed,
                     double elapsed_s) {
    if (overruns.ran(first_due, current, missed, elapsed_s)) {
      log::warn(options.member, "real-time overrun at step " + std::to_string(current) + ": skipped " + std::to_string(missed) +
                                    " due step(s) the loop came to too late; " + overruns.totals_text() +
                                    " (warned at most every " + host_detail::fmt_s(kOverrunWarnIntervalS) + " s)");
    }
    check_overrun_limit(overruns);
  }

  void check_overrun_limit(const OverrunCounter& overruns) const {
    if (overruns.exceeded()) {
      throw RunError(options.member + ": real-time overrun: " + std::to_string(overruns.figures().missed_steps) +
                     " due steps skipped, more than --max-missed-steps " + std::to_string(overruns.max_missed()) +
                     (options.max_missed_steps ? "" : " (default: " + shortest_text(kDefaultMaxMissedFraction * 100.0) + " % of the run's steps)") + "; " + overruns.totals_text());
    }
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
      if (impl_->lockstep_host && !(impl_->peer_losses && impl_->peer_losses->coordinator_lost())) {
        impl_->lockstep_host->publish_failure(e.what(), dynamic_cast<const RunConfigError*>(&e) != nullptr);
      }
    } catch (...) {
    }
    for (auto& slot : impl_->slots) {  // e.g. the evaluator keeps what it recorded
      try {
        slot->component->on_abort(e.what());
      } catch (const std::exception& abort_error) {
        log::warn(impl_->options.member, slot->spec->name + ": after the failure: " + abort_error.what());
      }
    }
    throw;
  }
}

}  // namespace robodds
