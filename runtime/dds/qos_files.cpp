#include "runtime/dds/qos_files.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastrtps/attributes/ParticipantAttributes.h>
#include <fastrtps/attributes/PublisherAttributes.h>
#include <fastrtps/attributes/SubscriberAttributes.h>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <netdb.h>
#include <arpa/inet.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "runtime/dds/security_files.hpp"
#include "runtime/dds/text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

/// Collects Fast DDS log entries so a rejected XML file can be reported in one line.
class CapturingConsumer : public dds::LogConsumer {
 public:
  void Consume(const dds::Log::Entry& entry) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (echo_) {  // $ROBODDS_FASTDDS_LOG: Fast DDS's own warnings and errors on stderr (debugging)
      std::fprintf(stderr, "[fastdds %s] %s\n", entry.kind == dds::Log::Kind::Error ? "error" : "warning", entry.message.c_str());
    }
    if (entry.kind == dds::Log::Kind::Error) {
      messages_.push_back(entry.message);
    }
  }
  std::vector<std::string> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::move(messages_);
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> messages_;
  const bool echo_ = std::getenv("ROBODDS_FASTDDS_LOG") != nullptr;
};

CapturingConsumer* install_log_consumer() {
  static CapturingConsumer* consumer = [] {
    auto owned = std::make_unique<CapturingConsumer>();
    CapturingConsumer* raw = owned.get();
    dds::Log::ClearConsumers();
    dds::Log::RegisterConsumer(std::move(owned));
    dds::Log::SetVerbosity(std::getenv("ROBODDS_FASTDDS_LOG") != nullptr ? dds::Log::Kind::Warning : dds::Log::Kind::Error);
    return raw;
  }();
  return consumer;
}

/// The loaded file that defines `<kind profile_name="name">` (for error messages), else `fallback`.
std::string file_defining(const std::vector<std::string>& files, const std::string& name, const std::string& fallback) {
  for (const std::string& file : files) {
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("profile_name=\"" + name + "\"") != std::string::npos) {
      return file;
    }
  }
  return fallback;
}

/// Fast DDS 2.9 parses a discovery-server locator with port 0, a port above 65535 (silently
/// truncated) or address 0.0.0.0 and then never reaches the server: discovery just never
/// happens. Reject such a profile at start-up instead, naming the file and the element.
void check_discovery_servers(const dds::DomainParticipantQos& qos, const std::string& profile, const std::string& file) {
  const auto& config = qos.wire_protocol().builtin.discovery_config;
  const std::string where = "participant profile '" + profile + "': discoveryServersList";
  const bool client = config.discoveryProtocol == rtps::DiscoveryProtocol_t::CLIENT ||
                      config.discoveryProtocol == rtps::DiscoveryProtocol_t::SUPER_CLIENT;
  if (client && config.m_DiscoveryServers.empty()) {
    throw ConfigError(located(file, where, "a discovery CLIENT needs at least one <RemoteServer>"));
  }
  for (const auto& server : config.m_DiscoveryServers) {
    const std::string element = where + ": RemoteServer " + guid_prefix_text(server.guidPrefix);
    if (server.metatrafficUnicastLocatorList.empty() && server.metatrafficMulticastLocatorList.empty()) {
      throw ConfigError(located(file, element, "has no locator: add a <metatrafficUnicastLocatorList> with the server's address and port"));
    }
    for (const auto& locator : server.metatrafficUnicastLocatorList) {
      const std::string address = rtps::IPLocator::ip_to_string(locator);
      if (locator.port == 0 || locator.port > 65535) {
        throw ConfigError(located(file, element + ": locator " + address,
                                  "port " + std::to_string(locator.port) + " is not a valid port (1-65535)"));
      }
      if (rtps::IPLocator::isAny(locator)) {
        throw ConfigError(located(file, element + ": locator " + address + ":" + std::to_string(locator.port),
                                  "address " + address + " is not a server address (give the server's IP)"));
      }
    }
  }
}

/// The IPv4 address of `host` (a dotted address or a name): ConfigError naming the option if it
/// does not resolve.
std::string ipv4_of(const DiscoveryServer& server) {
  in_addr parsed{};
  if (inet_pton(AF_INET, server.host.c_str(), &parsed) == 1) {
    return server.host;
  }
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int rc = getaddrinfo(server.host.c_str(), nullptr, &hints, &found);
  if (rc != 0 || found == nullptr) {
    throw ConfigError("--discovery-server: cannot resolve '" + server.host + "' to an IPv4 address (" + gai_strerror(rc) + ")");
  }
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr, text, sizeof text);
  freeaddrinfo(found);
  return text;
}

