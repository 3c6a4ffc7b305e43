#include "runtime/health/peer_watch.hpp"

#include <algorithm>
#include <cmath>

#include "common/number_text.hpp"

namespace robodds {
namespace {

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) {
    text += (text.empty() ? "'" : ", '") + name + "'";
  }
  return text;
}

}  // namespace

std::string participant_name_of_group(const std::string& group) { return "robodds-" + group; }

std::string group_of_participant(const std::string& participant, const std::vector<std::string>& groups) {
  for (const std::string& group : groups) {
    if (participant == participant_name_of_group(group)) {
      return group;
    }
  }
  return "";
}

PeerWatch::PeerWatch(std::vector<std::string> others, double deadline_s) : others_(std::move(others)), deadline_s_(deadline_s) {}

bool PeerWatch::check(double elapsed_s, const std::vector<std::string>& discovered, bool run_ended,
                      const std::vector<std::string>* heard) {
  const auto found = [&](const std::string& group) {
    return has(discovered, participant_name_of_group(group)) && (heard == nullptr || has(*heard, group));
  };
  if (!checked_) {
    if (elapsed_s < deadline_s_ && !run_ended) {
      return false;
    }
    checked_ = true;
    judged_s_ = elapsed_s;
    for (const std::string& group : others_) {
      if (!has(discovered, participant_name_of_group(group))) {
        missing_.push_back(group);
      } else if (!found(group)) {
        unheard_.push_back(group);
      }
    }
    return !missing_.empty() || !unheard_.empty();
  }
  for (const std::vector<std::string>* judged : {&missing_, &unheard_}) {
    for (const std::string& group : *judged) {
      if (!has(late_, group) && found(group)) {
        late_.push_back(group);
      }
    }
  }
  return false;
}

bool PeerWatch::lost(const std::string& group, double at_s, const std::string& how) {
  if (has(lost_groups_, group)) {
    return false;
  }
  lost_groups_.push_back(group);
  lost_.push_back("lost group '" + group + "' at " + shortest_text(std::round(at_s * 100.0) / 100.0) + " s after the start (" +
                  how + ")");
  return true;
}

std::string PeerWatch::degraded() const {
  std::string text = discovery_text();
  for (const std::string& loss : lost_) {
    text += (text.empty() ? "" : "; ") + loss;
  }
  return text;
}

std::string PeerWatch::discovery_text() const {
  if (missing_.empty() && unheard_.empty()) {
    return "";
  }
  const std::string when = judged_s_ < deadline_s_ ? " during its run (" + shortest_text(std::round(judged_s_ * 10.0) / 10.0) +
                                                         " s, shorter than the start timeout of " + shortest_text(deadline_s_) + " s)"
                                                   : " within " + shortest_text(deadline_s_) + " s of its start";
  std::string text;
  if (!missing_.empty()) {
    text = "did not discover group(s) " + quoted_list(missing_) + when;
  }
  if (!unheard_.empty()) {
    text += (text.empty() ? "" : "; ") + std::string("discovered group(s) ") + quoted_list(unheard_) + " but heard nothing from them" +
            when + " (their participant was seen, none of their topics matched: e.g. a Discovery Server restarted within its lease)";
  }
  if (missing_.size() == others_.size()) {
    text += ": no participant of the run at all (are the other hosts running, on the same domain, and is discovery reachable:"
            " multicast, or the discovery server?)";
  }
  if (!late_.empty()) {
    text += " (discovered later: " + quoted_list(late_) + ")";
  }
  return text;
}

}  // namespace robodds
