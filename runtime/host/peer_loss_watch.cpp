#include "runtime/host/peer_loss_watch.hpp"

#include <algorithm>
#include <cmath>

#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/bus.hpp"

namespace robodds {
namespace {

/// Participant names of a lockstep coordinator without components: `robodds host --coordinate`
/// ("coordinator") and the runner of `robodds run --deploy processes` ("run").
bool is_coordinator(const std::string& participant) {
  return participant == participant_name_of_group("coordinator") || participant == participant_name_of_group("run");
}

std::string how_lost(const PeerLoss& loss) {
  return loss.dropped ? "its participant '" + loss.participant +
                            "' dropped: no announcement within its lease (killed, frozen, or its machine or network down)"
                      : "its participant '" + loss.participant + "' left before the run's end (it failed or was stopped)";
}

std::string lost_at_step(const std::string& group, std::uint64_t step, const PeerLoss& loss) {
  return "lockstep: group '" + group + "' lost at step " + std::to_string(step) + ": " + how_lost(loss);
}

}  // namespace

PeerLossWatch::PeerLossWatch(const PeerLossSource* source, const Scenario& scenario, std::string member,
                             std::vector<std::string> members)
    : source_(source), scenario_(scenario), member_(std::move(member)), members_(std::move(members)) {
  for (const GroupSpec& group : scenario_.groups) {
    if (group.name != member_) {
      others_.push_back(group.name);
    }
  }
}

std::vector<PeerLoss> PeerLossWatch::new_losses() {
  if (source_ == nullptr || source_->peer_loss_count() == seen_) {
    return {};
  }
  std::vector<PeerLoss> all = source_->peer_losses();
  std::vector<PeerLoss> fresh(all.begin() + static_cast<std::ptrdiff_t>(std::min(seen_, all.size())), all.end());
  seen_ = all.size();
  return fresh;
}

std::vector<PeerLossWatch::Drop> PeerLossWatch::confirmed_drops() {
  std::vector<Drop> confirmed;
  std::vector<Drop> waiting;
  const std::int64_t now_ns = monotonic_now_ns();
  for (Drop& drop : pending_) {
    if (source_->participant_alive(drop.loss.participant)) {
      const double back_after_s = std::round(static_cast<double>(now_ns - drop.loss.at_ns) * 1e-7) / 100.0;
      log::warn(member_, "participant '" + drop.loss.participant + "' dropped and was discovered again " +
                             shortest_text(back_after_s) + " s later: a stall (of this process or of group '" + drop.group +
                             "'), not a death; the run goes on");
    } else if (static_cast<double>(now_ns - drop.loss.at_ns) * 1e-9 > kRediscoveryGraceS) {
      confirmed.push_back(std::move(drop));
    } else {
      waiting.push_back(std::move(drop));
    }
  }
  pending_ = std::move(waiting);
  return confirmed;
}

void PeerLossWatch::check_lockstep(std::uint64_t step, bool host_running, bool coordinating) {
  for (const PeerLoss& loss : new_losses()) {
    if (host_running && is_coordinator(loss.participant) && coordinator_gone_.empty()) {
      coordinator_gone_ = how_lost(loss);
      coordinator_gone_ns_ = monotonic_now_ns();
    }
    if (!loss.dropped) {
      continue;
    }
    std::string group = host_running ? group_of_participant(loss.participant, others_) : "";
    if (group.empty() && coordinating) {
      group = group_of_participant(loss.participant, members_);
    }
    if (!group.empty()) {
      pending_.push_back(Drop{loss, group});
    }
  }
  for (const Drop& drop : confirmed_drops()) {
    if ((host_running && group_of_participant(drop.loss.participant, others_) == drop.group) ||
        (coordinating && group_of_participant(drop.loss.participant, members_) == drop.group)) {
      throw RunError(lost_at_step(drop.group, step, drop.loss));
    }
  }
  if (host_running && !coordinator_gone_.empty() &&
      static_cast<double>(monotonic_now_ns() - coordinator_gone_ns_) * 1e-9 > kCoordinatorGraceS) {
    if (source_->participant_alive(participant_name_of_group("coordinator")) ||
        source_->participant_alive(participant_name_of_group("run"))) {
      coordinator_gone_.clear();  // dropped and discovered again: a stall, not a death
      return;
    }
    coordinator_lost_ = true;
    throw RunError(member_ + ": lockstep: the coordinator was lost at step " + std::to_string(step) + ": " + coordinator_gone_);
  }
}

void PeerLossWatch::check_realtime(PeerWatch& watch, double elapsed_s, double remaining_s) {
  std::vector<Drop> lost;  // a clean goodbye counts at once, a drop once confirmed
  for (const PeerLoss& loss : new_losses()) {
    std::string group = group_of_participant(loss.participant, others_);
    if (group.empty() || (!loss.dropped && remaining_s < kEndMarginS)) {
      continue;
    }
    (loss.dropped ? pending_ : lost).push_back(Drop{loss, std::move(group)});
  }
  for (Drop& drop : confirmed_drops()) {
    lost.push_back(std::move(drop));
  }
  for (const auto& [loss, group] : lost) {
    report_lost(watch, group, elapsed_s - static_cast<double>(monotonic_now_ns() - loss.at_ns) * 1e-9, how_lost(loss));
  }
}

void PeerLossWatch::check_silent_loops(PeerWatch& watch, LoopAlive& alive, double elapsed_s, double remaining_s) {
  const auto participant_alive = [this](const std::string& group) {
    return source_ != nullptr && source_->participant_alive(participant_name_of_group(group));
  };
  for (const LoopSilence::Silent& silent : alive.silent(elapsed_s, elapsed_s + remaining_s, participant_alive)) {
    report_lost(watch, silent.group, elapsed_s,
                "its loop stopped: nothing on run/alive since " + shortest_text(std::round(silent.last_heard_s * 100.0) / 100.0) +
                    " s while its participant is alive");
  }
}

void PeerLossWatch::report_lost(PeerWatch& watch, const std::string& group, double at_s, const std::string& how) const {
  const std::string standbys = standby_groups_of(group);
  if (!standbys.empty()) {
    log::warn(member_, "group '" + group + "' lost at " + shortest_text(std::round(at_s * 100.0) / 100.0) +
                           " s after the start (" + how + "); its hot standby in " + standbys + " takes over");
    return;
  }
  if (watch.lost(group, at_s, how)) {
    log::warn(member_, "degraded: " + watch.degraded() + "; the run goes on (the components' own input timeouts stop what depended on it)");
  }
}

std::string PeerLossWatch::standby_groups_of(const std::string& group) const {
  std::string groups;
  for (const std::string& primary : scenario_.group(group).components) {
    std::string found;
    for (const GroupSpec& other : scenario_.groups) {
      for (const std::string& name : other.components) {
        if (other.name != group && scenario_.component(name).standby_for == primary) {
          found = other.name;
        }
      }
    }
    if (found.empty()) {
      return "";
    }
    if (groups.find("'" + found + "'") == std::string::npos) {
      groups += (groups.empty() ? "'" : ", '") + found + "'";
    }
  }
  return groups;
}

}  // namespace robodds
