#pragma once
// Issue 27: "each estimator estimates the noise level of its inputs online ... report the
// estimated noise in the estimate sample or in summary.json". The estimate samples carry it per
// instance (a robot, a robot-peer pair); summary.json gets, per estimate stream, the mean over
// the instances of their last reported value and the largest of them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>

#include "common/json_writer.hpp"

namespace robodds::evaluator {

/// The last noise level (std, in the stream's unit) each instance reported. A value <= 0 (or not
/// finite) means "none estimated" (e.g. the truth estimator) and is not kept.
class NoiseLevels {
 public:
  void add(std::uint64_t instance, double std) {
    if (std::isfinite(std) && std > 0.0) {
      last_[instance] = std;
    }
  }
  bool empty() const { return last_.empty(); }
  /// The last value `instance` reported; 0 when none.
  double last(std::uint64_t instance) const {
    const auto it = last_.find(instance);
    return it == last_.end() ? 0.0 : it->second;
  }
  /// Writes `mean_key` (mean over the instances of their last value) and `max_key` (the largest);
  /// nothing when no instance reported one.
  void write(JsonWriter& json, const std::string& mean_key, const std::string& max_key) const {
    if (last_.empty()) {
      return;
    }
    double sum = 0.0, largest = 0.0;
    for (const auto& [instance, std] : last_) {
      sum += std;
      largest = std::max(largest, std);
    }
    json.value(mean_key, sum / static_cast<double>(last_.size()));
    json.value(max_key, largest);
  }
  /// The levels of `other`'s instances added (instances of both: `other`'s value).
  void merge(const NoiseLevels& other) {
    for (const auto& [instance, std] : other.last_) {
      last_[instance] = std;
    }
  }

 private:
  std::map<std::uint64_t, double> last_;
};

}  // namespace robodds::evaluator
