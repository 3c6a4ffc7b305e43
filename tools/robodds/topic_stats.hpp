#pragma once
// The figures of `robodds hz` and `robodds bw`, like `ros2 topic hz` / `ros2 topic bw`: a window of
// the last N arrivals (wall-clock receipt time, serialized size) of a topic or of one instance,
// and the rate, period extremes and spread, and bandwidth over it. Pure (std only).

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

namespace robodds {

/// One received sample: when it arrived and how large its serialized payload was.
struct Arrival {
  std::int64_t time_ns = 0;  // ns, wall clock on arrival
  std::size_t bytes = 0;     // serialized payload with its 4-byte encapsulation header
};

/// The last `capacity` arrivals, in time order.
class ArrivalWindow {
 public:
  /// `capacity` >= 2 (a period needs two arrivals); std::invalid_argument otherwise.
  explicit ArrivalWindow(std::size_t capacity);
  /// Adds one arrival; the oldest leaves when the window is full. Kept sorted by time: samples of
  /// two writers stamped by two receive threads may be handed over slightly out of order.
  void add(const Arrival& arrival);
  const std::deque<Arrival>& arrivals() const { return arrivals_; }
  /// Arrivals added since the window was made (also those that left it).
  std::uint64_t total() const { return total_; }

 private:
  std::size_t capacity_;
  std::deque<Arrival> arrivals_;
  std::uint64_t total_ = 0;
};

/// The periods between successive arrivals of a window (`ros2 topic hz`).
struct PeriodStats {
  std::size_t messages = 0;  // arrivals in the window (periods + 1: ros2's "window")
  double rate_hz = 0.0;      // Hz, 1 / mean period
  double mean_s = 0.0;       // s
  double min_s = 0.0;        // s
  double max_s = 0.0;        // s
  double std_s = 0.0;        // s, population standard deviation of the periods (as ros2)
};
/// nullopt with fewer than two arrivals, or when they all arrived at one instant (no rate).
std::optional<PeriodStats> period_stats(const ArrivalWindow& window);

/// The sizes of a window's samples and the bandwidth they took (`ros2 topic bw`).
struct SizeStats {
  std::size_t messages = 0;  // arrivals in the window
  double bytes_per_s = 0.0;  // B/s: the bytes that arrived after the first, over the window's span
  double mean_bytes = 0.0;   // B
  std::size_t min_bytes = 0;
  std::size_t max_bytes = 0;
};
/// nullopt with fewer than two arrivals, or a window of no span (no rate).
std::optional<SizeStats> size_stats(const ArrivalWindow& window);

}  // namespace robodds
