#include "tools/robodds/compose.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <vector>

#include "common/did_you_mean.hpp"
#include "runtime/base/realtime_priority.hpp"
#include "runtime/dds/security_files.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/host_args.hpp"
#include "runtime/bus/qos_profiles.hpp"

namespace robodds {
namespace {

using C = ComposeConstants;

/// The run id is the same for every service of a run; compose takes it from the environment.
const ArgPlaceholders kRunIdFromEnvironment = {{"--run-id", "${ROBODDS_RUN_ID:-1}"}};

/// A YAML scalar: plain when unambiguous, otherwise double-quoted. Quoting anything with ':',
/// '$', spaces or a number/boolean look keeps compose from reading a string as another type.
std::string scalar(const std::string& text) {
  static const std::set<std::string> kReserved = {"y", "n", "yes", "no", "true", "false", "on", "off", "null", "~"};
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool safe_chars = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '_' || c == '.' || c == '/' || c == '-';
  });
  const auto starts_with = [&text](const char* prefix) { return text.rfind(prefix, 0) == 0; };
  const unsigned char first = static_cast<unsigned char>(text.empty() ? ' ' : text.front());
  // Not a digit, '.' or '-' first: ".5", ".inf" or "-1" would read as numbers.
  const bool plain_start = std::isalpha(first) != 0 || first == '/' || first == '_' || starts_with("./") || starts_with("../") ||
                           (starts_with("--") && text.size() > 2 && std::isalpha(static_cast<unsigned char>(text[2])) != 0);
  if (safe_chars && plain_start && kReserved.count(lower) == 0) {
    return text;
  }
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
    }
    quoted += c;
  }
  return quoted + "\"";
}

std::string flow_list(const std::vector<std::string>& items) {
  std::string text = "[";
  for (std::size_t i = 0; i < items.size(); ++i) {
    text += (i == 0 ? "" : ", ") + scalar(items[i]);
  }
  return text + "]";
}

/// Compose service names double as DNS names on the network: keep to what compose accepts.
bool valid_service_name(const std::string& name) {
  return !name.empty() && std::isalnum(static_cast<unsigned char>(name.front())) != 0 &&
         std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isalnum(c) != 0 || c == '_' || c == '.' || c == '-'; });
}

struct Service {
  std::string name;
  std::string comment;
  std::vector<std::string> entrypoint;  // empty: the image's (robodds host)
  std::vector<std::string> command;
  std::vector<std::string> volumes;
  std::vector<std::string> depends_on;
  bool init = false;
  bool uses_robodds_env = true;
  bool real_time_priority = false;  // cap_add and ulimits of --rt-priority
};

class ComposeWriter {
 public:
  ComposeWriter(const Scenario& scenario, const ComposeOptions& options) : scenario_(scenario), options_(options) {}

  std::string write() {
    validate();
    header();
    out_ << "services:\n";
    bool first = true;
    for (const Service& service : services()) {
      write_service(service, first);
      first = false;
    }
    footer();
    return out_.str();
  }

 private:
  bool bridge() const { return options_.network == ComposeNetwork::kBridge; }
  bool server() const { return options_.discovery == ComposeDiscovery::kServer; }
  bool secure() const { return !options_.security_dir.empty(); }
  /// The service's own identity folder, read-only, where --security kSecurityDir finds it.
  std::string identity_mount(const std::string& identity) const {
    return options_.security_dir + "/" + identity + ":" + C::kSecurityDir + "/" + identity + ":ro";
  }
  std::string in_share(const std::string& repo_path) const { return std::string(C::kShareDir) + "/" + repo_path; }
  std::string from_repo(const std::string& repo_path) const { return options_.repo_dir + "/" + repo_path; }
  std::string read_only_mount(const std::string& repo_path) const {
    return from_repo(repo_path) + ":" + in_share(repo_path) + ":ro";
  }
  std::string out_dir() const { return std::string(C::kShareDir) + "/out/" + scenario_.name; }

