#include "tools/robodds/topic_report.hpp"

#include <algorithm>
#include <cstdio>

#include "common/number_text.hpp"

namespace robodds {
namespace {

std::string printf_text(const char* format, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

std::string seconds_text(const std::optional<double>& s) { return s ? shortest_text(*s) + " s" : "Infinite"; }

std::string plural(int n, const char* one) { return std::to_string(n) + " " + one + (n == 1 ? "" : "s"); }

std::string where(const DiscoveredEndpoint& e) { return e.participant + " @ " + (e.host.empty() ? "(host not announced)" : e.host); }

}  // namespace

bool InstanceOrder::operator()(const std::string& a, const std::string& b) const {
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      // Compare two runs of digits by value: without leading zeros, the longer is larger.
      std::size_t ie = i;
      std::size_t je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      const std::size_t is = std::min(a.find_first_not_of('0', i), ie);
      const std::size_t js = std::min(b.find_first_not_of('0', j), je);
      if (ie - is != je - js) {
        return ie - is < je - js;
      }
      const int cmp = a.compare(is, ie - is, b, js, je - js);
      if (cmp != 0) {
        return cmp < 0;
      }
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) {
        return a[i] < b[j];
      }
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j || (a.size() - i == b.size() - j && a < b);
}

std::string hz_text(const std::string& instance, const PeriodStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%saverage rate: %.3f\n\tmin: %.3fs max: %.3fs std dev: %.5fs window: %zu\n",
                instance.empty() ? "" : (instance + ": ").c_str(), s.rate_hz, s.min_s, s.max_s, s.std_s, s.messages);
  return buf;
}

std::string byte_text(double bytes) {
  if (bytes < 1000.0) {
    return printf_text("%.0f B", bytes);
  }
  if (bytes < 1e6) {
    return printf_text("%.2f KB", bytes / 1e3);
  }
  return printf_text("%.2f MB", bytes / 1e6);
}

std::string bw_text(const SizeStats& s) {
  return byte_text(s.bytes_per_s) + "/s from " + std::to_string(s.messages) + " messages\n\tMessage size mean: " +
         byte_text(s.mean_bytes) + " min: " + byte_text(static_cast<double>(s.min_bytes)) +
         " max: " + byte_text(static_cast<double>(s.max_bytes)) + "\n";
}

std::string qos_line(const EndpointQos& q) {
  std::string out = q.reliability + ", " + q.durability;
  if (q.deadline_s) {
    out += ", deadline " + seconds_text(q.deadline_s);
  }
  if (q.lifespan_s) {
    out += ", lifespan " + seconds_text(q.lifespan_s);
  }
  if (q.liveliness != "AUTOMATIC" || q.liveliness_lease_s) {
    out += ", liveliness " + q.liveliness + (q.liveliness_lease_s ? " " + seconds_text(q.liveliness_lease_s) : "");
  }
  if (q.ownership == "EXCLUSIVE") {
    out += ", ownership EXCLUSIVE" + (q.ownership_strength ? " " + std::to_string(*q.ownership_strength) : std::string());
  }
  return out;
}

std::string topics_verbose_text(const std::vector<DiscoveredTopic>& topics) {
  std::string out;
  for (const DiscoveredTopic& t : topics) {
    out += t.name + " [" + t.type_name + "] " + plural(t.writers, "writer") + ", " + plural(t.readers, "reader") + "\n";
    for (const DiscoveredEndpoint& e : t.endpoints) {
      out += std::string("    ") + (e.writer ? "writer" : "reader") + "  " + where(e) + "  " + qos_line(e.qos) + "\n";
    }
  }
  return out;
}

std::string topic_info_text(const DiscoveredTopic& topic) {
  std::string out = "Type: " + topic.type_name + "\n";
  for (const bool writers : {true, false}) {
    out += std::string("\n") + (writers ? "Writer count: " + std::to_string(topic.writers) : "Reader count: " + std::to_string(topic.readers)) + "\n";
    for (const DiscoveredEndpoint& e : topic.endpoints) {
      if (e.writer != writers) {
        continue;
      }
      const EndpointQos& q = e.qos;
      out += "\nParticipant: " + e.participant + "\nHost: " + (e.host.empty() ? "(not announced)" : e.host) +
             "\nEndpoint type: " + (writers ? "WRITER" : "READER") + "\nGUID: " + e.guid + "\nQoS:\n  Reliability: " + q.reliability +
             "\n  History (Depth): UNKNOWN (not announced in discovery)\n  Durability: " + q.durability +
             "\n  Lifespan: " + seconds_text(q.lifespan_s) + "\n  Deadline: " + seconds_text(q.deadline_s) +
             "\n  Liveliness: " + q.liveliness + "\n  Liveliness lease duration: " + seconds_text(q.liveliness_lease_s) +
             "\n  Ownership: " + q.ownership +
             (q.ownership_strength ? " (strength " + std::to_string(*q.ownership_strength) + ")" : std::string()) + "\n";
    }
  }
  return out;
}

}  // namespace robodds
