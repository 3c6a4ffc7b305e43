#include "tools/robodds/sweep_resume.hpp"

#include "common/number_text.hpp"

namespace robodds::sweep {
namespace {

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& w : words) {
    text += (text.empty() ? "" : " ") + w;
  }
  return text;
}

std::string differs(const std::string& option, const std::string& planned, const std::string& given) {
  return option + ": '" + planned + "' in sweep.json, '" + given + "' on the command line";
}

}  // namespace

std::vector<PlannedRun> missing_runs(const std::vector<PlannedRun>& runs, const std::set<std::size_t>& finished) {
  std::vector<PlannedRun> missing;
  for (const PlannedRun& run : runs) {
    if (finished.count(run.index) == 0) {
      missing.push_back(run);
    }
  }
  return missing;
}

std::string spec_difference(const SweepSpec& planned, const SweepSpec& given) {
  if (planned.source != given.source) {
    return differs("the scenario", planned.source, given.source);
  }
  if (planned.seeds != given.seeds) {
    return differs("--seeds", planned.seeds, given.seeds);
  }
  if (planned.grid != given.grid) {
    return differs("--set", joined(planned.grid), joined(given.grid));
  }
  if (planned.run_args != given.run_args) {  // --duration
    return differs("the run options (--duration)", joined(planned.run_args), joined(given.run_args));
  }
  if (planned.run_timeout_s != given.run_timeout_s) {
    return differs("--run-timeout", shortest_text(planned.run_timeout_s), shortest_text(given.run_timeout_s));
  }
  return "";
}

}  // namespace robodds::sweep
