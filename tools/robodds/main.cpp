// robodds: run scenarios, host components, inspect topics.
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

#include "runtime/dds_bus.hpp"
#include "runtime/discovery.hpp"
#include "runtime/error.hpp"
#include "runtime/host.hpp"
#include "runtime/log.hpp"
#include "runtime/sample_format.hpp"
#include "runtime/share_dir.hpp"
#include "tools/robodds/builtin_components.hpp"
#include "tools/robodds/deploy_command.hpp"
#include "tools/robodds/process_group.hpp"

#ifndef ROBODDS_SOURCE_DIR
#define ROBODDS_SOURCE_DIR "."
#endif

namespace robodds {
namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop = true; }

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : fallback;
}

std::string share_dir() { return share_dir_of_this_process(ROBODDS_SOURCE_DIR); }

std::string self_exe() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) {
    throw RunError("cannot find the robodds executable (/proc/self/exe)");
  }
  buf[n] = '\0';
  return buf;
}

/// DDS options shared by every subcommand (flags override the environment).
struct DdsFlags {
  int domain = -1;
  std::vector<std::string> qos_files;
  std::string participant_profile;

  void add_to(CLI::App* app) {
    app->add_option("--domain", domain, "DDS domain id (default: $ROBODDS_DOMAIN_ID or 0)")->check(CLI::Range(0, 232));
    app->add_option("--qos", qos_files, "QoS profile XML file(s) (default: deploy/qos/robodds_qos.xml, plus $ROBODDS_QOS_FILE if set)");
    app->add_option("--participant-profile", participant_profile,
                    "participant profile (default: $ROBODDS_PARTICIPANT_PROFILE or robodds.participant)");
  }
  DdsOptions resolve(const std::string& participant_name) const {
    DdsOptions o;
    const std::string env_domain = env_or("ROBODDS_DOMAIN_ID", "0");
    try {
      o.domain_id = domain >= 0 ? domain : std::stoi(env_domain);
    } catch (const std::exception&) {
      throw ConfigError("ROBODDS_DOMAIN_ID: expected an integer 0..232, got '" + env_domain + "'");
    }
    if (o.domain_id < 0 || o.domain_id > 232) {
      throw ConfigError("ROBODDS_DOMAIN_ID: " + std::to_string(o.domain_id) + " is outside 0..232");
    }
    if (!qos_files.empty()) {
      o.qos_files = qos_files;
    } else {
      o.qos_files.push_back(share_dir() + "/deploy/qos/robodds_qos.xml");
      const std::string extra = env_or("ROBODDS_QOS_FILE", "");
      if (!extra.empty() && extra != o.qos_files.front()) {
        o.qos_files.push_back(extra);
      }
    }
    o.participant_profile = !participant_profile.empty() ? participant_profile
                                                         : env_or("ROBODDS_PARTICIPANT_PROFILE", kDefaultParticipantProfile);
    o.participant_name = participant_name;
    return o;
  }
};

/// Lockstep options shared by `run` and `host` (timeouts, coordinator window).
struct TimeoutFlags {
  double input_timeout_s = 10.0;
  double start_timeout_s = 30.0;
  std::size_t lockstep_window = 1;
  void add_to(CLI::App* app) {
    app->add_option("--input-timeout", input_timeout_s, "s, lockstep: max wait for a component's inputs at one step");
    app->add_option("--start-timeout", start_timeout_s, "s, max wait for peers to start");
    app->add_option("--lockstep-window", lockstep_window,
                    "lockstep coordinator: ticks outstanding at once (1 = each tick waits for all acknowledgements; "
                    "more pipelines the groups, same results)")
        ->check(CLI::Range(1, 64));
  }
  void apply_to(HostOptions& options) const {
    options.input_timeout_s = input_timeout_s;
    options.start_timeout_s = start_timeout_s;
    options.lockstep_window = lockstep_window;
  }
};

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

void show_progress(std::uint64_t step, std::uint64_t last) {
  static const bool on_terminal = isatty(STDERR_FILENO) != 0;  // a system call: ask once, not per tick
  if (!on_terminal) {
    return;
  }
  static auto last_print = std::chrono::steady_clock::now();
  const auto now = std::chrono::steady_clock::now();
  if (step != last && now - last_print < std::chrono::milliseconds(200)) {
    return;
  }
  last_print = now;
  std::fprintf(stderr, "\r  step %llu / %llu (%3.0f%%)%s", static_cast<unsigned long long>(step),
               static_cast<unsigned long long>(last), last > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(last) : 100.0,
               step == last ? "\n" : "");
}

