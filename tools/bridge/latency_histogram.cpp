#include "tools/bridge/latency_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace robodds::bridge {

LatencyHistogram::LatencyHistogram() : buckets_(static_cast<std::size_t>(kRangeNs / kBucketNs), 0) {}

void LatencyHistogram::add(std::int64_t latency_ns) {
  latency_ns = std::max<std::int64_t>(latency_ns, 0);
  ++count_;
  max_ = std::max(max_, latency_ns);
  if (latency_ns >= kRangeNs) {
    ++over_;
  } else {
    ++buckets_[static_cast<std::size_t>(latency_ns / kBucketNs)];
  }
}

std::int64_t LatencyHistogram::quantile_ns(double q) const {
  if (count_ == 0) {
    return 0;
  }
  // The rank of the quantile, 1-based: the smallest value with at least q of the samples at or below it.
  const auto rank = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < buckets_.size(); ++i) {
    seen += buckets_[i];
    if (seen >= rank) {
      return std::min(static_cast<std::int64_t>(i + 1) * kBucketNs, max_);
    }
  }
  return max_;
}

std::string LatencyHistogram::summary() const {
  char line[160];
  std::snprintf(line, sizeof(line), "%llu messages, p50 %.0f us, p99 %.0f us, max %.0f us",
                static_cast<unsigned long long>(count_), static_cast<double>(quantile_ns(0.5)) / 1e3,
                static_cast<double>(quantile_ns(0.99)) / 1e3, static_cast<double>(max_) / 1e3);
  return line;
}

}  // namespace robodds::bridge
