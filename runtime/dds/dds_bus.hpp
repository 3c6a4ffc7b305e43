#pragma once
// Creates the Fast DDS implementation of Bus. This header stays free of Fast DDS includes.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/bus/qos_profiles.hpp"
#include "runtime/bus/run_digest.hpp"

namespace robodds {

/// A Fast DDS Discovery Server a participant is the client of (`--discovery-server`).
struct DiscoveryServer {
  std::string host;   // IPv4 address or host name (resolved when the participant is made)
  int port = 11811;   // UDP port of the server's metatraffic locator
};

struct DdsOptions {
  int domain_id = 0;
  std::vector<std::string> qos_files;  // loaded in order; the first must define the data profiles
  std::string participant_profile = kDefaultParticipantProfile;
  std::string participant_name = "robodds";
  // DDS Security (`--security DIR`): empty = an unsecured participant. The participant uses the
  // files of DIR/<security_identity>/ (runtime/dds/security_files.hpp), checked before it is made.
  std::string security_dir;
  std::string security_identity;
  /// Non-empty: the participant is a Discovery Server CLIENT of these servers instead of what its
  /// profile says; server i of the list has server id i (GUID prefix 44.53.<i>.5f...: start it
  /// with `fast-discovery-server -i <i>`), the others are its backups.
  std::vector<DiscoveryServer> discovery_servers;
  /// The scenario components this process runs, announced to the other participants
  /// (component_announcement.hpp) so their inputs accept this process's writers as producers.
  std::vector<std::string> components;
  /// A host of a scenario run also announces its run and the digest of what it loaded
  /// (runtime/bus/run_digest.hpp); nullopt: neither (a tool, a component without a scenario).
  std::optional<std::uint64_t> run_id;
  RunDigest digest;
  /// At least this many bytes of shared-memory segment (the participant's outgoing messages) and of
  /// UDP receive buffer (its incoming ones): every such transport of its profile is grown to it
  /// (grow_transport_buffers); 0: the profile's own. runtime/launch/transport_buffers.hpp says why
  /// a lockstep host may need more.
  std::size_t transport_buffer_bytes = 0;
};

class DdsBus : public Bus {
 public:
  /// Readers are created when start() runs, so that every local subscriber of a topic is
  /// registered before the first (possibly transient-local) sample is delivered.
  virtual void start() = 0;
  /// Deletes every reader; no sample or event callback runs once it returns. Call it before
  /// destroying what the callbacks point to (a host's inputs, a notifier): otherwise a sample
  /// arriving while the bus is being destroyed reaches freed memory.
  virtual void close_readers() = 0;
  /// Samples this process's readers' own filters left out because no subscriber reads their step
  /// (ReaderHandle::set_step_needs). A robodds writer leaves them out itself: those never arrive
  /// and are not counted here.
  virtual std::uint64_t samples_left_out_on_arrival() const = 0;
};

/// Loads and validates the QoS files and creates one DomainParticipant. Throws ConfigError naming
/// the file and the rejected element, or a missing profile, and RunError if DDS fails.
std::unique_ptr<DdsBus> make_dds_bus(const DdsOptions& options);

// The QoS files (defined in runtime/dds/qos_files.cpp).

/// Loads the QoS files into the process-wide profile store (idempotent per file); ConfigError on
/// a malformed file, naming the file and Fast DDS's reason.
void load_qos_files(const std::vector<std::string>& files);

/// Loads the QoS files and checks that they define every profile a bus with these options can ask
/// for (required_profiles()), without creating a participant: ConfigError naming the file and the
/// first missing profile. make_dds_bus() runs it first; a launcher runs it before spawning hosts.
void check_qos_profiles(const DdsOptions& options);

}  // namespace robodds
