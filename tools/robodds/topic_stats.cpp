#include "tools/robodds/topic_stats.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

namespace robodds {

ArrivalWindow::ArrivalWindow(std::size_t capacity) : capacity_(capacity) {
  if (capacity < 2) {
    throw std::invalid_argument("a window of " + std::to_string(capacity) + " samples: it needs at least 2 (one period)");
  }
}

void ArrivalWindow::add(const Arrival& arrival) {
  // Nearly always appended at the end: the search from the back stops at once.
  auto it = arrivals_.end();
  while (it != arrivals_.begin() && std::prev(it)->time_ns > arrival.time_ns) {
    --it;
  }
  arrivals_.insert(it, arrival);
  if (arrivals_.size() > capacity_) {
    arrivals_.pop_front();
  }
  ++total_;
}

std::optional<PeriodStats> period_stats(const ArrivalWindow& window) {
  const std::deque<Arrival>& a = window.arrivals();
  if (a.size() < 2 || a.back().time_ns == a.front().time_ns) {
    return std::nullopt;
  }
  PeriodStats s;
  s.messages = a.size();
  const double periods = static_cast<double>(a.size() - 1);
  s.mean_s = static_cast<double>(a.back().time_ns - a.front().time_ns) * 1e-9 / periods;
  s.rate_hz = 1.0 / s.mean_s;
  s.min_s = INFINITY;
  s.max_s = 0.0;
  double sum_sq = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double period = static_cast<double>(a[i].time_ns - a[i - 1].time_ns) * 1e-9;
    s.min_s = std::min(s.min_s, period);
    s.max_s = std::max(s.max_s, period);
    sum_sq += (period - s.mean_s) * (period - s.mean_s);
  }
  s.std_s = std::sqrt(sum_sq / periods);
  return s;
}

std::optional<SizeStats> size_stats(const ArrivalWindow& window) {
  const std::deque<Arrival>& a = window.arrivals();
  if (a.size() < 2 || a.back().time_ns == a.front().time_ns) {
    return std::nullopt;
  }
  SizeStats s;
  s.messages = a.size();
  s.min_bytes = a.front().bytes;
  s.max_bytes = a.front().bytes;
  double total = 0.0;
  for (const Arrival& arrival : a) {
    total += static_cast<double>(arrival.bytes);
    s.min_bytes = std::min(s.min_bytes, arrival.bytes);
    s.max_bytes = std::max(s.max_bytes, arrival.bytes);
  }
  s.mean_bytes = total / static_cast<double>(a.size());
  // The first arrival opens the span; its bytes came before it.
  s.bytes_per_s = (total - static_cast<double>(a.front().bytes)) / (static_cast<double>(a.back().time_ns - a.front().time_ns) * 1e-9);
  return s;
}

}  // namespace robodds
