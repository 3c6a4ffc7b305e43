#include "runtime/bus/qos_profiles.hpp"

namespace robodds {

const char* to_string(QosClass qos_class) {
  switch (qos_class) {
    case QosClass::kSensor:
      return kSensorProfile;
    case QosClass::kState:
      return kStateProfile;
    case QosClass::kCommand:
      return kCommandProfile;
    case QosClass::kMission:
      return kMissionProfile;
    case QosClass::kLockstep:
      return kLockstepProfile;
  }
  return "?";  // unreachable: every enumerator is handled above (-Wswitch checks it)
}

const std::vector<std::string>& data_profile_names() {
  static const std::vector<std::string> names = {kSensorProfile,   kStateProfile,         kCommandProfile, kMissionProfile,
                                                 kLockstepProfile, kLockstepLocalProfile, kMonitorProfile};
  return names;
}

const std::vector<std::string>& participant_profile_names() {
  static const std::vector<std::string> names = {kDefaultParticipantProfile, kUdpOnlyParticipantProfile,
                                                 kSecureLocalParticipantProfile, kDiscoveryClientParticipantProfile};
  return names;
}

std::vector<QosProfileRef> required_profiles(const std::string& participant_profile) {
  std::vector<QosProfileRef> profiles = {{"participant", participant_profile}};
  for (const std::string& name : data_profile_names()) {
    profiles.push_back({"data_writer", name});
    profiles.push_back({"data_reader", name});
  }
  return profiles;
}

}  // namespace robodds
