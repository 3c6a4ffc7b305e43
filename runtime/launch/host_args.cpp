#include "runtime/launch/host_args.hpp"

#include <CLI/CLI.hpp>

#include <limits>

#include "common/number_parse.hpp"
#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/realtime_priority.hpp"
#include "runtime/health/overrun_counter.hpp"

namespace robodds {
namespace {

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) {
    text += (text.empty() ? "" : ",") + item;
  }
  return text;
}

/// Appends "--name value" when the value differs from the default or has a placeholder.
class ArgvWriter {
 public:
  explicit ArgvWriter(const ArgPlaceholders& placeholders) : placeholders_(placeholders) {}

  void option(const std::string& name, const std::string& value, bool is_default) {
    const auto placeholder = placeholders_.find(name);
    if (placeholder != placeholders_.end()) {
      argv_.insert(argv_.end(), {name, placeholder->second});
    } else if (!is_default) {
      argv_.insert(argv_.end(), {name, value});
    }
  }
  void flag(const std::string& name, bool set) {
    if (set) {
      argv_.push_back(name);
    }
  }
  std::vector<std::string> take() { return std::move(argv_); }

 private:
  const ArgPlaceholders& placeholders_;
  std::vector<std::string> argv_;
};

/// A positive, finite number of seconds (CLI::PositiveNumber lets "nan" through). The step count
/// it gives with the step is checked later, in one place (checked_last_step()).
CLI::Validator positive_seconds() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::optional<double> value = parse_finite_number(text);
        if (!value || !(*value > 0.0)) {
          return "must be a positive, finite number of seconds (got " + text + ")";
        }
        return {};
      },
      "SECONDS");
}

/// A whole number 0..2^64-1 written in decimal digits (CLI11 would turn "-1" into 2^64-1).
CLI::Validator whole_number(const std::string& placeholder) {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (!parse_whole_number(text, std::numeric_limits<std::uint64_t>::max())) {
          return "must be a whole number 0..18446744073709551615 (got " + text + ")";
        }
        return {};
      },
      placeholder);
}

}  // namespace

void add_duration_option(CLI::App* app, std::optional<double>& duration_s, const std::string& help) {
  app->add_option_function<double>(
         "--duration", [&duration_s](const double& seconds) { duration_s = seconds; }, help)
      ->check(positive_seconds());
}

void add_step_option(CLI::App* app, std::optional<double>& step_s, const std::string& help) {
  app->add_option_function<double>(
         "--step", [&step_s](const double& seconds) { step_s = seconds; }, help)
      ->check(positive_seconds());
}

void add_seed_option(CLI::App* app, std::optional<std::uint64_t>& seed, const std::string& help) {
  app->add_option_function<std::uint64_t>(
         "--seed", [&seed](const std::uint64_t& value) { seed = value; }, help)
      ->check(whole_number("SEED"));
}

void add_max_missed_steps_option(CLI::App* app, std::optional<std::uint64_t>& max_missed_steps) {
  app->add_option_function<std::uint64_t>(
         "--max-missed-steps", [&max_missed_steps](const std::uint64_t& value) { max_missed_steps = value; },
         "real time: fail the run when a host skips more than N due steps (default: " +
             shortest_text(kDefaultMaxMissedFraction * 100.0) + " % of the run's steps)")
      ->check(whole_number("N"));
}

void add_rt_priority_option(CLI::App* app, std::optional<int>& rt_priority) {
  app->add_option_function<std::string>(
         kRtPriorityOption, [&rt_priority](const std::string& text) { rt_priority = rt_priority_from_text(text); },
         "run SCHED_FIFO at this priority (1..99) with locked memory (mlockall), so other load on the machine cannot "
         "delay the real-time loop; needs root, CAP_SYS_NICE + CAP_IPC_LOCK, or rtprio/memlock in limits.conf")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            const std::string problem = rt_priority_problem(text);
            return problem.empty() ? problem : problem + " (got " + text + ")";
          },
          ""))
      ->type_name("N");
}

bool DdsArgs::operator==(const DdsArgs& o) const {
  return domain == o.domain && qos_files == o.qos_files && participant_profile == o.participant_profile &&
         security_dir == o.security_dir && discovery_servers == o.discovery_servers;
}

bool LockstepArgs::operator==(const LockstepArgs& o) const {
  return input_timeout_s == o.input_timeout_s && start_timeout_s == o.start_timeout_s && lockstep_window == o.lockstep_window;
}

bool HostArgs::operator==(const HostArgs& o) const {
  return scenario == o.scenario && group == o.group && components == o.components && params == o.params && sets == o.sets && added_components == o.added_components &&
         member == o.member && coordinate == o.coordinate && members == o.members && run_id == o.run_id && out == o.out &&
         deploy == o.deploy && realtime == o.realtime && epoch_ns == o.epoch_ns && duration_s == o.duration_s &&
         seed == o.seed && log_level == o.log_level && max_missed_steps == o.max_missed_steps &&
         rt_priority == o.rt_priority && type == o.type && name == o.name && robots == o.robots &&
         step_s == o.step_s && dds == o.dds && lockstep == o.lockstep;
}