/// Turns the participant into a Discovery Server CLIENT of `servers` (server id = position, the
/// GUID prefix Fast DDS gives a server started with that id).
void make_discovery_client(dds::DomainParticipantQos& qos, const std::vector<DiscoveryServer>& servers) {
  auto& config = qos.wire_protocol().builtin.discovery_config;
  config.discoveryProtocol = rtps::DiscoveryProtocol_t::CLIENT;
  config.m_DiscoveryServers.clear();
  for (std::size_t id = 0; id < servers.size(); ++id) {
    rtps::RemoteServerAttributes server;
    eprosima::fastdds::rtps::get_server_client_default_guidPrefix(static_cast<int>(id), server.guidPrefix);
    rtps::Locator_t locator;
    rtps::IPLocator::setIPv4(locator, ipv4_of(servers[id]));
    locator.port = static_cast<std::uint32_t>(servers[id].port);
    server.metatrafficUnicastLocatorList.push_back(locator);
    config.m_DiscoveryServers.push_back(server);
  }
}

/// Whether the loaded QoS files define `profile` (asks Fast DDS's profile store; no participant needed).
bool profile_defined(const QosProfileRef& profile) {
  using eprosima::fastrtps::xmlparser::XMLP_ret;
  using eprosima::fastrtps::xmlparser::XMLProfileManager;
  if (profile.element == "participant") {
    eprosima::fastrtps::ParticipantAttributes attributes;
    return XMLProfileManager::fillParticipantAttributes(profile.name, attributes, false) == XMLP_ret::XML_OK;
  }
  if (profile.element == "data_writer") {  // Fast DDS 2.9 keeps <data_writer> as a publisher profile
    eprosima::fastrtps::PublisherAttributes attributes;
    return XMLProfileManager::fillPublisherAttributes(profile.name, attributes, false) == XMLP_ret::XML_OK;
  }
  eprosima::fastrtps::SubscriberAttributes attributes;
  return XMLProfileManager::fillSubscriberAttributes(profile.name, attributes, false) == XMLP_ret::XML_OK;
}

/// The builtin plugins of Fast DDS (authentication PKI-DH, access control Permissions,
/// cryptography AES-GCM-GMAC) on the participant, with the identity's checked files; what is
/// encrypted is the governance's (tools/robodds/security_policy.cpp).
void add_security_properties(dds::DomainParticipantQos& qos, const DdsOptions& options) {
  if (options.security_identity.empty()) {
    throw ConfigError("--security " + options.security_dir + ": this process has no DDS Security identity (a host needs "
                      "--group or --coordinate alone; docs/security.md)");
  }
  const SecurityFiles files = check_security_files(options.security_dir, options.security_identity);
  auto& properties = qos.properties().properties();
  const auto add = [&properties](const std::string& name, const std::string& value) { properties.emplace_back(name, value); };
  add("dds.sec.auth.plugin", "builtin.PKI-DH");
  add("dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + files.identity_ca);
  add("dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + files.certificate);
  add("dds.sec.auth.builtin.PKI-DH.private_key", "file://" + files.private_key);
  add("dds.sec.access.plugin", "builtin.Access-Permissions");
  add("dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + files.identity_ca);
  add("dds.sec.access.builtin.Access-Permissions.governance", "file://" + files.governance);
  add("dds.sec.access.builtin.Access-Permissions.permissions", "file://" + files.permissions);
  add("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
  // Said once per participant, so a deployment's logs show that each process really runs secure
  // (tests/containers/compose_e2e.sh checks it for every container).
  log::info("security", "DDS Security on: identity '" + options.security_identity + "' (" + files.certificate +
                            "), authentication PKI-DH, access control Permissions, cryptography AES-GCM-GMAC");
}

}  // namespace

void check_qos_profiles(const DdsOptions& options) {
  load_qos_files(options.qos_files);
  // Data profiles are looked for in the first file, the participant profile in any (named: the last).
  const std::string first = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.front();
  const std::string last = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.back();
  for (const QosProfileRef& profile : required_profiles(options.participant_profile)) {
    if (!profile_defined(profile)) {
      const bool participant = profile.element == "participant";
      throw ConfigError(located(participant ? last : first, profile.element + " profile '" + profile.name + "'",
                                participant ? "not found in the loaded QoS files" : "not found"));
    }
  }
}

void load_qos_files(const std::vector<std::string>& files) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  CapturingConsumer* consumer = install_log_consumer();
  for (const std::string& file : files) {
    if (loaded.count(file) != 0) {
      continue;
    }
    if (!std::ifstream(file).good()) {
      throw ConfigError(located(file, "", "QoS profile file not found or not readable"));
    }
    consumer->take();
    const ReturnCode_t rc = dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file);
    dds::Log::Flush();
    // Fast DDS logs the real problem first, then one "Error parsing ..." line per enclosing
    // element and per later profile: the first two name the element and where it sits.
    std::string reasons;
    const std::vector<std::string> messages = consumer->take();
    for (std::size_t i = 0; i < messages.size() && i < 2; ++i) {
      reasons += (reasons.empty() ? "" : "; ") + messages[i];
    }
    if (rc != ReturnCode_t::RETCODE_OK) {
      throw ConfigError(located(file, "", "rejected by Fast DDS (2.9 XML schema): " +
                                              (reasons.empty() ? std::string("malformed XML") : reasons)));
    }
    if (!messages.empty()) {
      // Loaded "successfully" but with errors, e.g. a profile name already defined by an earlier
      // file: Fast DDS keeps the first definition and drops this one, which would silently run
      // with other QoS than the file says.
      throw ConfigError(located(file, "", "Fast DDS reported errors while loading it: " + reasons));
    }
    loaded.insert(file);
  }
}

std::string take_dds_errors() {
  CapturingConsumer* consumer = install_log_consumer();
  dds::Log::Flush();
  // Fast DDS logs the cause first, then the same cause again wrapped by each caller: keep the first.
  const std::vector<std::string> messages = consumer->take();
  if (messages.empty()) {
    return "";
  }
  std::string first = messages.front();
  while (!first.empty() && (first.back() == '\n' || first.back() == ' ')) {
    first.pop_back();
  }
  return first;
}

void apply_peer_lease(dds::DomainParticipantQos& qos) {
  rtps::DiscoverySettings& discovery = qos.wire_protocol().builtin.discovery_config;
  const rtps::DiscoverySettings defaults;
  if (discovery.leaseDuration != defaults.leaseDuration) {
    return;  // the profile set its own lease: it wins
  }
  discovery.leaseDuration = eprosima::fastrtps::Duration_t(kPeerLeaseS);
  discovery.leaseDuration_announcementperiod = eprosima::fastrtps::Duration_t(kPeerAnnouncementS);
}

void apply_writer_qos_beyond_xml(const std::string& profile, dds::DataWriterQos& qos) {
  if (profile == kLockstepProfile) {
    // Why: docs/performance.md, "Session 15" (piggyback heartbeats).
    qos.reliable_writer_qos().disable_heartbeat_piggyback = true;
  }
}

std::optional<std::size_t> kernel_receive_buffer_max() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  std::size_t bytes = 0;
  if (in >> bytes) {
    return bytes;
  }
  return std::nullopt;
}

