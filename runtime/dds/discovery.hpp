#pragma once
// Topic discovery for `robodds topics` and `robodds replay`: which topics exist on a domain, with type and QoS.

#include <string>
#include <vector>

#include "runtime/dds/dds_bus.hpp"

namespace robodds {

struct DiscoveredTopic {
  std::string name;
  std::string type_name;
  int writers = 0;
  int readers = 0;
  std::string writer_qos;  // e.g. "RELIABLE/TRANSIENT_LOCAL" (first writer seen)
  std::string reader_qos;
  /// The participants whose writers of the topic were seen (their names, or their GUID prefix if
  /// unnamed), sorted, each once: who else publishes it (robodds replay).
  std::vector<std::string> writer_participants;
};

/// Listens on the domain for `seconds` and returns the topics seen, sorted by name.
std::vector<DiscoveredTopic> discover_topics(const DdsOptions& options, double seconds);

}  // namespace robodds
