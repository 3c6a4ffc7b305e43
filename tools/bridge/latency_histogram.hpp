#pragma once
// Latencies in 1 us buckets up to 10 ms (above: counted as over, the maximum kept exactly), for
// the bridge's receive->send figures printed at exit. Not thread-safe: one thread records.

#include <cstdint>
#include <string>
#include <vector>

namespace robodds::bridge {

class LatencyHistogram {
 public:
  static constexpr std::int64_t kBucketNs = 1000;     // 1 us
  static constexpr std::int64_t kRangeNs = 10000000;  // 10 ms

  LatencyHistogram();
  void add(std::int64_t latency_ns);
  std::uint64_t count() const { return count_; }
  /// The upper edge (ns) of the bucket holding quantile q in [0, 1]; max() when it lies above the
  /// range; 0 when empty.
  std::int64_t quantile_ns(double q) const;
  std::int64_t max_ns() const { return max_; }
  /// "N messages, p50 X us, p99 Y us, max Z us".
  std::string summary() const;

 private:
  std::vector<std::uint64_t> buckets_;
  std::uint64_t over_ = 0;
  std::uint64_t count_ = 0;
  std::int64_t max_ = 0;
};

}  // namespace robodds::bridge
