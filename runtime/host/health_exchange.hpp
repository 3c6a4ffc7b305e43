#pragma once
// Host health across processes, DDS-native: every host of a run across processes publishes its
// HostHealth once on `run/health` (idl::HostReport keyed by member; the `mission` profile:
// reliable, transient local, keep last 1 per member) when it has run its last step, before its
// components finish; the host of a component that asked for the run's health (the evaluator,
// ComponentContext::record_run()) waits a bounded time for every other group's report
// and adds them to RunFigures::hosts, naming the groups it did not hear from.
//
// The lockstep end: the final tick runs on every host in parallel. A host publishes its report
// after its components ran the final step and before it acknowledges the tick, so no host
// waits for another's on_finish(): the evaluator's host only waits for reports, which every
// other host sends without waiting for anyone. In real time every host ends at the same wall
// time (epoch + duration), so the reports arrive within the discovery/transport latency.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/component/component.hpp"
#include "runtime/health/host_health.hpp"

namespace robodds {

/// How long the evaluator's host waits for the other hosts' reports at the end (s).
inline constexpr double kHealthWaitS = 5.0;

/// HostHealth <-> idl::HostReport (strings longer than the IDL bounds are cut).
idl::HostReport to_report(const HostHealth& health, std::uint64_t run_id);
HostHealth from_report(const idl::HostReport& report);

class HealthExchange {
 public:
  /// Advertises run/health; with `others` non-empty also subscribes to it (reports of `run_id`
  /// only). Call before the bus starts. `run` must outlive this object.
  HealthExchange(RunContext& run, std::string member, std::uint64_t run_id, std::vector<std::string> others);

  /// Publishes figures.hosts.front() (this host's), then, when collecting, waits up to
  /// `timeout_s` for the others' reports and appends them to figures.hosts in `others` order;
  /// the missing ones go to figures.hosts_not_heard and one warning names them.
  void exchange(RunFigures& figures, std::uint64_t step, double timeout_s = kHealthWaitS);

 private:
  RunContext& run_;
  std::string member_;
  std::uint64_t run_id_;
  std::vector<std::string> others_;
  StepState state_;
  std::unique_ptr<Output<idl::HostReport>> output_;
  std::unique_ptr<Input<idl::HostReport>> input_;
  std::shared_ptr<ReaderHandle> reader_;
};

}  // namespace robodds
