#pragma once
// Paper 3: the true poses of every robot of the scenario (peers included), kept by step while a
// relative pose estimate of that step may still come (relative_recorder.hpp).

#include <cstdint>
#include <map>

#include "sim/evaluator/track.hpp"

namespace robodds::evaluator {

class TruthByRobot {
 public:
  void add(std::uint32_t robot, const PoseSample& sample) { robots_[robot].add(sample); }
  /// Truth of `robot` has arrived up to `step` (a sample at that step is there, or never comes).
  bool reached(std::uint32_t robot, std::uint64_t step) const {
    auto it = robots_.find(robot);
    return it != robots_.end() && it->second.reached(step);
  }
  /// The true pose of `robot` at `step`, nullptr if there is none.
  const PoseSample* at(std::uint32_t robot, std::uint64_t step) const {
    auto it = robots_.find(robot);
    return it != robots_.end() ? it->second.at(step) : nullptr;
  }
  void drop_before(std::uint64_t step) {
    for (auto& [id, window] : robots_) {
      window.drop_before(step);
    }
  }

 private:
  std::map<std::uint32_t, TruthWindow> robots_;
};

}  // namespace robodds::evaluator
