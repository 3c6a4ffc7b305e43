#pragma once
// A lockstep coordinator without a scenario file (`robodds coordinate`, or `robodds host
// --coordinate` without --scenario): it steps component executables (robodds-<type>) that run
// without one either. The lockstep protocol needs only the step (every tick carries it and every
// host checks it against its own --step), the last step (the final tick), the run id and the
// members to wait for; this turns those options into the scenario of a host that runs no
// component and only coordinates.

#include <string>
#include <vector>

#include "runtime/config/scenario.hpp"
#include "runtime/launch/host_args.hpp"

namespace robodds {

/// The scenario of a coordinator alone: no robots, components or groups; step `args.step_s`
/// (default kStandaloneStepS, the component executables' default), duration `args.duration_s`
/// (required: the run ends there), seed `args.seed` (default 1; the ticks do not carry it: each
/// executable takes its own --seed). ConfigError naming the option and the reason for a missing
/// --duration, a step count over kMaxLastStep, bad --members (check_members()), or options that
/// belong to the component executables (--robot, --name, --params, --set, --group, --components).
Scenario coordinator_scenario(const HostArgs& args);

/// The names of a --members text split at commas, empty ones kept ("a,,b" -> a, "", b), so that
/// check_members() can name them (CLI11's delimiter drops them silently).
std::vector<std::string> split_members(const std::string& text);

/// --members of a coordinator: at least one, none empty, none twice, none longer than the
/// acknowledgement's member key (kMaxMemberLength). ConfigError naming --members, the list and
/// the member. Names are free (no did-you-mean: nothing to compare them with).
void check_members(const std::vector<std::string>& members);

/// Characters of a member name: the key of an acknowledgement is a string<64> (idl/robodds.idl).
inline constexpr std::size_t kMaxMemberLength = 64;

}  // namespace robodds
