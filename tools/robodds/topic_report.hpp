#pragma once
// What `robodds hz`, `robodds bw`, `robodds info TOPIC` and `robodds topics -v` print, in the
// words of `ros2 topic hz/bw/info -v`: from the window figures (topic_stats.hpp) and the
// endpoints discovery announced (runtime/dds/discovery.hpp, a plain struct). Pure (std only).
#include <string>

#include "runtime/dds/discovery.hpp"
#include "tools/robodds/topic_stats.hpp"

namespace robodds {

/// "average rate: 100.000\n\tmin: 0.010s max: 0.010s std dev: 0.00001s window: 101\n"
/// (ros2 topic hz's two lines; `instance` non-empty: "robot_id=1: " before the first).
std::string hz_text(const std::string& instance, const PeriodStats& stats);

/// The order `--per-key` prints instances in: numbers by value ("robot_id=2" before
/// "robot_id=10", "robot_id=1, peer_id=3" before "robot_id=1, peer_id=12"), the rest as text.
struct InstanceOrder {
  bool operator()(const std::string& a, const std::string& b) const;
};

/// A size in bytes as ros2 topic bw writes one: "76 B", "1.53 KB", "2.10 MB" (1000-based).
std::string byte_text(double bytes);

/// "7.60 KB/s from 100 messages\n\tMessage size mean: 76 B min: 76 B max: 76 B\n".
std::string bw_text(const SizeStats& stats);

/// One endpoint's announced QoS on one line: "RELIABLE, VOLATILE, deadline 0.5 s, liveliness
/// MANUAL_BY_TOPIC 1 s"; lifespan, deadline and a liveliness lease only when finite, ownership
/// only when EXCLUSIVE (with its strength).
std::string qos_line(const EndpointQos& qos);

/// `robodds topics -v`: per topic "NAME [TYPE] W writers, R readers" then one line per endpoint:
/// "    writer  PARTICIPANT @ HOST  QOS".
std::string topics_verbose_text(const std::vector<DiscoveredTopic>& topics);

/// `robodds info TOPIC` (as `ros2 topic info -v`): the type, the writer count, each writer's
/// participant, host, GUID and QoS one per line, then the readers the same way. `topic` may have
/// no endpoint (nothing seen): the counts are 0. History is written UNKNOWN: discovery does not
/// carry it.
std::string topic_info_text(const DiscoveredTopic& topic);

}  // namespace robodds
