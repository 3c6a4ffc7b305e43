#include "common/param_checks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace robodds::param_checks {

void reject(std::string_view key, std::string_view requirement, std::string_view got) {
  std::string message(key);
  message.append(": ").append(requirement).append(" (got ").append(got).append(")");
  throw std::invalid_argument(message);
}

void reject(std::string_view key, std::string_view requirement, double got) {
  reject(key, requirement, shortest_text(got));
}

void require_finite(std::string_view key, double value) {
  if (!std::isfinite(value)) {
    reject(key, "must be finite", value);
  }
}

void require_positive(std::string_view key, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    reject(key, "must be > 0 and finite", value);
  }
}

void require_in_open_interval(std::string_view key, double value, double low, double high) {
  if (!(value > low && value < high)) {
    reject(key, "must be in (" + shortest_text(low) + ", " + shortest_text(high) + ")", value);
  }
}

void require_at_least(std::string_view key, long long value, long long minimum) {
  if (value < minimum) {
    reject(key, "must be >= " + std::to_string(minimum), std::to_string(value));
  }
}

void require_non_negative(std::string_view key, double value, std::string_view meaning_of_zero) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    std::string requirement = "must be >= 0 and finite";
    if (!meaning_of_zero.empty()) {
      requirement.append(" (").append(meaning_of_zero).append(")");
    }
    reject(key, requirement, value);
  }
}

}  // namespace robodds::param_checks
