#include "runtime/launch/coordinator_scenario.hpp"

#include <algorithm>
#include <set>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    text += (i == 0 ? "" : ",") + items[i];
  }
  return text;
}

}  // namespace

std::vector<std::string> split_members(const std::string& text) {
  std::vector<std::string> members;
  if (text.empty()) {
    return members;  // none given: check_members() says what to give
  }
  std::size_t begin = 0;
  for (std::size_t comma = text.find(','); comma != std::string::npos; comma = text.find(',', begin)) {
    members.push_back(text.substr(begin, comma - begin));
    begin = comma + 1;
  }
  members.push_back(text.substr(begin));
  return members;
}

void check_members(const std::vector<std::string>& members) {
  if (members.empty()) {
    throw ConfigError("--members: give the members to wait for, e.g. --members sim,sensing (each component executable's "
                      "--member, by default its --name, by default its type)");
  }
  const std::string list = "--members '" + joined(members) + "': ";
  std::set<std::string> seen;
  for (std::size_t i = 0; i < members.size(); ++i) {
    const std::string& member = members[i];
    if (member.empty()) {
      throw ConfigError(list + "member " + std::to_string(i + 1) + " is empty");
    }
    if (member.size() > kMaxMemberLength) {
      throw ConfigError(list + "'" + member + "' is longer than " + std::to_string(kMaxMemberLength) + " characters");
    }
    if (!seen.insert(member).second) {
      throw ConfigError(list + "'" + member + "' is given twice");
    }
  }
}

Scenario coordinator_scenario(const HostArgs& args) {
  if (!args.robots.empty() || !args.name.empty() || !args.params.empty() || !args.sets.empty() || !args.group.empty() ||
      !args.components.empty()) {
    throw ConfigError("a coordinator without a scenario runs no component: --robot, --name, --params, --set, --group and "
                      "--components belong to the component executables it coordinates");
  }
  check_members(args.members);
  if (!args.duration_s) {
    throw ConfigError("--duration is required without a scenario: the coordinator ends the run there (s)");
  }
  Scenario scenario;
  scenario.file = "(command line of the coordinator)";
  scenario.name = "coordinate";
  scenario.description = "a lockstep coordinator of component executables, without a scenario file";
  scenario.step_s = args.step_s.value_or(kStandaloneStepS);
  scenario.duration_s = *args.duration_s;
  scenario.seed = args.seed.value_or(1);
  checked_last_step(scenario.step_s, scenario.duration_s, "", "--duration");
  return scenario;
}

}  // namespace robodds
