#pragma once
// Numbers read from command-line text (options such as --seed, --step, --robot): the whole text
// must be the number, so "7abc" or "-1" for a whole number is refused rather than read as 7 or
// 2^64-1. Callers turn a refusal into their own one-line error naming the option.

#include <cstdint>
#include <optional>
#include <string>

namespace robodds {

/// Decimal digits only (no sign, no spaces), value at most `max`; nullopt otherwise.
std::optional<std::uint64_t> parse_whole_number(const std::string& text, std::uint64_t max);

/// A finite double (strtod syntax, the whole text); nullopt for anything else, NaN and infinities.
std::optional<double> parse_finite_number(const std::string& text);

}  // namespace robodds
