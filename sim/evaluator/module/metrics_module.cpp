#include "sim/evaluator/module/metrics_module.hpp"

namespace robodds::evaluator {

std::optional<std::string> mission_verdict(const std::vector<std::optional<std::vector<std::string>>>& verdicts) {
  bool judged = false;
  std::string reasons;
  for (const auto& verdict : verdicts) {
    if (!verdict) {
      continue;
    }
    judged = true;
    for (const std::string& reason : *verdict) {
      reasons += (reasons.empty() ? "" : "; ") + reason;
    }
  }
  if (!judged) {
    return std::nullopt;
  }
  return reasons.empty() ? std::string("complete") : "incomplete: " + reasons;
}

}  // namespace robodds::evaluator