std::vector<std::string> to_argv(const HostArgs& args, const ArgPlaceholders& placeholders) {
  const HostArgs defaults;
  ArgvWriter w(placeholders);
  w.option("--scenario", args.scenario, args.scenario.empty());
  w.option("--group", args.group, args.group.empty());
  w.option("--components", join(args.components), args.components.empty());
  w.option("--params", args.params, args.params.empty());
  for (const std::string& added : args.added_components) {
    w.option("--add-component", added, false);
  }
  for (const std::string& assignment : args.sets) {
    w.option("--set", assignment, false);
  }
  w.option("--member", args.member, args.member.empty());
  w.flag("--coordinate", args.coordinate);
  w.option("--members", join(args.members), args.members.empty());
  w.option("--run-id", std::to_string(args.run_id), args.run_id == defaults.run_id);
  w.option("--out", args.out, args.out.empty());
  w.option("--deploy", args.deploy, args.deploy.empty());
  w.flag("--realtime", args.realtime);
  w.option("--epoch-ns", std::to_string(args.epoch_ns), args.epoch_ns == defaults.epoch_ns);
  w.option("--duration", args.duration_s ? shortest_text(*args.duration_s) : "", !args.duration_s);
  w.option("--seed", args.seed ? std::to_string(*args.seed) : "", !args.seed);
  w.option("--log", args.log_level, args.log_level.empty());
  w.option("--max-missed-steps", args.max_missed_steps ? std::to_string(*args.max_missed_steps) : "", !args.max_missed_steps);
  w.option(kRtPriorityOption, args.rt_priority ? std::to_string(*args.rt_priority) : "", !args.rt_priority);
  w.option("--type", args.type, args.type.empty());
  w.option("--name", args.name, args.name.empty());
  for (const std::string& robot : args.robots) {
    w.option("--robot", robot, false);
  }
  w.option("--step", args.step_s ? shortest_text(*args.step_s) : "", !args.step_s);
  w.option("--domain", std::to_string(args.dds.domain), args.dds.domain == defaults.dds.domain);
  std::vector<std::string> argv = w.take();
  for (const std::string& file : args.dds.qos_files) {
    argv.insert(argv.end(), {"--qos", file});
  }
  ArgvWriter rest(placeholders);
  rest.option("--participant-profile", args.dds.participant_profile, args.dds.participant_profile.empty());
  rest.option("--security", args.dds.security_dir, args.dds.security_dir.empty());
  rest.option("--discovery-server", args.dds.discovery_servers, args.dds.discovery_servers.empty());
  rest.option("--input-timeout", shortest_text(args.lockstep.input_timeout_s),
              args.lockstep.input_timeout_s == defaults.lockstep.input_timeout_s);
  rest.option("--start-timeout", shortest_text(args.lockstep.start_timeout_s),
              args.lockstep.start_timeout_s == defaults.lockstep.start_timeout_s);
  rest.option("--lockstep-window", std::to_string(args.lockstep.lockstep_window),
              args.lockstep.lockstep_window == defaults.lockstep.lockstep_window);
  for (std::string& arg : rest.take()) {
    argv.push_back(std::move(arg));
  }
  return argv;
}

void add_dds_options(CLI::App* app, DdsArgs& args) {
  app->add_option("--domain", args.domain, "DDS domain id (default: $ROBODDS_DOMAIN_ID or 0)")->check(CLI::Range(0, 232));
  app->add_option("--qos", args.qos_files,
                  "QoS profile XML file(s) (default: deploy/qos/robodds_qos.xml, plus $ROBODDS_QOS_FILE if set)");
  app->add_option("--participant-profile", args.participant_profile,
                  "participant profile (default: $ROBODDS_PARTICIPANT_PROFILE or robodds.participant)");
  app->add_option("--security", args.security_dir,
                  "DDS Security: directory made by `robodds security init` (authenticated, access-controlled, encrypted; "
                  "default: $ROBODDS_SECURITY_DIR or none)");
  app->add_option("--discovery-server", args.discovery_servers,
                  "ADDR[:PORT][,ADDR[:PORT]...]: discover through these Fast DDS Discovery Servers (port 11811 by default; "
                  "the i-th has server id i, the others are backups: start them with `fast-discovery-server -i <i>`) "
                  "instead of the participant profile's discovery");
}

std::string discovery_servers_text(const std::vector<DiscoveryServer>& servers) {
  std::string text;
  for (const DiscoveryServer& server : servers) {
    text += (text.empty() ? "" : ",") + server.host + ":" + std::to_string(server.port);
  }
  return text;
}

