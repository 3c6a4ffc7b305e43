#include "runtime/health/loop_silence.hpp"

#include <utility>

namespace robodds {

LoopSilence::LoopSilence(std::vector<std::string> groups) {
  for (std::string& group : groups) {
    groups_.emplace(std::move(group), Group{});
  }
}

void LoopSilence::heard(const std::string& group, double elapsed_s) {
  auto it = groups_.find(group);
  if (it == groups_.end()) {
    return;
  }
  it->second.heard = true;
  it->second.last_heard_s = elapsed_s;
}

std::vector<LoopSilence::Silent> LoopSilence::check(double elapsed_s, double end_s,
                                                   const std::function<bool(const std::string&)>& participant_alive) {
  std::vector<Silent> silent;
  for (auto& [name, group] : groups_) {
    if (!group.heard || group.named || elapsed_s - group.last_heard_s <= kSilenceLimitS ||
        group.last_heard_s >= end_s - kEndMarginS || !participant_alive(name)) {
      continue;
    }
    group.named = true;
    silent.push_back(Silent{name, group.last_heard_s});
  }
  return silent;
}

std::vector<std::string> LoopSilence::heard_groups() const {
  std::vector<std::string> heard;
  for (const auto& [name, group] : groups_) {
    if (group.heard) {
      heard.push_back(name);
    }
  }
  return heard;
}

}  // namespace robodds