/// Adds the runner's wall-clock figures to summary.json (kept apart from "metrics").
void append_run_section(const std::string& out_dir, const std::string& deploy, const std::string& mode, const RunStats& stats) {
  const std::string path = out_dir + "/summary.json";
  std::ifstream in(path);
  if (!in) {
    return;
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  const std::size_t end = text.rfind('}');
  if (end == std::string::npos) {
    return;
  }
  char run[512];
  std::snprintf(run, sizeof(run),
                ",\n  \"run\": {\n    \"deploy\": \"%s\",\n    \"mode\": \"%s\",\n    \"wall_time_s\": %.6f,\n    \"ticks\": %llu,\n    \"ticks_per_s\": %.1f\n  }\n}\n",
                deploy.c_str(), mode.c_str(), stats.wall_s, static_cast<unsigned long long>(stats.steps),
                stats.wall_s > 0 ? static_cast<double>(stats.steps) / stats.wall_s : 0.0);
  text = text.substr(0, text.find_last_not_of(" \n", end - 1) + 1) + run;
  std::ofstream(path, std::ios::binary) << text;
}

/// Prints summary.json's numbers as an aligned "key  value" table.
void print_summary(const std::string& out_dir) {
  std::ifstream in(out_dir + "/summary.json");
  if (!in) {
    std::printf("(no summary.json in %s: the scenario has no evaluator)\n", out_dir.c_str());
    return;
  }
  std::vector<std::string> path;
  std::string line;
  std::printf("\nsummary (%s/summary.json)\n", out_dir.c_str());
  while (std::getline(in, line)) {
    const std::size_t q1 = line.find('"');
    const std::size_t colon = line.find("\": ");
    if (q1 != std::string::npos && colon != std::string::npos) {
      const std::string key = line.substr(q1 + 1, colon - q1 - 1);
      std::string value = line.substr(colon + 3);
      if (value == "{") {
        path.push_back(key);
        continue;
      }
      if (!value.empty() && value.back() == ',') {
        value.pop_back();
      }
      std::string full;
      for (const std::string& p : path) {
        full += p + ".";
      }
      std::printf("  %-48s %s\n", (full + key).c_str(), value.c_str());
    } else if (line.find('}') != std::string::npos && !path.empty()) {
      path.pop_back();
    }
  }
}

int run_host(const Scenario& scenario, const DdsOptions& dds, HostOptions options, TimeMode mode, const std::string& out_dir,
             RunStats* stats_out) {
  ComponentRegistry registry;
  register_builtin_components(registry);
  auto bus = make_dds_bus(dds);
  Notifier notifier;
  RunContext run;
  run.scenario = &scenario;
  run.bus = bus.get();
  run.notifier = &notifier;
  run.mode = mode;
  run.output_dir = out_dir;
  run.share_dir = share_dir();
  run.single_process = options.single_process;
  options.stop = &g_stop;
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
  if (stats_out != nullptr) {
    *stats_out = stats;
  }
  return 0;
}

/// Runs sim/report/report.py on a run's output directory; returns its exit code.
int make_plots(const std::string& out_dir) {
  const std::string script = share_dir() + "/sim/report/report.py";
  const std::string command = "python3 '" + script + "' '" + out_dir + "'";
  std::fflush(stdout);  // our buffered output first, then the child's
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

std::uint64_t make_run_id() {
  return (static_cast<std::uint64_t>(std::time(nullptr)) << 20) ^ static_cast<std::uint64_t>(getpid());
}

}  // namespace
}  // namespace robodds

