#pragma once
// Typed inputs and outputs of components, free of Fast DDS headers; one header per part:
//   step_state.hpp    where a component is in time (StepState, kNeverAgain)
//   subscription.hpp  what a component asks for (Subscription) and the runtime's InputOptions
//   input_counts.hpp  accepted and dropped samples, per reason
//   input_base.hpp    per stream: readiness, producer, lost samples, freshness, wake-ups
//   input.hpp         Input<Msg>: typed storage and reads, the checks of every sample
//   output.hpp        Output<Msg>: header stamping, ended instances
//
// Lockstep rule (docs/architecture.md): every sample carries its `step` and its producer's
// `next_step`. A consumer due at step m with input delay d waits, per expected instance,
// until the newest sample has next_step > m - d: then every sample with step <= m - d has
// arrived, whatever the delivery order across topics and processes. It then reads only
// samples with step <= m - d. The result is the same co-located, across processes or hosts.

#include "runtime/io/input.hpp"
#include "runtime/io/output.hpp"
#include "runtime/io/subscription.hpp"
