#pragma once
// A metrics module's figures of each robot, found in O(1) per sample (runtime/bus/key_index.hpp)
// rather than by a walk down a map (log N cache misses at 1,000 robots), and visited in id order.

#include <cstdint>
#include <map>
#include <vector>

#include "runtime/bus/key_index.hpp"

namespace robodds::evaluator {

template <class Figures>
class PerRobot {
 public:
  PerRobot() = default;
  // get() hands out pointers into robots_ (by_number_): not copyable.
  PerRobot(const PerRobot&) = delete;
  PerRobot& operator=(const PerRobot&) = delete;

  /// The figures of robot `id`, made from `args` at its first sample.
  template <class... Args>
  Figures& get(std::uint32_t id, const Args&... args) {
    const auto [number, added] = numbers_.insert(id);
    if (added) {
      by_number_.push_back(&robots_.try_emplace(id, args...).first->second);
    }
    return *by_number_[number];
  }
  /// The figures of robot `id`, nullptr if none of its samples came.
  const Figures* find(std::uint32_t id) const {
    const auto it = robots_.find(id);
    return it != robots_.end() ? &it->second : nullptr;
  }
  /// Every robot's figures, in id order.
  std::map<std::uint32_t, Figures>& all() { return robots_; }

 private:
  std::map<std::uint32_t, Figures> robots_;
  KeyIndex numbers_;                  // robot id -> index in by_number_
  std::vector<Figures*> by_number_;   // nodes of robots_ (a map's nodes never move)
};

}  // namespace robodds::evaluator
