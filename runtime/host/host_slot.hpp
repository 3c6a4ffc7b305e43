#pragma once
// Pieces of the host shared by host.cpp, lockstep_host.cpp and lockstep_coordinator.cpp: one
// hosted component with its step bookkeeping, and the small time/text helpers of their error
// messages. Not a public API: components and tools use runtime/host/host.hpp.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "runtime/component/component.hpp"
#include "runtime/host/health_exchange.hpp"

namespace robodds::host_detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Seconds with one decimal, as every timeout message prints them.
inline std::string fmt_s(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f", seconds);
  return buf;
}

/// "; DDS: ..." naming unmatched topics and incompatible QoS, so a wait that timed out because
/// peers never matched says so (empty when everything matched).
inline std::string dds_report(Bus& bus) {
  const std::string report = bus.match_report();
  return report.empty() ? "" : "; " + report;
}

/// Sim time of `step` in ns: the stamp of every sample of that step.
inline std::int64_t sim_stamp_ns(std::uint64_t step, double step_s) {
  return static_cast<std::int64_t>(std::llround(static_cast<double>(step) * step_s * 1e9));
}

/// One component of this host and where it is in the run.
struct ComponentSlot {
  const ComponentSpec* spec = nullptr;
  std::unique_ptr<Component> component;
  std::unique_ptr<ComponentContext> context;
  StepState state;
  bool pending = false;         // lockstep: due at the current tick and not yet run
  bool has_run = false;
  std::uint64_t last_run_step = 0;
  Clock::time_point last_run_wall;

  /// on_start(); a component's exception becomes a RunError naming it.
  void start() {
    try {
      component->on_start();
    } catch (const std::exception& e) {
      throw RunError("component '" + spec->name + "' failed at the start of the run: " + e.what());
    }
  }

  /// on_step(); a component's exception becomes a RunError naming it and the step.
  void run(std::uint64_t step, double time_s, double dt_s) {
    try {
      component->on_step(StepInfo{step, time_s, dt_s, state.stamp_ns});
    } catch (const std::exception& e) {
      throw RunError("component '" + spec->name + "' failed at step " + std::to_string(step) + ": " + e.what());
    }
    has_run = true;
    last_run_step = step;
  }

  /// on_finish(); a component's exception becomes a RunError naming it.
  void finish(std::uint64_t step, double time_s) {
    try {
      component->on_finish(StepInfo{step, time_s, 0.0, state.stamp_ns});
    } catch (const std::exception& e) {
      throw RunError("component '" + spec->name + "' failed while finishing: " + e.what());
    }
  }
};

/// What this host reports about its run (RunFigures::hosts): `figures`, its inputs' counts, its
/// components' compute times and what `bus` dropped undecoded.
inline HostHealth host_health(const std::string& member, const OverrunFigures& figures,
                              const std::vector<std::unique_ptr<ComponentSlot>>& slots, const Bus& bus) {
  HostHealth health;
  health.member = member;
  health.figures = figures;
  health.undecodable = bus.undecodable_samples();
  for (const auto& slot : slots) {
    health.components.push_back(component_health(slot->spec->name, slot->context->inputs()));
    add_stage_timing(health.timing, slot->spec->name, slot->context->compute_times());
  }
  return health;
}

/// The end of a run on this host, after its last step `last_step` (lockstep or real time): the
/// run's figures and this host's health into run.figures, across processes the other hosts'
/// health over run/health (`health`, may be null), then every component's on_finish().
/// `degraded`: why this host ran degraded (real time, PeerWatch), or empty.
inline void finish_run(RunContext& run, const std::string& member, const OverrunFigures& overruns,
                       std::vector<std::unique_ptr<ComponentSlot>>& slots, HealthExchange* health,
                       std::uint64_t last_step, double wall_time_s, const std::string& degraded = "") {
  run.figures.ticks = last_step + 1;
  run.figures.wall_time_s = wall_time_s;
  run.figures.hosts = {host_health(member, overruns, slots, *run.bus)};
  run.figures.hosts.front().degraded = degraded;
  if (health != nullptr) {
    health->exchange(run.figures, last_step);
  }
  for (auto& slot : slots) {
    slot->finish(last_step, static_cast<double>(last_step) * run.scenario->step_s);
  }
}

/// A bus callback that hands `input` the samples of run `run_id` only: ticks, acknowledgements
/// and health reports of another run sharing the DDS domain are ignored.
template <class Msg>
SampleCallback samples_of_run(Input<Msg>* input, std::uint64_t run_id) {
  return [input, run_id](const void* sample, const SampleMeta& meta) {
    const auto& message = *static_cast<const Msg*>(sample);
    if (message.run_id() == run_id) {
      input->on_sample(message, meta);
    }
  };
}

}  // namespace robodds::host_detail
