#pragma once
// The project's topics: name, IDL type, QoS class, key, producers and consumers. The single
// source for the runtime (type checks, QoS profile choice), the topic CLI and docs/topics.md.

#include <string>
#include <vector>

#include "runtime/bus.hpp"

namespace robodds {

struct TopicInfo {
  std::string name;
  std::string type_name;  // e.g. robodds::idl::RobotState
  std::string qos_class;  // sensor | state | command | mission | lockstep
  std::string key;        // e.g. "robot_id"
  std::string producers;
  std::string consumers;
};

const std::vector<TopicInfo>& topic_catalog();
/// nullptr if the topic is not in the catalog.
const TopicInfo* find_topic(const std::string& name);
/// The topic's info; throws ConfigError naming the topic and the known topics.
const TopicInfo& topic_info(const std::string& name);

/// QoS profile used for a topic in a time mode. Simulated time (lockstep) must lose nothing and
/// must not depend on discovery timing, so every data topic uses the reliable, transient-local
/// `lockstep` profile there (missions keep `mission`); real-time uses the topic's own class.
/// `single_process`: every component of the run is in this process (co-located run), so lockstep
/// topics use `lockstep_local` (intra-process delivery is lossless without the reliable protocol).
std::string qos_profile_for(const TopicInfo& topic, TimeMode mode, bool single_process);

/// Participant/data profile names the runtime needs from the QoS file.
inline constexpr const char* kDefaultParticipantProfile = "robodds.participant";
inline constexpr const char* kMonitorProfile = "monitor";

}  // namespace robodds
