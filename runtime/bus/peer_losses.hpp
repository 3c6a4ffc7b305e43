#pragma once
// Participants of the domain that went away, as the transport saw them: a host that died (its
// lease expired) or left (it said goodbye). A capability of a bus that discovers peers (the Fast
// DDS bus), kept out of Bus itself so that buses without peers (MemoryBus, ColocatedBus) need
// nothing: the host asks `dynamic_cast<const PeerLossSource*>(bus)` (docs/deployment.md, "Long
// runs and failures across machines").

#include <cstdint>
#include <string>
#include <vector>

namespace robodds {

struct PeerLoss {
  std::string participant;  // its participant name, e.g. "robodds-estimation"
  /// True: its lease expired without a goodbye (killed, frozen, its machine or network down);
  /// false: it left cleanly (its process ended or deleted its participant).
  bool dropped = true;
  std::int64_t at_ns = 0;  // monotonic_now_ns() when this process learnt it
};

class PeerLossSource {
 public:
  virtual ~PeerLossSource() = default;
  /// How many losses peer_losses() holds: cheap, for a loop that polls it every iteration.
  virtual std::size_t peer_loss_count() const = 0;
  /// Every loss so far, oldest first (a participant that comes back and goes again counts twice).
  virtual std::vector<PeerLoss> peer_losses() const = 0;
  /// Whether a participant named `participant` is alive now (discovered, not gone since): one
  /// that was dropped and is discovered again was stalled (or starved of CPU), not dead.
  virtual bool participant_alive(const std::string& participant) const = 0;
};

}  // namespace robodds
