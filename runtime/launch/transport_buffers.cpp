#include "runtime/launch/transport_buffers.hpp"

#include <algorithm>

namespace robodds {

namespace {
constexpr std::size_t kFastDdsDefaultSegmentBytes = 512 * 1024;  // SharedMemTransportDescriptor's
constexpr std::size_t kRoundBytes = 64 * 1024;
}  // namespace

std::size_t transport_buffer_bytes(std::size_t robots_served, std::size_t lockstep_window) {
  if (robots_served == 0) {
    return 0;
  }
  // Saturating: absurd figures give the cap instead of wrapping around.
  if (lockstep_window >= kTransportBufferMaxBytes || robots_served >= kTransportBufferMaxBytes) {
    return kTransportBufferMaxBytes;
  }
  const std::size_t ticks = std::max<std::size_t>(1, lockstep_window) + 1;
  const std::size_t per_tick = robots_served * kTransportBytesPerRobotTick;  // < 2^26 x 2^9: no overflow
  if (ticks > kTransportBufferMaxBytes / per_tick) {
    return kTransportBufferMaxBytes;
  }
  const std::size_t needed = ticks * per_tick;
  if (needed <= kFastDdsDefaultSegmentBytes) {
    return 0;
  }
  return std::min(kTransportBufferMaxBytes, (needed + kRoundBytes - 1) / kRoundBytes * kRoundBytes);
}

}  // namespace robodds
