#include "runtime/health/compute_times.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace robodds {

ComputeTimes::ComputeTimes(std::size_t max_samples) : max_samples_(std::max<std::size_t>(max_samples, 1)) {}

ComputeTimes::Stage& ComputeTimes::stage(const std::string& name) {
  for (Stage& s : stages_) {  // a component has a handful of stages
    if (s.name == name) {
      return s;
    }
  }
  stages_.push_back(Stage{name, 0, 0.0, {}});
  return stages_.back();
}

std::uint64_t ComputeTimes::next_random() {  // splitmix64
  std::uint64_t z = (random_state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

void ComputeTimes::add_ms(const std::string& name, double ms) {
  if (!std::isfinite(ms) || ms < 0.0) {
    return;
  }
  Stage& s = stage(name);
  ++s.count;
  s.max_ms = std::max(s.max_ms, ms);
  if (s.samples_ms.size() < max_samples_) {
    s.samples_ms.push_back(ms);
    return;
  }
  // Algorithm R: the count-th sample replaces a kept one with probability max_samples / count.
  const std::uint64_t slot = next_random() % s.count;
  if (slot < max_samples_) {
    s.samples_ms[static_cast<std::size_t>(slot)] = ms;
  }
}

double nearest_rank_percentile(const std::vector<double>& sorted, double p) {
  const double n = static_cast<double>(sorted.size());
  const auto rank = static_cast<std::size_t>(std::ceil(p * n / 100.0));  // 1-based; p * n is exact
  return sorted[std::min(std::max<std::size_t>(rank, 1), sorted.size()) - 1];
}

std::vector<ComputeTimes::Summary> ComputeTimes::summaries() const {
  std::vector<Summary> out;
  for (const Stage& s : stages_) {
    std::vector<double> sorted = s.samples_ms;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    Summary summary;
    summary.stage = s.name;
    summary.count = s.count;
    summary.median_ms = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    summary.p99_ms = nearest_rank_percentile(sorted, 99.0);
    summary.max_ms = s.max_ms;
    out.push_back(std::move(summary));
  }
  return out;
}

std::size_t ComputeTimes::samples_kept() const {
  std::size_t kept = 0;
  for (const Stage& s : stages_) {
    kept += s.samples_ms.size();
  }
  return kept;
}

ScopedComputeTimer::ScopedComputeTimer(ComputeTimes& times, std::string stage)
    : times_(times), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}

ScopedComputeTimer::~ScopedComputeTimer() {
  times_.add_ms(stage_, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count());
}

}  // namespace robodds
