#pragma once
// Where a component is in time, shared by its inputs and outputs (input.hpp, output.hpp).

#include <cstdint>
#include <limits>

#include "runtime/bus/bus.hpp"

namespace robodds {

inline constexpr std::uint64_t kNeverAgain = std::numeric_limits<std::uint64_t>::max();

/// Where a component is in time; shared by its inputs and outputs.
struct StepState {
  std::uint64_t step = 0;          // the step being processed
  std::uint64_t period_steps = 1;  // the component runs every period_steps steps
  std::int64_t stamp_ns = 0;       // sim time (lockstep) or wall time (real-time) of `step`
  TimeMode mode = TimeMode::kLockstep;
};

}  // namespace robodds
