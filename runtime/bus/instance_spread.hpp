#pragma once
// Spreading one topic's instances over several writers of that topic in one process.
//
// Why: a `lockstep` writer keeps KEEP_LAST 48 samples per instance, and Fast DDS 2.9 keeps a
// writer's whole history in one vector, dropping an instance's oldest sample by erasing it from
// near the front: every write moves (depth x instances) pointers. With one writer for 200 robots
// that was 77 kB per sample and ~14 % of the `sim` host's time; with 1,000 robots the cost per
// robot-tick grew with the robots (docs/performance.md, "Across processes at scale"). One writer
// per kRobotsPerLockstepWriter robots keeps that cost flat. Readers see
// the same topic, type, keys and QoS: only the writer GUID of an instance differs, and each
// instance keeps one writer for the run (one producer per instance still holds per writer).

#include <cstddef>
#include <cstdint>

#include "runtime/bus/key_index.hpp"

namespace robodds {

/// One lockstep writer per this many robots of a robot-keyed topic (a few dozen instances per
/// writer: the vector erase stays small; more writers cost discovery endpoints and heartbeats).
/// A topic keyed by robot and peer has this many robots' pairs per writer.
inline constexpr std::size_t kRobotsPerLockstepWriter = 32;

/// Writers for a robot-keyed topic of a run with `robots` robots: ceil(robots / per_writer), at
/// least 1.
constexpr std::size_t writers_for_robots(std::size_t robots, std::size_t per_writer = kRobotsPerLockstepWriter) {
  return robots <= per_writer ? 1 : (robots + per_writer - 1) / per_writer;
}

/// Which writer publishes an instance: the n-th instance seen (n = 0, 1, ...) goes to writer
/// n mod writers, so the writers hold equal shares, and an instance keeps its writer. In
/// lockstep the first-write order is the same in every run, so is the assignment. Not
/// thread-safe (a writer is used from one thread at a time).
class InstanceSpread {
 public:
  explicit InstanceSpread(std::size_t writers) : writers_(writers == 0 ? 1 : writers) {}

  std::size_t writers() const { return writers_; }

  /// The writer (0 .. writers()-1) of the instance with this key (idl::instance_key).
  std::size_t writer_of(std::uint64_t instance_key) {
    if (writers_ == 1) {
      return 0;
    }
    return index_.insert(instance_key).first % writers_;
  }

 private:
  std::size_t writers_;
  KeyIndex index_;
};

}  // namespace robodds
