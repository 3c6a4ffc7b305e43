#include "runtime/lockstep/history_checkpoints.hpp"

namespace robodds {

std::optional<std::uint64_t> history_checkpoint_steps(std::uint64_t window, std::uint64_t period_steps,
                                                      std::uint64_t delay_steps, std::uint64_t depth) {
  // Samples that may be written after the needed one while the host waits c steps: W + c + d - 1.
  const std::uint64_t fixed = window + delay_steps;  // W + d: the part a wait cannot shorten, + 1
  if (fixed > depth) {
    return std::nullopt;  // W + 1 + d - 1 > depth even when waiting at every step
  }
  const std::uint64_t longest_gap = depth - fixed + 1;  // the largest c with W + c + d - 1 <= depth
  return period_steps <= longest_gap ? 0 : longest_gap;
}

}  // namespace robodds
