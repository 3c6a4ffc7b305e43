#pragma once
// Real time across processes: does this host see the groups it runs with? A host whose peers
// never appear on the domain (a discovery server that died before it started, multicast blocked)
// would otherwise run alone, receive nothing and end "completed". After `deadline_s` on its own
// clock the host compares the participants it discovered (the host names each "robodds-<group>",
// DdsOptions::participant_name) with the scenario's other groups it exchanges a topic with (the
// host works them out from the scenario: Host::Impl::peer_watch()); those missing make the run
// degraded: logged at once, in the host's health report (summary.json "status": "degraded") and
// in its exit code (docs/deployment.md, "Long runs and failures across machines").

#include <string>
#include <vector>

namespace robodds {

/// The participant name a host of group `group` uses ("robodds-<group>").
std::string participant_name_of_group(const std::string& group);
/// The group among `groups` whose host uses participant name `participant`; "" for none.
std::string group_of_participant(const std::string& participant, const std::vector<std::string>& groups);

class PeerWatch {
 public:
  /// `others`: the scenario's other groups (none: nothing to watch); `deadline_s`: s after the
  /// run's start by which they must have been discovered.
  PeerWatch(std::vector<std::string> others, double deadline_s);

  /// Checks once, at the first call with `elapsed_s` >= the deadline (or with `run_ended`: a run
  /// shorter than the deadline is judged at its end), which of the other groups have no
  /// participant in `discovered` (participant names), and, given `heard` (the groups whose run/alive
  /// beats arrived; null: not known), which were discovered but never heard: their participant was
  /// relayed but none of their topics matched (seen with a Discovery Server restarted within its
  /// lease, docs/deployment.md). True when that made the run degraded (then degraded() says why);
  /// later calls only note groups that turned up (or were heard) late.
  bool check(double elapsed_s, const std::vector<std::string>& discovered, bool run_ended = false,
             const std::vector<std::string>* heard = nullptr);

  /// Real time: group `group` was lost `at_s` after the start (its participant's lease expired,
  /// or it left before the run's end): the run is degraded from then on. `how` says how, e.g.
  /// "its participant dropped". Only the first loss of each group is kept; returns whether this
  /// one was new.
  bool lost(const std::string& group, double at_s, const std::string& how);

  /// Empty while nothing is missing or lost; else e.g. "did not discover group(s) 'sim',
  /// 'control' within 10 s of its start (discovered later: 'sim')", or for a run that ended
  /// before the deadline "... during its run (6 s, shorter than the start timeout of 30 s)",
  /// and "lost group 'estimation' at 5.2 s after the start (its participant dropped)", joined by "; ".
  std::string degraded() const;
  bool checked() const { return checked_; }
  /// The groups this host watches (the constructor's `others`).
  const std::vector<std::string>& others() const { return others_; }

 private:
  std::string discovery_text() const;  // degraded()'s part about discovery at the deadline

  std::vector<std::string> others_;
  double deadline_s_;
  bool checked_ = false;
  double judged_s_ = 0.0;  // s after the start when it was checked
  std::vector<std::string> missing_;
  std::vector<std::string> unheard_;  // discovered but never heard at the deadline
  std::vector<std::string> late_;  // missing or unheard at the deadline, found since
  std::vector<std::string> lost_;  // lost(): "lost group 'x' at T s after the start (how)"
  std::vector<std::string> lost_groups_;
};

}  // namespace robodds
