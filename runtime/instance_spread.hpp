#pragma once
// Spreading one topic's instances over several writers of that topic in one process.
//
// Why: a `lockstep` writer keeps KEEP_LAST 48 samples per instance, and Fast DDS 2.9 keeps a
// writer's whole history in one vector, dropping an instance's oldest sample by erasing it from
// near the front: every write moves (depth x instances) pointers. With one writer for 200 robots
// that was 77 kB per sample and ~14 % of the `sim` host's time; with 1,000 robots the cost per
// robot-tick grew with the robots (docs/performance.md, "Across processes at scale"). Writers
// holding at most kInstancesPerLockstepWriter instances each keep that cost flat. Readers see
// the same topic, type, keys and QoS: only the writer GUID of an instance differs, and each
// instance keeps one writer for the run (one producer per instance still holds per writer).

#include <cstddef>
#include <cstdint>

#include "runtime/key_index.hpp"

namespace robodds {

/// At most this many instances per lockstep writer (a few dozen: the vector erase stays within
/// the L1/L2 caches; more writers cost discovery endpoints and heartbeats, so not fewer).
inline constexpr std::size_t kInstancesPerLockstepWriter = 32;

/// Writers for a topic with `instances` instances: ceil(instances / per_writer), at least 1.
constexpr std::size_t writers_for_instances(std::size_t instances, std::size_t per_writer = kInstancesPerLockstepWriter) {
  return instances <= per_writer ? 1 : (instances + per_writer - 1) / per_writer;
}

/// Which writer publishes an instance: the n-th instance seen (n = 0, 1, ...) goes to writer
/// n mod writers, so the writers hold equal shares, and an instance keeps its writer. In
/// lockstep the first-write order is the same in every run, so is the assignment. Not
/// thread-safe (a writer is used from one thread at a time).
class InstanceSpread {
 public:
  explicit InstanceSpread(std::size_t writers) : writers_(writers == 0 ? 1 : writers) {}

  std::size_t writers() const { return writers_; }

  /// The writer (0 .. writers()-1) of the instance with this key hash (e.g. stable_hash of the
  /// DDS instance handle's bytes). Two instances whose hashes collide share a writer: harmless.
  std::size_t writer_of(std::uint64_t instance_hash) {
    if (writers_ == 1) {
      return 0;
    }
    return index_.insert(instance_hash).first % writers_;
  }

 private:
  std::size_t writers_;
  KeyIndex index_;
};

}  // namespace robodds
