#include "runtime/bus/step_needs.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace robodds {
namespace {

/// The first m >= from with m = residue (mod period); the largest value when it would overflow.
std::uint64_t first_from(std::uint64_t from, std::uint64_t period, std::uint64_t residue) {
  const std::uint64_t ahead = (residue + period - from % period) % period;
  return from > std::numeric_limits<std::uint64_t>::max() - ahead ? std::numeric_limits<std::uint64_t>::max() : from + ahead;
}

}  // namespace

StepNeeds StepNeeds::of_component(std::uint64_t period_steps, std::uint64_t checkpoint_steps, std::uint64_t delay_steps) {
  StepNeeds needs;
  if (period_steps <= 1 || checkpoint_steps == 1) {
    return needs;  // due or waiting at every step: every sample
  }
  // k = 0 (mod p) read at m = k - d: m = -d (mod p).
  needs.add_stride(period_steps, (period_steps - delay_steps % period_steps) % period_steps);
  if (checkpoint_steps > 1) {
    needs.add_stride(checkpoint_steps, (checkpoint_steps - delay_steps % checkpoint_steps) % checkpoint_steps);
  }
  return needs;
}

void StepNeeds::add_stride(std::uint64_t period, std::uint64_t residue) {
  const std::pair<std::uint64_t, std::uint64_t> stride{period, residue};
  const auto at = std::lower_bound(strides_.begin(), strides_.end(), stride);
  if (at == strides_.end() || *at != stride) {
    strides_.insert(at, stride);
  }
}

bool StepNeeds::needs(std::uint64_t step, std::uint64_t next_step) const {
  if (all() || next_step <= step) {
    return true;
  }
  for (const auto& [period, residue] : strides_) {
    if (first_from(step, period, residue) < next_step) {
      return true;
    }
  }
  return false;
}

std::uint64_t StepNeeds::first_read_step_from(std::uint64_t from) const {
  if (all()) {
    return from;
  }
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max();
  for (const auto& [period, residue] : strides_) {
    first = std::min(first, first_from(from, period, residue));
  }
  return first;
}

void StepNeeds::add(const StepNeeds& other) {
  if (all() || other.all()) {
    *this = StepNeeds{};
    return;
  }
  for (const auto& [period, residue] : other.strides_) {
    add_stride(period, residue);
  }
}

std::string StepNeeds::text() const {
  std::string out = "steps";
  for (const auto& [period, residue] : strides_) {
    out += " " + std::to_string(period) + ":" + std::to_string(residue);
  }
  return out;
}

std::optional<StepNeeds> StepNeeds::parse(const std::string& text) {
  std::istringstream in(text);
  std::string word;
  if (!(in >> word) || word != "steps") {
    return std::nullopt;
  }
  StepNeeds needs;
  while (in >> word) {
    const std::size_t colon = word.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == word.size() ||
        word.find_first_not_of("0123456789:") != std::string::npos || word.find(':', colon + 1) != std::string::npos ||
        colon > 19 || word.size() - colon - 1 > 19) {
      return std::nullopt;
    }
    const std::uint64_t period = std::stoull(word.substr(0, colon));
    const std::uint64_t residue = std::stoull(word.substr(colon + 1));
    if (period < 2 || residue >= period) {
      return std::nullopt;
    }
    needs.add_stride(period, residue);
  }
  return needs;
}

}  // namespace robodds
