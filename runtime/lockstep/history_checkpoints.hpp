#pragma once
// Lockstep across processes: how often a host must wait for a component's inputs so that no
// producer can run further ahead of them than its writer history keeps.
//
// A consumer due every p steps reading d steps late needs, at its due step m, the samples up to
// m - d. Its host acknowledges steps without running it, and producers run up to `window` ticks
// past the last acknowledged step: between two steps at which the host waited for the inputs,
// c steps apart, W + c + d - 1 samples of an instance may be written after the one it needs.
// A writer keeping fewer may drop a sample a reader never got (e.g. a reader that matched late,
// at the start; a packet repaired from the history): the run would stop on a broken chain of
// steps. Waiting at the due steps alone (c = p) suffices while W + p + d - 1 <= depth; beyond,
// the host also waits for the inputs (without running the component) every c steps, the
// largest c with W + c + d - 1 <= depth. A 1 Hz sensor at a 100 Hz step then runs across
// processes with the default depth 48 instead of being refused. Pure: counts of steps/samples.

#include <cstdint>
#include <optional>

namespace robodds {

/// The steps between the extra waits of a consumer due every `period_steps` (>= 1) reading
/// `delay_steps` late, under a coordinator `window` (>= 1) and a writer history of `depth`
/// samples per instance: 0 when its due steps suffice; nullopt when even a wait at every step
/// cannot keep the bound (window + delay > depth).
std::optional<std::uint64_t> history_checkpoint_steps(std::uint64_t window, std::uint64_t period_steps,
                                                      std::uint64_t delay_steps, std::uint64_t depth);

}  // namespace robodds
