#pragma once
// The samples of one catalog topic as they arrive on the domain, as their serialized payloads
// (runtime/dds/raw_bus.hpp: the bytes on the wire, never decoded but to name a new instance):
// what `robodds hz` and `robodds bw` measure, with the wall-clock time Fast DDS stamped on arrival.
#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/dds/dds_bus.hpp"
#include "runtime/dds/raw_bus.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tools/robodds/topic_stats.hpp"

namespace robodds {

struct TopicArrival {
  std::string instance;  // e.g. "robot_id=2" (label_instances), else empty
  Arrival arrival;
};

class TopicWatch {
 public:
  /// Joins the domain and reads `topic` with its monitor profile (matches every writer).
  /// `label_instances`: name each arrival's instance by its key ("robot_id=2", decoding the first
  /// sample of each instance only).
  TopicWatch(const TopicInfo& topic, const DdsOptions& dds, bool label_instances);
  ~TopicWatch();
  TopicWatch(const TopicWatch&) = delete;
  TopicWatch& operator=(const TopicWatch&) = delete;
  /// The arrivals since the last call, oldest first.
  std::vector<TopicArrival> take();

 private:
  std::string label(const RawSample& sample);

  const TopicInfo& topic_;
  const bool label_instances_;
  std::mutex mutex_;
  std::vector<TopicArrival> pending_;
  std::map<std::array<std::uint8_t, 16>, std::string> labels_;  // DDS instance handle -> label
  std::unique_ptr<RawBus> bus_;  // last: its reader's callback uses the members above
};

/// What `robodds hz` and `robodds bw` share: how long, which windows, what to print.
struct TopicReport {
  std::size_t window = 2;    // arrivals per window (>= 2)
  bool per_key = false;      // one window per instance
  double duration_s = 0.0;   // s; 0: until `stop`
  std::string tool;          // "hz", "bw": names the tool in the notice that nothing came yet
  /// The text of one window, or "" when it has no figure yet (a single arrival).
  std::function<std::string(const std::string& instance, const ArrivalWindow& window)> format;
};

/// Reads `topic` and prints, every second, each window that got arrivals since the last print
/// (formatted by `report.format`), "no new messages" for one that got none; at the end of
/// --duration once more. Nothing after 5 s: one notice on stderr naming the domain (listening goes
/// on). Returns 0; RunError (nothing_seen_text) when a --duration passed without any arrival.
int watch_and_report(const TopicInfo& topic, const DdsOptions& dds, const TopicReport& report, const std::atomic<bool>& stop);

/// "no sample on T within S s on DDS domain D (`robodds topics --domain D` lists the topics seen
/// there)": what every topic tool says when nothing came.
std::string nothing_seen_text(const std::string& topic, double seconds, int domain);

}  // namespace robodds
