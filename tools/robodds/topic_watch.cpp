#include "tools/robodds/topic_watch.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/sample_codec.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/topic_report.hpp"

namespace robodds {

TopicWatch::TopicWatch(const TopicInfo& topic, const DdsOptions& dds, bool label_instances)
    : topic_(topic), label_instances_(label_instances) {
  bus_ = make_raw_bus(dds);
  bus_->reader(
      topic.name, topic.type_name, monitor_profile_for(topic),
      [this](const RawSample& sample) {
        TopicArrival a{label_instances_ ? label(sample) : std::string(),
                       Arrival{sample.reception_time_ns, sample.size}};
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.push_back(std::move(a));
      },
      [this](const std::string& event) { log::warn("topic", topic_.name + ": " + event); });
  bus_->start();
}

TopicWatch::~TopicWatch() { bus_->close_readers(); }

std::vector<TopicArrival> TopicWatch::take() {
  std::vector<TopicArrival> out;
  std::lock_guard<std::mutex> lock(mutex_);
  out.swap(pending_);
  return out;
}

std::string TopicWatch::label(const RawSample& sample) {
  // One reader thread at a time calls this (raw_bus.hpp): labels_ needs no lock.
  const auto found = labels_.find(sample.instance);
  if (found != labels_.end()) {
    return found->second;
  }
  std::string text = "(undecodable)";
  try {
    const std::shared_ptr<void> decoded = sample_codec().deserialize(topic_.type_name, sample.data, sample.size);
    idl::dispatch_type(topic_.type_name, [&](auto tag) {
      using Msg = typename decltype(tag)::type;
      text = idl::instance_label(*static_cast<const Msg*>(decoded.get()));
    });
  } catch (const ConfigError&) {
    return text;  // a payload that does not decode names no instance; the next one may
  }
  return labels_[sample.instance] = text;
}

int watch_and_report(const TopicInfo& topic, const DdsOptions& dds, const TopicReport& report, const std::atomic<bool>& stop) {
  using Clock = std::chrono::steady_clock;
  TopicWatch watch(topic, dds, report.per_key);
  // instance ("" without --per-key) -> its window, printed robot_id=2 before robot_id=10
  std::map<std::string, ArrivalWindow, InstanceOrder> windows;
  std::map<std::string, std::uint64_t> printed_at;  // instance -> ArrivalWindow::total() at its last print
  const auto start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(report.duration_s));
  auto next_print = start + std::chrono::seconds(1);
  bool noticed = false;
  const auto print = [&](bool last_print) {
    std::string out;
    for (const auto& [instance, window] : windows) {
      std::uint64_t& last = printed_at[instance];
      if (window.total() == last) {
        if (last_print) {
          continue;  // said a second ago
        }
        out += (instance.empty() ? "" : instance + ": ") + "no new messages\n";
        continue;
      }
      const std::string text = report.format(instance, window);
      if (!text.empty()) {
        out += text;
        last = window.total();
      }
    }
    std::fputs(out.c_str(), stdout);
    std::fflush(stdout);
  };
  for (;;) {
    const bool timed = report.duration_s > 0.0;
    const bool done = stop || (timed && Clock::now() >= deadline);
    for (TopicArrival& a : watch.take()) {
      windows.try_emplace(a.instance, report.window).first->second.add(a.arrival);
    }
    if (done) {
      if (timed && !stop && windows.empty()) {
        throw RunError(nothing_seen_text(topic.name, report.duration_s, dds.domain_id));
      }
      print(true);  // the figures of the last part second
      return 0;
    }
    if (Clock::now() >= next_print) {
      print(false);
      next_print += std::chrono::seconds(1);
    }
    if (windows.empty() && !noticed && Clock::now() - start >= std::chrono::seconds(5)) {
      std::fprintf(stderr, "robodds %s: %s; still listening\n", report.tool.c_str(), nothing_seen_text(topic.name, 5.0, dds.domain_id).c_str());
      noticed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // 20 ms: a print at most 20 ms late, a few wake-ups per second
  }
}

std::string nothing_seen_text(const std::string& topic, double seconds, int domain) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", seconds);
  return "no sample on " + topic + " within " + s + " s " + on_domain_text(domain);
}

}  // namespace robodds