  void validate() const {
    if (options_.scenario_path.empty() || options_.scenario_path.find('$') != std::string::npos) {
      throw ConfigError(located(scenario_.file, "", "scenario path '" + options_.scenario_path +
                                                        "' cannot be mounted (empty or contains '$')"));
    }
    for (const ComponentSpec& component : scenario_.components) {
      const std::vector<std::string>& types = options_.component_types;
      if (std::find(types.begin(), types.end(), component.type) == types.end()) {
        std::string known;
        for (const std::string& type : types) {
          known += (known.empty() ? "" : ", ") + type;
        }
        throw ConfigError(located(scenario_.file, "components." + component.name,
                                  "unknown component type '" + component.type + "'" + did_you_mean(component.type, types) +
                                      " (known: " + known + ")"));
      }
    }
    if (!valid_service_name(scenario_.name)) {
      throw ConfigError(located(scenario_.file, "name", "scenario name '" + scenario_.name +
                                                            "' is not usable as a compose project and output directory name (letters, digits, '_', '.', '-')"));
    }
    if (secure() && server()) {
      throw ConfigError(located(scenario_.file, "", "--security goes with --discovery multicast: the Fast DDS Discovery Server "
                                                    "would need a DDS Security identity of its own, which `robodds security init` does not make"));
    }
    if (secure() && options_.security_dir.find_first_of("$:") != std::string::npos) {
      throw ConfigError(located(scenario_.file, "", "security directory '" + options_.security_dir +
                                                    "' cannot be mounted (contains '$' or ':')"));
    }
    for (const GroupSpec& group : scenario_.groups) {
      if (!valid_service_name(group.name)) {
        throw ConfigError(located(scenario_.file, "groups." + group.name,
                                  "group name '" + group.name + "' is not a valid compose service name (letters, digits, '_', '.', '-')"));
      }
      if (group.name == C::kCoordinatorService || (server() && group.name == C::kDiscoveryService)) {
        throw ConfigError(located(scenario_.file, "groups." + group.name,
                                  "group name '" + group.name + "' is reserved for the generated " + group.name + " service"));
      }
    }
  }

  /// Bridge + Discovery Server: the clients find the server by its service name through
  /// ROS_DISCOVERY_SERVER (Fast DDS resolves the DNS name; its XML locators take no names), over the
  /// UDP-only profile, so the network needs no fixed subnet or address: docker picks the subnet and
  /// two such deployments run side by side on one engine.
  bool server_by_name() const { return server() && bridge(); }

  std::string participant_profile() const {
    if (server() && !bridge()) {
      return kDiscoveryClientParticipantProfile;
    }
    // Bridge: containers do not share /dev/shm, so shared memory can only fail between them
    // ("topics visible, no data" when Fast DDS takes a peer for local): UDP only.
    // Host network: the default SHM + UDP profile, made to work by ipc: host.
    return bridge() ? kUdpOnlyParticipantProfile : kDefaultParticipantProfile;
  }

  /// The second QoS file (robodds_qos.xml is always loaded first, from the share dir). On the host
  /// network the server listens on 127.0.0.1, which the shipped client profile names.
  std::string qos_file_repo_path() const {
    return server() && !bridge() ? "deploy/qos/discovery_client.xml" : "deploy/qos/robodds_qos.xml";
  }

  /// Where the server listens: every address of its container on the bridge (the clients reach it
  /// by name), loopback on the host network.
  std::string listen_address() const { return bridge() ? "0.0.0.0" : "127.0.0.1"; }
  std::string server_locator() const {
    return (bridge() ? std::string(C::kDiscoveryService) : std::string("127.0.0.1")) + ":" + std::to_string(C::kDiscoveryPort);
  }

