#pragma once
// Hosts of one run must have loaded the same scenario, run options and QoS files (issue 24,
// finding 7; docs/deployment.md, "Multi-host by hand"). Each host announces the digest of what
// it loaded (HostOptions::digest, runtime/bus/run_digest.hpp) and compares it with the digests
// the other hosts of its run announce, again whenever discovery changes.

#include <cstdint>
#include <string>
#include <utility>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/run_digest.hpp"

namespace robodds {

class DigestCheck {
 public:
  /// `own` empty: nothing to compare (a component without a scenario file); never differs.
  DigestCheck(RunDigest own, std::uint64_t run_id) : own_(std::move(own)), run_id_(run_id) {}

  /// The verdict on the hosts `bus` has discovered; asks the bus again only when its discovery
  /// generation moved. Cheap to call at every step.
  const DigestVerdict& verdict(const Bus& bus);

  /// Lockstep: RunConfigError "<member>: host 'x' loaded a different ... : every host of a run must
  /// load the same files" when a discovered host of the run differs.
  void fail_on_difference(const Bus& bus, const std::string& member);

  /// The error text of a difference (member, the difference, what to do); it ends with
  /// kAdvice, by which a coordinator knows a member's failure report for one.
  static std::string message(const std::string& member, const std::string& difference);
  static constexpr const char* kAdvice =
      "every host of one run must load the same scenario, options and QoS files (docs/deployment.md, \"Multi-host by hand\")";

 private:
  RunDigest own_;
  std::uint64_t run_id_;
  bool asked_ = false;
  std::uint64_t generation_ = 0;
  DigestVerdict verdict_;
};

}  // namespace robodds
