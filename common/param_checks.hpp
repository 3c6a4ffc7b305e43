#pragma once
// Checks for the validate() of the plain parameter structs. Each failure throws
// std::invalid_argument("key: requirement (got value)"): the key comes first so that the node
// can name the YAML file and line, and the value is the shortest text of the double (so NaN reads
// "nan"). Comparisons are written so that NaN fails them.

#include <string_view>

namespace robodds::param_checks {

[[noreturn]] void reject(std::string_view key, std::string_view requirement, std::string_view got);
[[noreturn]] void reject(std::string_view key, std::string_view requirement, double got);

/// "key: must be finite".
void require_finite(std::string_view key, double value);

/// "key: must be > 0 and finite".
void require_positive(std::string_view key, double value);

/// "key: must be in (low, high)", for an open interval.
void require_in_open_interval(std::string_view key, double value, double low, double high);

/// "key: must be >= minimum", for counts.
void require_at_least(std::string_view key, long long value, long long minimum);

/// "key: must be >= 0 and finite", followed by " (meaning_of_zero)" when one is given, e.g.
/// "0 = no limit".
void require_non_negative(std::string_view key, double value, std::string_view meaning_of_zero = {});

}  // namespace robodds::param_checks
