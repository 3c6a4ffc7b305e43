#include "runtime/component/param_keys.hpp"
#include "runtime/launch/launch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <set>
#include <system_error>
#include <thread>
#include <unistd.h>

#include "common/number_parse.hpp"
#include "common/number_text.hpp"
#include "runtime/bus/colocated_bus.hpp"
#include "runtime/launch/added_components.hpp"
#include "runtime/launch/coordinator_scenario.hpp"
#include "runtime/dds/dds_sample_codec.hpp"
#include "runtime/dds/security_files.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/failed_summary.hpp"
#include "runtime/launch/host_digest.hpp"
#include "runtime/base/log.hpp"
#include "runtime/base/realtime_priority.hpp"
#include "runtime/host/producer_check.hpp"
#include "runtime/bus/qos_profiles.hpp"
#include "runtime/launch/process_group.hpp"
#include "runtime/launch/transport_buffers.hpp"
#include "runtime/config/share_dir.hpp"
#include "runtime/launch/standalone_scenario.hpp"
#include "runtime/topics/topic_catalog.hpp"

#ifndef ROBODDS_SOURCE_DIR
#define ROBODDS_SOURCE_DIR "."
#endif

namespace robodds {
namespace {

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : fallback;
}

/// Whether this host announces and compares the digest of what it loaded (docs/deployment.md,
/// "Multi-host by hand"): not with ROBODDS_NO_DIGEST_CHECK=1, for hosts that knowingly load
/// different files (e.g. a test of what a QoS mismatch does once it gets through).
bool digest_check_wanted() { return env_or("ROBODDS_NO_DIGEST_CHECK", "") != "1"; }

/// The robodds executable, which the child hosts run.
std::string self_exe() {
  const std::string path = this_executable();
  if (path.empty()) {
    throw RunError("cannot find the robodds executable (/proc/self/exe)");
  }
  return path;
}

std::vector<std::string> all_members(const Scenario& scenario) {
  std::vector<std::string> members;
  for (const GroupSpec& g : scenario.groups) {
    members.push_back(g.name);
  }
  return members;
}

std::vector<std::string> all_components(const Scenario& scenario) {
  std::vector<std::string> names;
  for (const ComponentSpec& c : scenario.components) {
    names.push_back(c.name);
  }
  return names;
}

std::uint64_t make_run_id() {
  return (static_cast<std::uint64_t>(std::time(nullptr)) << 20) ^ static_cast<std::uint64_t>(getpid());
}

void apply(const LockstepArgs& lockstep, HostOptions& options) {
  options.input_timeout_s = lockstep.input_timeout_s;
  options.start_timeout_s = lockstep.start_timeout_s;
  options.lockstep_window = lockstep.lockstep_window;
}

TimeMode time_mode(bool realtime) { return realtime ? TimeMode::kRealtime : TimeMode::kLockstep; }

/// The DDS options of a participant with DDS Security identity `identity` (unused when unsecured).
DdsOptions with_identity(DdsOptions dds, const std::string& identity) {
  dds.security_identity = identity;
  return dds;
}

RunStats run_colocated(const ComponentRegistry& registry, const Scenario& scenario, const LaunchOptions& launch,
                       const ScenarioProducers& producers) {
  HostOptions options;
  options.member = "colocated";
  options.components = all_components(scenario);
  options.coordinator = true;
  options.members = {"colocated"};
  options.single_process = true;
  options.lockstep_in_memory = true;  // ticks and acks stay in the process (HostOptions)
  options.max_missed_steps = launch.max_missed_steps;
  apply(launch.lockstep, options);
  options.progress = launch.progress;
  options.stop = launch.stop;
  options.graceful_stop = launch.realtime ? launch.graceful_stop : nullptr;
  // One participant is every group and the coordinator: the `colocated` identity, whose
  // permissions are the union of theirs (tools/robodds/security_policy.hpp).
  return run_in_process(registry, scenario, with_identity(launch.dds, kColocatedIdentity), options,
                        InProcessRun{time_mode(launch.realtime), launch.out_dir, to_string(Deploy::kColocated), true, &producers});
}

/// The command line of the child host of `group`.
std::vector<std::string> child_argv(const Scenario& scenario, const LaunchOptions& launch, const std::string& group,
                                    std::uint64_t run_id, std::int64_t epoch_ns) {
  HostArgs args;
  args.scenario = launch.scenario_file;
  args.group = group;
  args.run_id = run_id;
  args.out = launch.out_dir;
  args.deploy = to_string(Deploy::kProcesses);
  args.realtime = launch.realtime;
  args.epoch_ns = launch.realtime ? epoch_ns : 0;
  args.seed = scenario.seed;
  args.duration_s = scenario.duration_s;
  args.sets = launch.sets;
  args.added_components = launch.added_components;
  args.log_level = launch.log_level;
  args.max_missed_steps = launch.max_missed_steps;
  args.rt_priority = launch.rt_priority;  // each child applies it before its participant exists
  args.dds.domain = launch.dds.domain_id;
  args.dds.qos_files = launch.dds.qos_files;
  args.dds.participant_profile = launch.dds.participant_profile;
  args.dds.security_dir = launch.dds.security_dir;  // the child's identity is its group
  args.dds.discovery_servers = discovery_servers_text(launch.dds.discovery_servers);
  args.lockstep.input_timeout_s = launch.lockstep.input_timeout_s;
  args.lockstep.start_timeout_s = launch.lockstep.start_timeout_s;
  args.lockstep.lockstep_window = launch.lockstep.lockstep_window;  // the hosts check their history bound with it
  std::vector<std::string> argv = {self_exe(), "host"};
  for (std::string& arg : to_argv(args)) {
    argv.push_back(std::move(arg));
  }
  return argv;
}

/// A secure run across processes (all on this machine) uses kSecureLocalParticipantProfile instead
/// of the default profile: with Fast DDS 2.9.1, discovery and handshakes handled by several receive
/// threads at once sometimes leave a pair of participants unauthenticated for good (the run stalls
/// at step 0); that profile puts them on one socket (deploy/qos/robodds_qos.xml, docs/security.md).
/// Another --participant-profile is kept as given.
LaunchOptions secure_local_profile(const Scenario& scenario, LaunchOptions launch) {
  if (launch.dds.security_dir.empty() || launch.dds.participant_profile != kDefaultParticipantProfile) {
    return launch;
  }
  if (scenario.groups.size() + 1 > kSecureLocalMaxParticipants) {
    log::warn("run", std::to_string(scenario.groups.size()) + " groups and the coordinator are more participants than " +
                         kSecureLocalParticipantProfile + " finds (" + std::to_string(kSecureLocalMaxParticipants) +
                         "): using " + kDefaultParticipantProfile +
                         ", whose secure start-up can stall with Fast DDS 2.9.1 (docs/security.md)");
    return launch;
  }
  launch.dds.participant_profile = kSecureLocalParticipantProfile;
  log::info("run", std::string("DDS Security across processes: participant profile ") + kSecureLocalParticipantProfile +
                       " (one socket for discovery and handshakes: Fast DDS 2.9.1 start-up race, docs/security.md)");
  return launch;
}

RunStats run_as_processes(const ComponentRegistry& registry, const Scenario& scenario, const LaunchOptions& given) {
  // Validate everything in this process first so that bad input fails before spawning.
  for (const ComponentSpec& c : scenario.components) {
    registry.get(c.type);
  }
  const LaunchOptions launch = secure_local_profile(scenario, given);
  check_qos_profiles(launch.dds);  // one error line here, not one per child and a coordinator
  if (!launch.dds.security_dir.empty()) {  // likewise every identity the run uses
    check_security_files(launch.dds.security_dir, kCoordinatorIdentity);
    for (const GroupSpec& group : scenario.groups) {
      check_security_files(launch.dds.security_dir, group.name);
    }
  }
  const std::uint64_t run_id = make_run_id();
  const std::int64_t epoch_ns = (wall_clock_now_ns() / 1000000000LL + 2) * 1000000000LL;  // start in 2 s, on a whole second
  ProcessGroup children;
  for (const GroupSpec& group : scenario.groups) {
    // With --rt-priority a host starts up (exec, loading, configuration) at the runner's priority:
    // beside CPU hogs its start at SCHED_OTHER took seconds and made its first steps late.
    // Real time: a process group of its own, so a terminal's Ctrl-C reaches the runner alone,
    // which stops every host after the same step (below); lockstep children get it as before.
    children.spawn(group.name, child_argv(scenario, launch, group.name, run_id, epoch_ns), "", launch.rt_priority.has_value(),
                   launch.realtime);
  }
  RunStats stats;
  if (launch.realtime) {
    const auto start = std::chrono::steady_clock::now();
    const double limit = 2.0 + scenario.duration_s + launch.lockstep.start_timeout_s;
    std::uint64_t end = scenario.last_step();
    bool stop_sent = false;
    while (children.reap_finished() > 0) {
      if (launch.stop != nullptr && launch.stop->load()) {
        throw RunError("interrupted by a signal");
      }
      // A graceful stop: every host ends after the same step, chosen here once step 0's wall time
      // has come (the hosts' loops start there; a signal during start-up waits for it).
      if (!stop_sent && launch.graceful_stop != nullptr && launch.graceful_stop->load() && wall_clock_now_ns() >= epoch_ns) {
        stop_sent = true;
        const std::uint64_t step = graceful_stop_step(epoch_ns, wall_clock_now_ns(), scenario.step_s);
        if (step < end) {
          end = step;
          stats.stopped_by = "signal";
          children.signal_all(SIGUSR1, step);
          log::info("run", "stopping on a signal: every host ends cleanly after step " + std::to_string(step) + " (t = " +
                               shortest_text(static_cast<double>(step) * scenario.step_s) + " s); a second signal aborts");
        }
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limit) {
        throw RunError("real-time run did not finish within " + std::to_string(limit) + " s");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    stats.steps = end + 1;
    stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
  }
  // Lockstep: this process is the coordinator alone (no components), the children the hosts.
  HostOptions options;
  options.coordinator = true;
  options.members = all_members(scenario);
  options.run_id = run_id;
  apply(launch.lockstep, options);
  options.progress = launch.progress;
  options.poll = [&children] { children.check_alive(); };
  options.stop = launch.stop;
  if (digest_check_wanted()) {
    options.digest = host_digest(scenario, "", launch.sets, with_identity(launch.dds, kCoordinatorIdentity));
  }
  stats = run_in_process(registry, scenario, with_identity(launch.dds, kCoordinatorIdentity), options,
                         InProcessRun{TimeMode::kLockstep, launch.out_dir, ""});
  children.wait_all(30.0);
  return stats;
}

}  // namespace

std::uint64_t graceful_stop_step(std::int64_t epoch_ns, std::int64_t now_ns, double step_s) {
  const double ahead_s = std::max(0.0, static_cast<double>(now_ns - epoch_ns) * 1e-9) + kGracefulStopAheadS;
  return static_cast<std::uint64_t>(std::ceil(ahead_s / step_s));
}

const char* to_string(Deploy deploy) { return deploy == Deploy::kProcesses ? "processes" : "colocated"; }

void apply_rt_priority_option(const std::optional<int>& priority, const std::string& who, bool announce) {
  if (!priority) {
    return;
  }
  const std::string warning = apply_rt_priority(*priority);
  if (!warning.empty()) {
    log::warn(who, warning);
  }
  if (announce) {
    log::info(who, std::string(kRtPriorityOption) + " " + std::to_string(*priority) + ": SCHED_FIFO priority " +
                       std::to_string(*priority) + " for the real-time loop, " +
                       std::to_string(communication_priority(*priority)) + " for the other threads, memory locked");
  }
}

std::string share_dir() { return share_dir_of_this_process(ROBODDS_SOURCE_DIR); }

DdsOptions resolve_dds(const DdsArgs& args, const std::string& participant_name) {
  DdsOptions o;
  if (args.domain >= 0) {
    o.domain_id = args.domain;  // --domain: CLI11 checked 0..232
  } else {
    // The whole text must be the number: "7x" is refused, not read as 7.
    const std::string env_domain = env_or("ROBODDS_DOMAIN_ID", "0");
    const std::optional<std::uint64_t> domain = parse_whole_number(env_domain, 232);
    if (!domain) {
      throw ConfigError("ROBODDS_DOMAIN_ID: expected a whole number 0..232, got '" + env_domain + "'");
    }
    o.domain_id = static_cast<int>(*domain);
  }
  if (!args.qos_files.empty()) {
    o.qos_files = args.qos_files;
  } else {
    o.qos_files.push_back(share_dir() + "/deploy/qos/robodds_qos.xml");
    const std::string extra = env_or("ROBODDS_QOS_FILE", "");
    if (!extra.empty() && extra != o.qos_files.front()) {
      o.qos_files.push_back(extra);
    }
  }
  o.participant_profile = !args.participant_profile.empty()
                              ? args.participant_profile
                              : env_or("ROBODDS_PARTICIPANT_PROFILE", kDefaultParticipantProfile);
  o.participant_name = participant_name;
  o.security_dir = !args.security_dir.empty() ? args.security_dir : env_or("ROBODDS_SECURITY_DIR", "");
  o.discovery_servers = parse_discovery_servers(args.discovery_servers);
  return o;
}

DdsOptions tools_dds(const DdsArgs& args, const std::string& participant_name) {
  return with_identity(resolve_dds(args, participant_name), kToolsIdentity);
}

RunStats run_in_process(const ComponentRegistry& registry, const Scenario& scenario, const DdsOptions& dds,
                        HostOptions options, const InProcessRun& in_process) {
  // Our hosts announce the components they run, so that inputs can tell the scenario's producers
  // from other writers (RunContext::assigned_producers).
  DdsOptions announced = dds;
  announced.components = options.components;
  if (!options.digest.empty()) {  // and what it loaded, which the other hosts of the run compare
    announced.run_id = options.run_id;
    announced.digest = options.digest;
  }
  const std::size_t robots_served = scenario.robots_served_by(options.components);
  if (!options.single_process && in_process.mode == TimeMode::kLockstep) {
    // Room for what it may be ahead of or behind its peers (transport_buffers.hpp).
    announced.transport_buffer_bytes = transport_buffer_bytes(robots_served, options.lockstep_window);
  }
  auto bus = make_dds_bus(announced);
  bus->expect_robots(robots_served);  // this process's writers' instances
  const bool has_standby = std::any_of(scenario.components.begin(), scenario.components.end(),
                                       [](const ComponentSpec& c) { return !c.standby_for.empty(); });
  // A co-located run: its components' samples stay in memory, DDS serves observers (and, in real
  // time, brings the topics no component here produces). Hot standby keeps DDS: its ownership
  // and deadlines work between processes.
  const bool in_memory = options.single_process && (in_process.mode == TimeMode::kLockstep || !has_standby);
  // Only inputs judge producers: a process without components (a coordinator) needs none.
  const bool assign = in_process.assign_producers && !options.components.empty();
  std::optional<ScenarioProducers> found;  // when the caller's start-up check did not find them
  const ScenarioProducers* producers = in_process.producers;
  if ((assign || has_standby || in_memory) && producers == nullptr) {
    found = scenario_producers(registry, scenario, in_process.mode);
    producers = &*found;
  }
  std::unique_ptr<ColocatedBus> colocated;
  if (in_memory && in_process.mode == TimeMode::kLockstep) {
    colocated = std::make_unique<ColocatedBus>(*bus);
  } else if (in_memory) {
    std::set<std::string> produced_here;  // every component of the scenario runs here
    for (const auto& [component, topics] : *producers) {
      produced_here.insert(topics.begin(), topics.end());
    }
    colocated = std::make_unique<ColocatedBus>(*bus, ColocatedWorld::kOpen, std::move(produced_here));
  }
  Notifier notifier;
  RunContext run;
  run.scenario = &scenario;
  run.bus = colocated ? static_cast<Bus*>(colocated.get()) : bus.get();
  run.notifier = &notifier;
  run.mode = in_process.mode;
  run.output_dir = in_process.out_dir;
  run.single_process = options.single_process;
  run.deploy_label = in_process.deploy_label;
  run.lockstep_window = std::max<std::size_t>(1, options.lockstep_window);
  if (assign) {
    run.assigned_producers = std::make_shared<const AssignedProducers>(assigned_producers(scenario, *producers));
    // The same in every host (found from the scenario): a recorder of the run waits for these.
    run.produced_instances =
        std::make_shared<const ProducedInstances>(produced_instances(registry, scenario, *producers, run.mode));
  }
  if (has_standby) {  // hot standby: the topics it writes use exclusive ownership
    run.exclusive_topics = exclusive_topics(scenario, *producers);
    apply_exclusive_ownership(*bus, scenario, *producers, run.exclusive_topics, options.components);
  }
  Host host(registry, run, options);
  // The readers call into the host's inputs and the notifier: delete them first, also on a throw.
  struct ReaderCloser {
    DdsBus& bus;
    ~ReaderCloser() { bus.close_readers(); }
  } closer{*bus};
  host.configure();
  bus->start();
  const RunStats stats = host.run();
  bus->flush(std::chrono::milliseconds(2000));
  return stats;
}

/// The registered scenario checks (shared facts), one producer per topic instance, where
/// standbys may run and the components' input rate assumptions (warnings logged when `warn`),
/// before anything starts. Returns the scenario's producers it found, for the run
/// (InProcessRun::producers): finding them configures every component once.
static ScenarioProducers check_producers(const ComponentRegistry& registry, const Scenario& scenario, TimeMode mode,
                                         bool single_process, bool warn = true) {
  for (const ComponentSpec& component : scenario.components) {
    registry.type_of(scenario, component);  // FILE: components.NAME.type: unknown ... did you mean
  }
  registry.check_scenario(scenario);
  check_standby_deployment(scenario, mode, single_process);
  // Installed before DDS is set up: the dry configure below may decode samples (a replay source
  // declares the instances its recording holds), as the run's own configure does.
  install_dds_sample_codec();
  const std::map<std::string, ComponentTopics> components = scenario_component_topics(registry, scenario, mode);
  ScenarioProducers producers = producers_of(components);
  check_one_producer_per_instance(scenario, producers);
  const std::vector<std::string> rate_warnings = check_input_rates(scenario, components, mode);
  if (warn) {
    for (const std::string& warning : rate_warnings) {
      log::warn("scenario", warning);
    }
  }
  return producers;
}

RunStats launch_run(const ComponentRegistry& registry, const Scenario& scenario, const LaunchOptions& options) {
  const ScenarioProducers producers =
      check_producers(registry, scenario, time_mode(options.realtime), options.deploy == Deploy::kColocated);
  try {
    return options.deploy == Deploy::kColocated ? run_colocated(registry, scenario, options, producers)
                                                : run_as_processes(registry, scenario, options);
  } catch (const RunError& e) {
    // The hosts have stopped (the children are reaped): the evaluator's partial summary, or none.
    record_failed_run(options.out_dir, e.what());
    throw;
  }
}

namespace {

/// The scenario a host runs: the scenario file with the command line's overrides, or (--type)
/// one component without a scenario file.
Scenario host_scenario(const ComponentRegistry& registry, const HostArgs& args) {
  if (!args.type.empty()) {
    if (!args.scenario.empty() || !args.group.empty() || !args.components.empty() || !args.sets.empty()) {
      throw ConfigError("robodds host: --type runs one component without a scenario; it does not go with --scenario, --group, "
                        "--components or --set (its own keys go in --params)");
    }
    registry.get(args.type);  // an unknown type names the known ones
    return standalone_scenario(args);
  }
  if (args.scenario.empty() && args.coordinate) {
    return coordinator_scenario(args);  // a coordinator of component executables (robodds coordinate)
  }
  if (args.scenario.empty()) {
    throw ConfigError("robodds host: --scenario is required (or --type: one component without a scenario file; or "
                      "`robodds coordinate`: a lockstep coordinator of component executables)");
  }
  if (!args.robots.empty() || !args.name.empty() || args.step_s) {
    throw ConfigError("robodds host: --robot, --name and --step describe a component without a scenario (--type); the scenario has its own");
  }
  Scenario scenario = load_scenario(args.scenario);
  add_components(scenario, args.added_components);  // before the overrides: --set may name them
  apply_run_overrides(scenario, args.duration_s, args.seed);
  if (!args.params.empty()) {
    apply_param_overrides(scenario, load_param_file(args.params), args.params);
  }
  check_param_keys(scenario, registry, args.sets, "--set");
  apply_param_overrides(scenario, parse_param_assignments(args.sets), "--set");
  return scenario;
}

}  // namespace

int run_host(const ComponentRegistry& registry, const HostArgs& args, const std::atomic<bool>* stop,
             const std::atomic<std::uint64_t>* stop_at_step) {
  const bool standalone = args.deploy != to_string(Deploy::kProcesses);  // not a child of `robodds run --deploy processes`
  // First: a refusal ends the host before anything started; every thread created later inherits it.
  const std::string who = !args.member.empty() ? args.member : !args.group.empty() ? args.group : !args.type.empty() ? args.type : "host";
  apply_rt_priority_option(args.rt_priority, who, standalone);
  const Scenario scenario = host_scenario(registry, args);
  // A child of `robodds run --deploy processes`: its parent logged the scenario's warnings once.
  const ScenarioProducers producers = check_producers(registry, scenario, time_mode(args.realtime), false, standalone);
  if (!args.out.empty() && args.deploy != to_string(Deploy::kProcesses)) {
    make_output_dir(args.out);  // a child of `robodds run --deploy processes` gets a checked one
  }
  HostOptions options;
  if (!args.type.empty()) {
    options.components = {scenario.components.front().name};
    options.member = scenario.groups.front().name;
  } else if (!args.group.empty()) {
    options.components = scenario.group(args.group).components;
    options.member = args.group;
  } else if (!args.components.empty()) {
    for (const std::string& c : args.components) {
      scenario.component(c);
    }
    options.components = args.components;
    options.member = "host";
  } else if (args.coordinate) {
    options.member = "coordinator";  // a coordinator alone (e.g. on its own machine): ticks only
  } else {
    throw ConfigError("robodds host: give --group or --components (or --coordinate alone)");
  }
  if (!args.member.empty()) {
    options.member = args.member;
  }
  check_standby_apart(scenario, options.components);
  if (!args.members.empty()) {
    check_members(args.members);  // a duplicate or empty name would be waited for in vain
  }
  options.run_id = args.run_id;
  options.coordinator = args.coordinate;
  options.members = !args.members.empty()         ? args.members
                    : options.components.empty() ? all_members(scenario)
                                                 : std::vector<std::string>{options.member};
  options.realtime_epoch_ns = args.epoch_ns;
  options.max_missed_steps = args.max_missed_steps;
  // A component without a scenario and without --duration runs until stopped: in real time a
  // signal is its normal end (on_finish runs, exit 0); in lockstep the final tick is.
  options.stop_ends_run = !args.type.empty() && !args.duration_s;
  apply(args.lockstep, options);
  options.stop = stop;
  options.stop_at_step = stop_at_step;
  // DDS Security identity: the group's (also under another --member), the coordinator's for a
  // coordinator alone; a host of loose --components has none (it would need a group's rights).
  const std::string identity = !args.type.empty()     ? scenario.groups.front().name
                               : !args.group.empty()  ? args.group
                               : options.components.empty() ? std::string(kCoordinatorIdentity)
                                                            : std::string();
  // A host on its own (a container, another machine) says what it runs and how the run ends, and
  // a coordinator its progress every 10 %: `docker-compose logs` shows them. A child of `robodds
  // run --deploy processes` stays quiet: its runner reports.
  const std::string run_name = "run " + std::to_string(options.run_id) + " of '" + scenario.name + "'";
  if (standalone && options.coordinator) {
    options.progress = [member = options.member, reported = std::uint64_t{0}](std::uint64_t step, std::uint64_t last) mutable {
      const std::uint64_t acked = step + 1;  // `step` is the index of the step just acknowledged
      const std::uint64_t decile = acked * 10 / (last + 1);
      if (decile > reported) {
        reported = decile;
        log::info(member, std::to_string(acked) + " of " + std::to_string(last + 1) + " steps acknowledged by every group (" +
                              std::to_string(decile * 10) + " %)");
      }
    };
  }
  if (standalone) {
    std::string what;
    for (const std::string& name : options.coordinator ? options.members : options.components) {
      what += (what.empty() ? "" : ", ") + name;
    }
    // A component executable in lockstep does nothing until a coordinator ticks: say so at once,
    // not only when the first tick's wait (--start-timeout, 30 s) runs out.
    const bool awaits_coordinator = !args.type.empty() && !args.realtime && !options.coordinator;
    log::info(options.member, run_name + ": " + (options.coordinator ? "coordinating " : "components ") + what +
                                  (args.realtime             ? " (real time)"
                                   : awaits_coordinator ? " (lockstep: waiting for the ticks of a coordinator of member '" +
                                                              options.member + "', e.g. `robodds coordinate --members " +
                                                              options.member + ",... --duration S`; --realtime needs none)"
                                                        : " (lockstep)"));
  }
  // A component executable without a scenario file knows no other producer: the first writer rule.
  const bool assign_producers = args.type.empty();
  const DdsOptions dds = with_identity(resolve_dds(args.dds, "robodds-" + options.member), identity);
  if (!args.type.empty() && !args.realtime) {
    // A component executable waiting for ticks: say which coordinator it waits for, and that it
    // needs none on the wall clock (it waited --start-timeout, 30 s by default, for the first tick).
    options.no_tick_advice = "is a lockstep coordinator alive on domain " + std::to_string(dds.domain_id) + " with run id " +
                             std::to_string(args.run_id) + " and waiting for member '" + options.member +
                             "' (`robodds coordinate --members " + options.member + ",... --step " +
                             shortest_text(scenario.step_s) + " --duration S`, or `robodds run`)? To run this component "
                             "without one, on the wall clock, give --realtime";
  }
  if (!args.scenario.empty() && digest_check_wanted()) {  // a host of a scenario: the others of its run must have loaded the same
    check_qos_profiles(dds);  // a missing or bad QoS file is named as such, not as unreadable for its digest
    options.digest = host_digest(scenario, args.params, args.sets, dds);
  }
  const RunStats stats = run_in_process(registry, scenario, dds,
                                        options, InProcessRun{time_mode(args.realtime), args.out, args.deploy, assign_producers, &producers});
  const std::string figures = std::to_string(stats.steps) + " steps in " + shortest_text(std::round(stats.wall_s * 10.0) / 10.0) + " s";
  if (!stats.degraded.empty()) {
    log::error(options.member, run_name + " ended DEGRADED after " + figures + ": " + stats.degraded + " (exit code " +
                                   std::to_string(kDegradedExitCode) + ")");
    return kDegradedExitCode;
  }
  if (standalone) {
    log::info(options.member, run_name + " completed: " + figures);
  }
  return 0;
}

int draw_plots(const std::string& out_dir, double timeout_s, const std::string& log_file) {
  const std::string script = share_dir() + "/sim/report/report.py";
  std::fflush(stdout);  // our buffered output first, then the child's
  try {
    return run_to_exit("python3 " + script, {"python3", script, out_dir}, timeout_s, log_file);
  } catch (const RunError& e) {
    log::warn("report", e.what());
    return 1;
  }
}

}  // namespace robodds