  void header() {
    const std::string scenario_arg = options_.scenario_path;
    std::string variant_args;
    if (server()) {
      variant_args += " --discovery server";
    }
    if (!bridge()) {
      variant_args += " --network host";
    }
    if (secure()) {
      variant_args += " --security " + options_.security_dir;
    }
    if (options_.rt_priority) {
      variant_args += " --rt-priority " + std::to_string(*options_.rt_priority);
    }
    const std::string compose = "docker-compose -p " + scenario_.name + " -f FILE";
    out_ << "# Generated by `robodds deploy compose " << scenario_arg << variant_args << "`\n"
         << "# (deploy/compose/regenerate.sh); do not edit. Scenario '" << scenario_.name << "': one container per\n"
         << "# deployment group, plus the lockstep coordinator" << (server() ? " and a Fast DDS Discovery Server" : "") << ".\n"
         << "# Discovery: " << (server() ? "Discovery Server at " + server_locator() : std::string("multicast (SIMPLE)"))
         << "; network: " << (bridge() ? std::string("user-defined bridge '") + C::kNetwork + "'" : std::string("host")) << ";\n"
         << "# participant profile: " << participant_profile() << ".\n";
    if (secure()) {
      out_ << "# DDS Security (--security " << options_.security_dir << "): each container mounts only its own identity\n"
           << "# DIR/<group>/ (the coordinator DIR/coordinator/), read-only; its files must be readable by uid 10001.\n";
    }
    if (options_.rt_priority) {
      out_ << "# --rt-priority " << *options_.rt_priority << ": every robodds service runs SCHED_FIFO with locked memory. The limits\n"
           << "# (ulimits rtprio 99, memlock unlimited) let its user (uid 10001) do so; cap_add SYS_NICE, IPC_LOCK\n"
           << "# serve an image run as root.\n";
    }
    if (bridge()) {
      out_ << "# UDP only: containers do not share /dev/shm, so Fast DDS shared memory between them can\n"
           << "# only fail (\"topics visible, no data\").\n";
    } else {
      out_ << "# ipc: host is required: on the host network every container has the host's addresses, so\n"
           << "# Fast DDS takes its peers for local processes and uses shared memory, whose segments live\n"
           << "# in /dev/shm. That is private per container unless ipc: host; without it topics match but\n"
           << "# no data arrives.\n";
    }
    out_ << "# Run from the repository root, FILE = this file (docs/deployment.md):\n"
         << "#   " << compose << " build     # once: the image\n"
         << "#   " << compose << " up -d\n"
         << "#   docker wait $(" << compose << " ps -q coordinator)   # exit code of the run, 0 = completed\n"
         << "#   " << compose << " run -T --rm --no-deps --entrypoint tar " << results_service()
         << " -C " << C::kShareDir << "/out -cf - " << scenario_.name << " | tar -xf - -C out/\n"
         << "#   " << compose << " down -v\n"
         << "# Results: volume <project>_results, folder " << out_dir() << " (the scenario's name, whatever -p is).\n"
         << "# ROBODDS_DOMAIN_ID, ROBODDS_RUN_ID and ROBODDS_IMAGE (defaults 0, 1, robodds:latest) are taken\n"
         << "# from the environment.\n";
  }

  /// A group service (it mounts the results volume) to read the results through.
  std::string results_service() const { return scenario_.groups.empty() ? std::string("GROUP") : scenario_.groups.back().name; }

  std::vector<Service> services() const {
    std::vector<Service> result;
    const std::string scenario_in_image = in_share(options_.scenario_path);
    const std::vector<std::string> common_mounts = {read_only_mount("deploy/qos"), read_only_mount(options_.scenario_path)};
    const std::vector<std::string> after_server = server() ? std::vector<std::string>{C::kDiscoveryService} : std::vector<std::string>{};

    if (server()) {
      Service discovery;
      discovery.name = C::kDiscoveryService;
      discovery.comment = server_by_name() ? "Fast DDS Discovery Server (server id 0, the first of ROS_DISCOVERY_SERVER); every participant is its client"
                                           : "Fast DDS Discovery Server (server id 0 = the prefix in the client profile); every participant is its client";
      discovery.entrypoint = {"fastdds", "discovery", "-i", "0", "-l", listen_address(), "-p", std::to_string(C::kDiscoveryPort)};
      discovery.init = true;  // `fastdds` is a Python wrapper: tini forwards SIGTERM on `docker-compose down`
      discovery.uses_robodds_env = false;
      result.push_back(discovery);
    }

    Service coordinator;
    coordinator.name = C::kCoordinatorService;
    coordinator.comment = "lockstep coordinator: ticks sim/clock, waits for every group's sim/step_done; exits 0 when the run completes";
    HostArgs coordinator_args;
    coordinator_args.scenario = scenario_in_image;
    coordinator_args.coordinate = true;
    coordinator_args.rt_priority = options_.rt_priority;
    if (secure()) {
      coordinator_args.dds.security_dir = C::kSecurityDir;
    }
    coordinator.command = to_argv(coordinator_args, kRunIdFromEnvironment);
    coordinator.volumes = common_mounts;
    if (secure()) {
      coordinator.volumes.push_back(identity_mount(kCoordinatorIdentity));
    }
    coordinator.depends_on = after_server;
    coordinator.real_time_priority = options_.rt_priority.has_value();
    result.push_back(coordinator);

    for (const GroupSpec& group : scenario_.groups) {
      Service host;
      host.name = group.name;
      std::string members;
      for (const std::string& name : group.components) {
        members += (members.empty() ? "" : ", ") + name + " (" + scenario_.component(name).type + ")";
      }
      host.comment = "group " + group.name + ": " + members;
      HostArgs host_args;
      host_args.scenario = scenario_in_image;
      host_args.group = group.name;
      host_args.out = out_dir();
      host_args.rt_priority = options_.rt_priority;
      if (secure()) {
        host_args.dds.security_dir = C::kSecurityDir;
      }
      host.command = to_argv(host_args, kRunIdFromEnvironment);
      host.volumes = common_mounts;
      if (secure()) {
        host.volumes.push_back(identity_mount(group.name));  // its own identity only
      }
      // Every host gets --out, as with `robodds run --deploy processes`; the evaluator writes there.
      host.volumes.push_back("results:" + std::string(C::kShareDir) + "/out");
      host.depends_on = after_server;
      host.real_time_priority = options_.rt_priority.has_value();
      result.push_back(host);
    }
    return result;
  }