bool grow_transport_buffers(dds::DomainParticipantQos& qos, std::size_t bytes) {
  namespace rtps_transport = eprosima::fastdds::rtps;
  const auto wanted = static_cast<uint32_t>(bytes);
  bool grew_udp = false;
  // Copies: the profile's descriptors are shared with every participant made from it.
  for (auto& transport : qos.transport().user_transports) {
    if (const auto* shm = dynamic_cast<const rtps_transport::SharedMemTransportDescriptor*>(transport.get())) {
      if (shm->segment_size() < wanted) {
        auto grown = std::make_shared<rtps_transport::SharedMemTransportDescriptor>(*shm);
        grown->segment_size(wanted);
        transport = grown;
      }
    } else if (const auto* udp = dynamic_cast<const rtps_transport::UDPv4TransportDescriptor*>(transport.get())) {
      if (udp->receiveBufferSize < wanted) {  // 0: the kernel's default
        auto grown = std::make_shared<rtps_transport::UDPv4TransportDescriptor>(*udp);
        grown->receiveBufferSize = wanted;
        transport = grown;
        grew_udp = true;
      }
    }
  }
  return grew_udp;
}

void warn_if_kernel_caps_receive_buffer(std::size_t bytes, std::optional<std::size_t> kernel_max) {
  if (!kernel_max || *kernel_max >= bytes) {
    return;
  }
  static std::once_flag once;
  std::call_once(once, [bytes, kernel_max] {
    log::warn("dds", "UDP receive buffer: this host asks for " + std::to_string(bytes) +
                         " bytes (its lockstep window and robots, runtime/launch/transport_buffers.hpp), the kernel "
                         "allows " + std::to_string(*kernel_max) +
                         " (net.core.rmem_max): between machines a full buffer drops messages and repairs slow the "
                         "run; raise it (sysctl -w net.core.rmem_max=" + std::to_string(bytes) +
                         ") on every host (local processes use shared memory and need nothing)");
  });
}

dds::DomainParticipantQos checked_participant_qos(const DdsOptions& options) {
  check_qos_profiles(options);
  const std::string last = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.back();
  dds::DomainParticipantQos qos;
  if (dds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(options.participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw ConfigError(located(last, "participant profile '" + options.participant_profile + "'", "not found in the loaded QoS files"));
  }
  apply_peer_lease(qos);
  if (options.transport_buffer_bytes > 0 && grow_transport_buffers(qos, options.transport_buffer_bytes)) {
    warn_if_kernel_caps_receive_buffer(options.transport_buffer_bytes, kernel_receive_buffer_max());
  }
  if (!options.discovery_servers.empty()) {
    make_discovery_client(qos, options.discovery_servers);
  }
  check_discovery_servers(qos, options.participant_profile,
                          file_defining(options.qos_files, options.participant_profile, last));
  if (!options.security_dir.empty()) {
    add_security_properties(qos, options);
  }
  return qos;
}

}  // namespace robodds
