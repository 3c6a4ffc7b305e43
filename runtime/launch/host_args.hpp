#pragma once
// The command line of `robodds host`, owned by one struct: the process runner and the compose
// generator render it to an argv, `robodds host` parses it back. Both sides use this file, so
// an option cannot be spelled one way by the writer and another by the reader.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/dds/dds_bus.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace robodds {

/// DDS options of every subcommand (flags override the environment; see resolve_dds()).
struct DdsArgs {
  int domain = -1;                      // -1: $ROBODDS_DOMAIN_ID or 0
  std::vector<std::string> qos_files;   // empty: deploy/qos/robodds_qos.xml (+ $ROBODDS_QOS_FILE)
  std::string participant_profile;      // empty: $ROBODDS_PARTICIPANT_PROFILE or robodds.participant
  std::string security_dir;             // empty: $ROBODDS_SECURITY_DIR or no DDS Security (docs/security.md)
  std::string discovery_servers;        // "ADDR[:PORT][,ADDR[:PORT]...]": Discovery Server client; empty: the profile's discovery
  bool operator==(const DdsArgs& other) const;
};

/// Lockstep timeouts and the coordinator's window (`robodds run` and `robodds host`).
struct LockstepArgs {
  double input_timeout_s = 10.0;    // s, max wait for a component's inputs at one step
  double start_timeout_s = 30.0;    // s, max wait for peers to start
  std::size_t lockstep_window = 1;  // coordinator: ticks outstanding at once (1 = strict)
  bool operator==(const LockstepArgs& other) const;
};

/// Every option of `robodds host`. Defaults are the parser's defaults: to_argv() writes only
/// the fields that differ from them, so a rendered command line stays short and stable.
struct HostArgs {
  std::string scenario;                 // scenario YAML file
  std::string group;                    // run the components of this group ...
  std::vector<std::string> components;  // ... or these component instances
  std::string params;                   // YAML map component.parameter -> value (over the scenario's)
  std::vector<std::string> sets;        // "component.parameter=value", over the scenario's and --params
  std::vector<std::string> added_components;  // "GROUP:NAME:TYPE" added to the scenario before --set (added_components.hpp)
  std::string member;                   // name in acknowledgements (empty: the group)
  bool coordinate = false;              // also publish ticks (a standalone lockstep host)
  std::vector<std::string> members;     // with coordinate: groups whose acknowledgements to wait for
  std::uint64_t run_id = 1;             // ticks of other runs are ignored
  std::string out;                      // output directory for the evaluator
  std::string deploy;                   // deployment label of summary.json's "run" section (empty: none)
  bool realtime = false;                // wall-clock timers instead of lockstep
  std::int64_t epoch_ns = 0;            // real time: wall clock (ns) of step 0 (0 = now)
  std::optional<double> duration_s;     // override the scenario duration (s)
  std::optional<std::uint64_t> seed;    // override the scenario seed
  std::string log_level;                // empty: the global --log (or $ROBODDS_LOG)
  std::optional<std::uint64_t> max_missed_steps;  // real time: fail past this many skipped steps (default 5 %)
  std::optional<int> rt_priority;       // SCHED_FIFO priority 1..99 + locked memory (runtime/base/realtime_priority.hpp)
  // One component without a scenario file (a component executable robodds-<type>, or
  // `robodds host --type`): the host makes a one-component scenario (standalone_scenario()).
  std::string type;                     // registered component type (instead of --scenario)
  std::string name;                     // its instance name (empty: the type): seeds, logs, acks
  std::vector<std::string> robots;      // robots it serves: "ID" or "ID:X,Y,THETA" (m, m, rad)
  std::optional<double> step_s;         // s, simulation step (default kStandaloneStepS)
  DdsArgs dds;
  LockstepArgs lockstep;
  bool operator==(const HostArgs& other) const;
};

/// Option name -> text written instead of the field's value, even when the value is the
/// default. The compose generator uses it for values compose substitutes at start, e.g.
/// {"--run-id", "${ROBODDS_RUN_ID:-1}"}.
using ArgPlaceholders = std::map<std::string, std::string>;

/// Step of a standalone component when --step is not given (s): the shipped scenarios' step.
inline constexpr double kStandaloneStepS = 0.01;
/// Duration of a standalone component when --duration is not given (s): "until stopped" (a
/// lockstep host ends with the coordinator's final tick; a real-time one with SIGINT/SIGTERM).
inline constexpr double kUntilStoppedS = 1e9;

/// The arguments after `robodds host` (no executable, no subcommand), in a fixed order.
std::vector<std::string> to_argv(const HostArgs& args, const ArgPlaceholders& placeholders = {});

/// The options add_host_options() registered, for a caller that needs more (e.g. required()).
struct HostArgOptions {
  CLI::Option* scenario = nullptr;
  CLI::Option* group = nullptr;
  CLI::Option* components = nullptr;
};

/// Registers every HostArgs option on `app`, writing into `args` (which must outlive parsing).
/// Nothing is required here: run_host() checks the combination (--scenario with --group or
/// --components, or --type; a coordinator alone).
HostArgOptions add_host_options(CLI::App* app, HostArgs& args);
/// Registers what a component executable (robodds-<type>) accepts: the options of one
/// component without a scenario file (--robot, --name, --step, --params of its own keys) and
/// the run options it shares with `robodds host` (--realtime, --out, --run-id, --member,
/// --duration, --seed, --log, DDS and lockstep options). `args.type` is the caller's.
void add_component_options(CLI::App* app, HostArgs& args);
/// --duration: a positive, finite number of seconds (NaN, inf, 0 and negatives are CLI errors).
void add_duration_option(CLI::App* app, std::optional<double>& duration_s, const std::string& help);
/// --step: a positive, finite number of seconds (NaN, inf, 0 and negatives are CLI errors).
void add_step_option(CLI::App* app, std::optional<double>& step_s, const std::string& help);
/// --seed: a whole number 0..2^64-1 in decimal digits ("-1" and overflow are CLI errors).
void add_seed_option(CLI::App* app, std::optional<std::uint64_t>& seed, const std::string& help);
/// --max-missed-steps: real time, the run fails when a host skips more due steps than this
/// (default: kDefaultMaxMissedFraction of the run's steps, runtime/health/overrun_counter.hpp).
void add_max_missed_steps_option(CLI::App* app, std::optional<std::uint64_t>& max_missed_steps);
/// --rt-priority N: SCHED_FIFO priority 1..99 and locked memory for the process (the caller
/// applies it with apply_rt_priority() before it creates a DDS participant).
void add_rt_priority_option(CLI::App* app, std::optional<int>& rt_priority);
/// The servers of --discovery-server (DdsArgs::discovery_servers), in order (server id = position):
/// ConfigError naming the option and the entry for an empty address, a bad port or over 255.
std::vector<DiscoveryServer> parse_discovery_servers(const std::string& text);
/// The --discovery-server text of `servers` ("ADDR:PORT,..."), which parse_discovery_servers() reads back.
std::string discovery_servers_text(const std::vector<DiscoveryServer>& servers);

void add_dds_options(CLI::App* app, DdsArgs& args);
void add_lockstep_options(CLI::App* app, LockstepArgs& args);

}  // namespace robodds