  /// Only the first service builds the image (`docker-compose build` would otherwise build the
  /// same image once per service); the others name it.
  void write_service(const Service& s, bool builds_image) {
    out_ << "  # " << s.comment << "\n"
         << "  " << s.name << ":\n"
         << "    image: " << scalar(C::kImage) << "\n";
    if (builds_image) {
      out_ << "    build:  # the one image of every service\n"
           << "      context: " << scalar(options_.repo_dir) << "\n"
           << "      dockerfile: " << scalar(C::kDockerfile) << "\n";
    }
    if (!s.entrypoint.empty()) {
      out_ << "    entrypoint: " << flow_list(s.entrypoint) << "\n";
    }
    if (!s.command.empty()) {
      out_ << "    command: " << flow_list(s.command) << "\n";
    }
    if (s.init) {
      out_ << "    init: true\n";
    }
    if (s.real_time_priority) {
      // What --rt-priority needs inside a container (docker drops SYS_NICE and IPC_LOCK by default).
      out_ << "    cap_add: [SYS_NICE, IPC_LOCK]\n"
           << "    ulimits:\n"
           << "      rtprio: " << kMaxRtPriority << "\n"
           << "      memlock: -1  # unlimited: mlockall(MCL_FUTURE) counts every later allocation\n";
    }
    if (s.uses_robodds_env) {
      out_ << "    environment:\n"
           << "      ROBODDS_DOMAIN_ID: " << scalar("${ROBODDS_DOMAIN_ID:-0}") << "\n"
           << "      ROBODDS_QOS_FILE: " << scalar(in_share(qos_file_repo_path())) << "\n"
           << "      ROBODDS_PARTICIPANT_PROFILE: " << scalar(participant_profile()) << "\n";
      if (server_by_name()) {
        out_ << "      ROS_DISCOVERY_SERVER: " << scalar(server_locator()) << "  # the discovery service, by name\n";
      }
    }
    if (!s.volumes.empty()) {
      out_ << "    volumes:\n";
      for (const std::string& v : s.volumes) {
        out_ << "      - " << scalar(v) << "\n";
      }
    }
    if (!s.depends_on.empty()) {
      out_ << "    depends_on: " << flow_list(s.depends_on) << "\n";
    }
    if (bridge()) {
      out_ << "    networks:\n"
           << "      - " << C::kNetwork << "\n";
    } else {
      // Host network: every container has the host's addresses, so Fast DDS takes its peers
      // for local processes and offers shared memory. Its segments live in /dev/shm, which is
      // private per container unless ipc: host: without it topics match but no data arrives.
      out_ << "    network_mode: host\n"
           << "    ipc: host  # share /dev/shm: Fast DDS shared memory between the containers (see the top)\n";
    }
  }

  void footer() {
    if (bridge()) {
      out_ << "networks:\n"
           << "  " << C::kNetwork << ":\n"
           << "    driver: bridge  # subnet chosen by docker: nothing here names an address\n";
    }
    out_ << "volumes:\n"
         << "  results: {}\n";
  }

  const Scenario& scenario_;
  const ComposeOptions& options_;
  std::ostringstream out_;
};

}  // namespace

std::string generate_compose(const Scenario& scenario, const ComposeOptions& options) {
  return ComposeWriter(scenario, options).write();
}

const char* to_string(ComposeDiscovery discovery) {
  return discovery == ComposeDiscovery::kServer ? "server" : "multicast";
}

const char* to_string(ComposeNetwork network) { return network == ComposeNetwork::kHost ? "host" : "bridge"; }

}  // namespace robodds
