#pragma once
// What an Input did with the samples it was handed (InputCounts), and the runtime's reasons for
// dropping one besides the sample checks (runtime/io/sample_checks.hpp).

#include <cstdint>
#include <map>
#include <string>

namespace robodds {

/// What an input did with the samples it was handed: accepted, or dropped and counted per reason
/// (e.g. "non_finite"), for logs and summary.json.
struct InputCounts {
  std::uint64_t accepted = 0;
  std::map<std::string, std::uint64_t> rejected;  // reason -> samples dropped
  /// reason -> accepted samples the consumer had to correct before use (e.g. a command saturated
  /// to the plant's limits); counted by the component with InputBase::count_adjusted().
  std::map<std::string, std::uint64_t> adjusted;
  std::uint64_t rejected_total() const {
    std::uint64_t total = 0;
    for (const auto& [reason, count] : rejected) {
      total += count;
    }
    return total;
  }
};

namespace detail {
/// Rejection reason of a sample with a NaN or infinite number.
inline constexpr const char* kRejectNonFinite = "non_finite";
/// Rejection reason of a sample of an instance that already has another producer (real time,
/// shared ownership: the first writer wins; docs/architecture.md, "One producer per instance").
inline constexpr const char* kRejectSecondProducer = "second_producer";
/// Rejection reason of a sample from a writer the scenario does not assign to its instance (a
/// foreign program, another component): InputOptions::producer_assigned.
inline constexpr const char* kRejectUnknownProducer = "unknown_producer";
/// Rejection reason of a sample whose key names a robot the scenario does not have.
inline constexpr const char* kRejectUnknownKey = "unknown_key";
/// Real time, shared ownership: a producer silent this long (the liveliness lease of the
/// real-time profiles) gives its instance up, so a restarted producer (new writer) takes over.
inline constexpr std::int64_t kProducerSilenceNs = 1000000000;

}  // namespace detail

}  // namespace robodds