int main(int argc, char** argv) {
  using namespace robodds;
  install_signal_handlers();
  CLI::App app{"robodds: deterministic DDS component system (run scenarios, host components, inspect topics)"};
  app.require_subcommand(1);
  std::string log_level = env_or("ROBODDS_LOG", "info");
  app.add_option("--log", log_level, "log level: debug, info, warn, error");

  // run
  auto* run_cmd = app.add_subcommand("run", "run a scenario (lockstep, co-located by default)");
  std::string scenario_file;
  std::string deploy = "colocated";
  std::string out_dir;
  std::uint64_t seed = 0;
  bool seed_given = false;
  bool realtime = false;
  DdsFlags run_dds;
  TimeoutFlags run_timeouts;
  run_cmd->add_option("scenario", scenario_file, "scenario YAML file")->required();
  run_cmd->add_option("--deploy", deploy, "colocated (one process) or processes (one per group)")
      ->check(CLI::IsMember({"colocated", "processes"}));
  run_cmd->add_option("--out", out_dir, "output directory (default out/<scenario name>)");
  run_cmd->add_option("--seed", seed, "override the scenario seed")->each([&](const std::string&) { seed_given = true; });
  run_cmd->add_flag("--realtime", realtime, "wall-clock timers instead of lockstep");
  double duration_s = 0.0;
  run_cmd->add_option("--duration", duration_s, "override the scenario duration (s)")->check(CLI::PositiveNumber);
  run_dds.add_to(run_cmd);
  run_timeouts.add_to(run_cmd);

  // host
  auto* host_cmd = app.add_subcommand("host", "run some of a scenario's components in this process");
  std::string host_scenario;
  std::string host_group;
  std::vector<std::string> host_components;
  std::string host_params;
  std::string host_member;
  std::uint64_t host_run_id = 1;
  std::string host_out;
  bool host_realtime = false;
  bool host_coordinate = false;
  std::int64_t host_epoch_ns = 0;
  std::uint64_t host_seed = 0;
  bool host_seed_given = false;
  DdsFlags host_dds;
  TimeoutFlags host_timeouts;
  host_cmd->add_option("--scenario", host_scenario, "scenario YAML (robots, step, parameters, groups)")->required();
  host_cmd->add_option("--group", host_group, "run the components of this group");
  host_cmd->add_option("--components", host_components, "run these component instances (comma separated)")->delimiter(',');
  host_cmd->add_option("--params", host_params, "YAML map component -> parameter overrides (on top of the scenario's)");
  host_cmd->add_option("--member", host_member, "name in acknowledgements (default: the group)");
  host_cmd->add_option("--run-id", host_run_id, "run id given by robodds run");
  host_cmd->add_option("--out", host_out, "output directory for the evaluator");
  host_cmd->add_flag("--realtime", host_realtime, "wall-clock timers instead of lockstep");
  host_cmd->add_flag("--coordinate", host_coordinate, "also publish ticks (a standalone lockstep host)");
  std::vector<std::string> host_members;
  host_cmd->add_option("--members", host_members,
                       "with --coordinate: groups whose acknowledgements to wait for (default: this host's group, "
                       "or every group of the scenario when the host runs no component)")
      ->delimiter(',');
  host_cmd->add_option("--epoch-ns", host_epoch_ns, "real time: wall clock (ns) of step 0");
  double host_duration_s = 0.0;
  host_cmd->add_option("--duration", host_duration_s, "override the scenario duration (s)")->check(CLI::PositiveNumber);
  host_cmd->add_option("--seed", host_seed, "override the scenario seed")->each([&](const std::string&) { host_seed_given = true; });
  host_dds.add_to(host_cmd);
  host_timeouts.add_to(host_cmd);

  // topics / echo / components
  auto* topics_cmd = app.add_subcommand("topics", "list the topics seen on the domain with type and QoS");
  double topics_seconds = 2.0;
  DdsFlags topics_dds;
  topics_cmd->add_option("--duration", topics_seconds, "s to listen");
  topics_dds.add_to(topics_cmd);
  auto* echo_cmd = app.add_subcommand("echo", "print samples of a topic");
  std::string echo_topic;
  int echo_count = 0;
  double echo_timeout = 0.0;
  DdsFlags echo_dds;
  echo_cmd->add_option("topic", echo_topic, "topic name, e.g. plant/state")->required();
  echo_cmd->add_option("--count", echo_count, "exit after this many samples (0 = until Ctrl-C)");
  echo_cmd->add_option("--timeout", echo_timeout, "s; fail if no sample arrives in time (0 = wait forever)");
  echo_dds.add_to(echo_cmd);
  auto* list_cmd = app.add_subcommand("components", "list the registered component types");
  auto* report_cmd = app.add_subcommand("report", "(re)generate the plots of a run from its CSVs");
  std::string report_dir;
  report_cmd->add_option("out_dir", report_dir, "output directory of a run")->required();
  bool no_plots = false;
  run_cmd->add_flag("--no-plots", no_plots, "do not draw the PNG plots at the end");

  DeployCommand deploy_cmd(app);  // deploy compose: docker-compose file from a scenario

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help and friends: CLI11 prints and exits 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Bad command line = bad input: one line and exit code 2, like every other ConfigError.
    std::fprintf(stderr, "robodds: error: %s (see robodds %s--help)\n", e.what(),
                 app.get_subcommands().empty() ? "" : (app.get_subcommands().front()->get_name() + " ").c_str());
    return 2;
  }

  try {
    log::set_level(log::parse_level(log_level));
    if (run_cmd->parsed()) {
      Scenario scenario = load_scenario(scenario_file);
      if (seed_given) {
        scenario.seed = seed;
      }
      if (duration_s > 0.0) {
        scenario.duration_s = duration_s;
      }
      if (out_dir.empty()) {
        out_dir = "out/" + scenario.name;
      }
      std::system(("mkdir -p '" + out_dir + "'").c_str());
      const TimeMode mode = realtime ? TimeMode::kRealtime : TimeMode::kLockstep;
      const DdsOptions dds = run_dds.resolve("robodds-run");
      RunStats stats;
      std::fflush(stdout);
      std::printf("robodds run %s: %s, %s, %llu steps of %g s, seed %llu\n", scenario.name.c_str(), deploy.c_str(),
                  realtime ? "real time" : "lockstep", static_cast<unsigned long long>(scenario.last_step() + 1),
                  scenario.step_s, static_cast<unsigned long long>(scenario.seed));
      if (deploy == "colocated") {
        HostOptions options;
        options.member = "colocated";
        options.components = all_components(scenario);
        options.coordinator = true;
        options.members = {"colocated"};
        options.single_process = true;
        run_timeouts.apply_to(options);
        options.progress = show_progress;
        run_host(scenario, dds, options, mode, out_dir, &stats);
      } else {
        // Validate everything in this process first so that bad input fails before spawning.
        {
          ComponentRegistry registry;
          register_builtin_components(registry);
          for (const ComponentSpec& c : scenario.components) {
            registry.get(c.type);
          }
        }
        const std::uint64_t run_id = make_run_id();
        timespec ts{};
        clock_gettime(CLOCK_REALTIME, &ts);
        const std::int64_t epoch_ns = (static_cast<std::int64_t>(ts.tv_sec) + 2) * 1000000000LL;  // start in 2 s
        ProcessGroup children;
        for (const GroupSpec& group : scenario.groups) {
          std::vector<std::string> args = {self_exe(), "--log", log_level, "host", "--scenario", scenario_file, "--group",
                                           group.name, "--run-id", std::to_string(run_id), "--out", out_dir,
                                           "--domain", std::to_string(dds.domain_id), "--participant-profile",
                                           dds.participant_profile, "--seed", std::to_string(scenario.seed), "--duration", std::to_string(scenario.duration_s),
                                           "--input-timeout", std::to_string(run_timeouts.input_timeout_s),
                                           "--start-timeout", std::to_string(run_timeouts.start_timeout_s)};
          for (const std::string& q : dds.qos_files) {
            args.push_back("--qos");
            args.push_back(q);
          }
          if (realtime) {
            args.push_back("--realtime");
            args.push_back("--epoch-ns");
            args.push_back(std::to_string(epoch_ns));
          }
          children.spawn(group.name, args);
        }
        if (realtime) {
          const auto start = std::chrono::steady_clock::now();
          const double limit = 2.0 + scenario.duration_s + run_timeouts.start_timeout_s;
          while (children.reap_finished() > 0) {
            if (g_stop) {
              throw RunError("interrupted by a signal");
            }
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limit) {
              throw RunError("real-time run did not finish within " + std::to_string(limit) + " s");
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
          stats.steps = scenario.last_step() + 1;
          stats.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        } else {
          HostOptions options;
          options.coordinator = true;
          options.members = all_members(scenario);
          options.run_id = run_id;
          run_timeouts.apply_to(options);
          options.progress = show_progress;
          options.poll = [&children] { children.check_alive(); };
          run_host(scenario, dds, options, mode, out_dir, &stats);
          children.wait_all(30.0);
        }
      }
      append_run_section(out_dir, deploy, realtime ? "realtime" : "lockstep", stats);
      std::printf("done: %llu ticks in %.3f s (%.0f ticks/s)\n", static_cast<unsigned long long>(stats.steps), stats.wall_s,
                  stats.wall_s > 0 ? static_cast<double>(stats.steps) / stats.wall_s : 0.0);
      print_summary(out_dir);
      if (!no_plots && make_plots(out_dir) != 0) {
        log::warn("run", "plots were not drawn (python3 with matplotlib missing?); the CSVs and summary.json are complete");
      }
      std::printf("results: %s\n", out_dir.c_str());
      return 0;
    }
    if (host_cmd->parsed()) {
      Scenario scenario = load_scenario(host_scenario);
      if (host_seed_given) {
        scenario.seed = host_seed;
      }
      if (host_duration_s > 0.0) {
        scenario.duration_s = host_duration_s;
      }
      if (!host_params.empty()) {
        const FlatParams overrides = load_param_file(host_params);
        for (const auto& [key, entry] : overrides) {
          const std::size_t dot = key.find('.');
          const std::string component = key.substr(0, dot);
          bool found = false;
          for (ComponentSpec& c : scenario.components) {
            if (c.name == component && dot != std::string::npos) {
              c.overrides[key.substr(dot + 1)] = entry;
              found = true;
            }
          }
          if (!found) {
            throw ConfigError(located(host_params, key, "expected <component>.<parameter> of a scenario component"));
          }
        }
      }
      HostOptions options;
      if (!host_group.empty()) {
        options.components = scenario.group(host_group).components;
        options.member = host_group;
      } else if (!host_components.empty()) {
        for (const std::string& c : host_components) {
          scenario.component(c);
        }
        options.components = host_components;
        options.member = "host";
      } else if (host_coordinate) {
        options.member = "coordinator";  // a coordinator alone (e.g. on its own machine): ticks only
      } else {
        throw ConfigError("robodds host: give --group or --components (or --coordinate alone)");
      }
      if (!host_member.empty()) {
        options.member = host_member;
      }
      options.run_id = host_run_id;
      options.coordinator = host_coordinate;
      options.members = !host_members.empty()        ? host_members
                        : options.components.empty() ? all_members(scenario)
                                                     : std::vector<std::string>{options.member};
      options.realtime_epoch_ns = host_epoch_ns;
      host_timeouts.apply_to(options);
      return run_host(scenario, host_dds.resolve("robodds-" + options.member), options,
                      host_realtime ? TimeMode::kRealtime : TimeMode::kLockstep, host_out, nullptr);
    }
    if (topics_cmd->parsed()) {
      const auto topics = discover_topics(topics_dds.resolve("robodds-topics"), topics_seconds);
      std::printf("%-24s %-36s %3s %3s  %-26s %s\n", "topic", "type", "W", "R", "writer QoS", "reader QoS");
      for (const DiscoveredTopic& t : topics) {
        std::printf("%-24s %-36s %3d %3d  %-26s %s\n", t.name.c_str(), t.type_name.c_str(), t.writers, t.readers,
                    t.writer_qos.c_str(), t.reader_qos.c_str());
      }
      if (topics.empty()) {
        std::printf("(no topics seen in %.1f s)\n", topics_seconds);
      }
      return 0;
    }
    if (echo_cmd->parsed()) {
      const TopicInfo& info = topic_info(echo_topic);
      // Declared before the bus so that they outlive it: the bus's reader callback uses them.
      Notifier notifier;
      std::mutex mutex;
      std::vector<std::string> lines;
      auto bus = make_dds_bus(echo_dds.resolve("robodds-echo"));
      idl::dispatch_type(info.type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        // Missions are transient local: read them with the mission profile to get the last one.
        bus->reader(echo_topic, info.type_name, info.qos_class == "mission" ? "mission" : kMonitorProfile,
                    [&](const void* sample) {
                      const Msg& m = *static_cast<const Msg*>(sample);
                      std::lock_guard<std::mutex> lock(mutex);
                      lines.push_back("--- " + echo_topic + " (" + idl::instance_label(m) + ")\n" + to_text(m));
                      notifier.notify();
                    },
                    [&](const std::string& e) { log::warn("echo", echo_topic + ": " + e); });
      });
      bus->start();
      int printed = 0;
      const auto start = std::chrono::steady_clock::now();
      while (!g_stop && (echo_count == 0 || printed < echo_count)) {
        const auto seen = notifier.generation();
        std::vector<std::string> batch;
        {
          std::lock_guard<std::mutex> lock(mutex);
          batch.swap(lines);
        }
        for (const std::string& text : batch) {
          if (echo_count != 0 && printed >= echo_count) {
            break;
          }
          std::fputs(text.c_str(), stdout);
          ++printed;
        }
        std::fflush(stdout);
        if (printed == 0 && echo_timeout > 0 &&
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > echo_timeout) {
          throw RunError("no sample on " + echo_topic + " within " + std::to_string(echo_timeout) + " s");
        }
        notifier.wait(seen, std::chrono::milliseconds(100));
      }
      return 0;
    }
    if (deploy_cmd.parsed()) {
      return deploy_cmd.run(share_dir());
    }
    if (report_cmd->parsed()) {
      return make_plots(report_dir);
    }
    if (list_cmd->parsed()) {
      ComponentRegistry registry;
      register_builtin_components(registry);
      for (const ComponentType& type : registry.types()) {
        std::printf("%-22s %s\n%-22s params: %s\n", type.name.c_str(), type.description.c_str(), "", type.defaults_file.c_str());
      }
      return 0;
    }
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return 2;
  } catch (const RunError& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return g_stop ? 130 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