std::vector<DiscoveryServer> parse_discovery_servers(const std::string& text) {
  std::vector<DiscoveryServer> servers;
  if (text.empty()) {
    return servers;
  }
  const auto bad = [&text](const std::string& entry, const std::string& why) {
    return ConfigError("--discovery-server '" + text + "': '" + entry + "' " + why + " (expected ADDR[:PORT][,ADDR[:PORT]...])");
  };
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find_first_of(",;", begin), text.size());
    const std::string entry = text.substr(begin, end - begin);
    const std::size_t colon = entry.rfind(':');
    DiscoveryServer server;
    server.host = entry.substr(0, colon);
    if (server.host.empty()) {
      throw bad(entry, "has no address");
    }
    if (server.host.find_first_of(" \t") != std::string::npos) {
      throw bad(entry, "has a space in its address");
    }
    if (colon != std::string::npos) {
      const std::optional<std::uint64_t> port = parse_whole_number(entry.substr(colon + 1), 65535);
      if (!port || *port == 0) {
        throw bad(entry, "has no valid port (1-65535)");
      }
      server.port = static_cast<int>(*port);
    }
    servers.push_back(server);
    if (servers.size() > 255) {
      throw bad(entry, "is one server too many: at most 255 (a server id is one byte of the GUID prefix)");
    }
    begin = end + 1;
  }
  return servers;
}

void add_lockstep_options(CLI::App* app, LockstepArgs& args) {
  app->add_option("--input-timeout", args.input_timeout_s, "s, lockstep: max wait for a component's inputs at one step");
  app->add_option("--start-timeout", args.start_timeout_s, "s, max wait for peers to start");
  app->add_option("--lockstep-window", args.lockstep_window,
                  "lockstep coordinator: ticks outstanding at once (1 = each tick waits for all acknowledgements; "
                  "more pipelines the groups, same results; at most 32; a host given it checks that its producers' "
                  "lockstep writer history covers it)")
      ->check(CLI::Range(1, 32));
}

namespace {

/// The options of a run that `robodds host` and a component executable share.
void add_run_options(CLI::App* app, HostArgs& args) {
  app->add_option("--run-id", args.run_id, "run id given by robodds run");
  app->add_option("--out", args.out, "output directory of the run (what its recording component writes)");
  app->add_option("--deploy", args.deploy,
                  "deployment label for the \"run\" section of summary.json (set by robodds run; default: no run section)");
  app->add_flag("--realtime", args.realtime, "wall-clock timers instead of lockstep");
  app->add_option("--epoch-ns", args.epoch_ns, "real time: wall clock (ns) of step 0");
  add_duration_option(app, args.duration_s, "override the scenario duration (s; a component without a scenario: until stopped)");
  add_seed_option(app, args.seed, "override the scenario seed (a component without a scenario: 1)");
  app->add_option("--log", args.log_level, "log level: debug, info, warn, error (default: the global --log)");
  add_max_missed_steps_option(app, args.max_missed_steps);
  add_rt_priority_option(app, args.rt_priority);
  add_dds_options(app, args.dds);
  add_lockstep_options(app, args.lockstep);
}

/// The options of one component without a scenario file (but its type).
void add_standalone_options(CLI::App* app, HostArgs& args) {
  app->add_option("--name", args.name, "without a scenario: instance name (default: the type); seeds derive from it");
  app->add_option("--robot", args.robots,
                  "without a scenario: a robot the component serves, ID or ID:X,Y,THETA (initial pose, m, m, rad); repeat for several");
  add_step_option(app, args.step_s, "without a scenario: simulation step (s, default 0.01)");
}

}  // namespace

void add_component_options(CLI::App* app, HostArgs& args) {
  add_standalone_options(app, args);
  app->add_option("--params", args.params,
                  "YAML file of this component's parameters over its defaults (keys as in its defaults file)");
  app->add_option("--member", args.member, "lockstep: name in acknowledgements (default: the instance name)");
  add_run_options(app, args);
}

HostArgOptions add_host_options(CLI::App* app, HostArgs& args) {
  HostArgOptions options;
  options.scenario = app->add_option("--scenario", args.scenario, "scenario YAML (robots, step, parameters, groups)");
  options.group = app->add_option("--group", args.group, "run the components of this group");
  options.components =
      app->add_option("--components", args.components, "run these component instances (comma separated)")->delimiter(',');
  app->add_option("--type", args.type, "run one component of this type without a scenario file");
  app->add_option("--params", args.params,
                  "YAML map component.parameter -> value over the scenario's (with --type: the component's own keys)");
  app->add_option("--set", args.sets, "component.parameter=value over the scenario's and --params (repeatable; with --scenario)");
  app->add_option("--add-component", args.added_components,
                  "GROUP:NAME:TYPE: adds a component to the scenario's group before --set (repeatable; what `robodds run "
                  "--record` gives its hosts)");
  app->add_option("--member", args.member, "name in acknowledgements (default: the group, or the instance name)");
  app->add_flag("--coordinate", args.coordinate, "also publish ticks (a standalone lockstep host)");
  app->add_option("--members", args.members,
                  "with --coordinate: groups whose acknowledgements to wait for (default: this host's group, "
                  "or every group of the scenario when the host runs no component)")
      ->delimiter(',');
  add_standalone_options(app, args);
  add_run_options(app, args);
  return options;
}

}  // namespace robodds
