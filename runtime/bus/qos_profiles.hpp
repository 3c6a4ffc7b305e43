#pragma once
// The QoS profile names the code uses. deploy/qos/robodds_qos.xml (data and default participant
// profiles) and deploy/qos/discovery_client.xml define them; runtime/bus/test/qos_profiles_test.cpp
// fails if a name here has no profile there. Write these constants, never the plain strings.

#include <cstddef>
#include <string>
#include <vector>

namespace robodds {

/// Data-writer/reader profiles (each defined as both <data_writer> and <data_reader>).
inline constexpr const char* kSensorProfile = "sensor";
inline constexpr const char* kStateProfile = "state";
inline constexpr const char* kCommandProfile = "command";
inline constexpr const char* kMissionProfile = "mission";
inline constexpr const char* kLockstepProfile = "lockstep";
/// `lockstep` for a co-located run (every component in one process): intra-process delivery.
inline constexpr const char* kLockstepLocalProfile = "lockstep_local";
/// Passive readers (`robodds echo`): the weakest QoS, matches writers of every profile.
inline constexpr const char* kMonitorProfile = "monitor";

/// Participant profiles.
inline constexpr const char* kDefaultParticipantProfile = "robodds.participant";  // SHM + UDPv4
inline constexpr const char* kUdpOnlyParticipantProfile = "robodds.participant.udp_only";
/// DDS Security on one machine: discovery and handshakes on one 127.0.0.1 socket (the Fast DDS
/// 2.9.1 race it avoids: deploy/qos/robodds_qos.xml, docs/security.md).
inline constexpr const char* kSecureLocalParticipantProfile = "robodds.participant.secure_local";
/// How many participants of one domain it finds on this machine (its transport's maxInitialPeersRange).
inline constexpr std::size_t kSecureLocalMaxParticipants = 32;
/// Defined in discovery_client.xml, which is loaded after robodds_qos.xml.
inline constexpr const char* kDiscoveryClientParticipantProfile = "robodds.participant.discovery_client";

/// QoS class of a topic in real time (docs/topics.md); in lockstep the runtime substitutes
/// `lockstep` for every class except kMission (see qos_profile_for()).
enum class QosClass { kSensor, kState, kCommand, kMission, kLockstep };

/// The profile name of a QoS class, e.g. "sensor" for QosClass::kSensor.
const char* to_string(QosClass qos_class);

/// Every data profile above, in declaration order: the runtime requires all of them at start-up.
const std::vector<std::string>& data_profile_names();
/// Every participant profile above.
const std::vector<std::string>& participant_profile_names();

/// A profile the runtime can ask the QoS files for: its XML element and its profile_name.
struct QosProfileRef {
  std::string element;  // "participant", "data_writer" or "data_reader"
  std::string name;
  bool operator==(const QosProfileRef& other) const { return element == other.element && name == other.name; }
};

/// Every profile a bus with participant profile `participant_profile` can ask for, in the order
/// they are checked before its participant is created: the participant profile, then each data
/// profile as a data_writer and as a data_reader.
std::vector<QosProfileRef> required_profiles(const std::string& participant_profile);

}  // namespace robodds
