#pragma once
// Topic discovery for `robodds topics` and `robodds replay`: which topics exist on a domain, with type and QoS.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "runtime/dds/dds_bus.hpp"

namespace robodds {

/// The QoS an endpoint announced in discovery (DDS's publication / subscription data). The history
/// kind and depth are not among them: DDS discovery does not carry them (`ros2 topic info -v`
/// prints UNKNOWN for the same reason).
struct EndpointQos {
  std::string reliability;                // RELIABLE, BEST_EFFORT
  std::string durability;                 // VOLATILE, TRANSIENT_LOCAL, TRANSIENT, PERSISTENT
  std::optional<double> deadline_s;       // s; nullopt: infinite (not set)
  std::optional<double> lifespan_s;       // s; nullopt: infinite (not set)
  std::string liveliness;                 // AUTOMATIC, MANUAL_BY_PARTICIPANT, MANUAL_BY_TOPIC
  std::optional<double> liveliness_lease_s;  // s; nullopt: infinite
  std::string ownership;                  // SHARED, EXCLUSIVE
  std::optional<std::uint32_t> ownership_strength;  // a writer with EXCLUSIVE ownership
};

/// One writer or reader of a topic as discovery announced it.
struct DiscoveredEndpoint {
  bool writer = true;       // false: a reader
  std::string guid;         // the endpoint's GUID, Fast DDS's text
  std::string participant;  // its participant's name (its GUID prefix when unnamed or not seen)
  std::string host;         // the host name its participant announced; empty: none announced
  EndpointQos qos;
};

struct DiscoveredTopic {
  std::string name;
  std::string type_name;
  int writers = 0;  // seen and not removed again
  int readers = 0;
  std::string writer_qos;  // e.g. "RELIABLE/TRANSIENT_LOCAL" (first writer seen)
  std::string reader_qos;
  /// The participants whose writers of the topic were seen (their names, or their GUID prefix if
  /// unnamed), sorted, each once: who else publishes it (robodds replay).
  std::vector<std::string> writer_participants;
  /// Every writer, then every reader, seen and not removed again, each sorted by participant.
  std::vector<DiscoveredEndpoint> endpoints;
};

/// Listens on the domain for `seconds` and returns the topics seen, sorted by name.
std::vector<DiscoveredTopic> discover_topics(const DdsOptions& options, double seconds);

}  // namespace robodds
