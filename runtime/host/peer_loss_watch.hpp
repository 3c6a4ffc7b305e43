#pragma once
// What a host across processes does when another host of its run goes away (issue 24, finding 6):
// the bus reports participants that dropped (lease expired: killed, frozen, machine or network
// down) or left (goodbye), runtime/bus/peer_losses.hpp; this turns them into the run's reaction.
// Lockstep: the run ends at once naming the group. Real time: the run goes on degraded, naming the
// group and when it was lost (PeerWatch). docs/deployment.md, "Long runs and failures across machines".

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/bus/peer_losses.hpp"
#include "runtime/config/scenario.hpp"
#include "runtime/health/peer_watch.hpp"
#include "runtime/host/loop_alive.hpp"

namespace robodds {

class PeerLossWatch {
 public:
  /// Lockstep: how long a host that lost its coordinator waits for the loss of a group that
  /// explains it (s): a coordinator that ends the run because a group died leaves at about the
  /// moment this host learns that death itself (the same lease, the same last announcement).
  static constexpr double kCoordinatorGraceS = 0.5;
  /// How long a dropped participant has to be discovered again before it counts as lost (s): a
  /// process starved of CPU for longer than the lease (this one or the peer: seen once on a
  /// 2-core machine at load 17) drops alive peers, whose queued or next announcement (every 0.5 s)
  /// brings them back at once. The lease (1.5 s) plus this stays within the 2 s bound.
  static constexpr double kRediscoveryGraceS = 0.4;
  /// Real time: a host that leaves cleanly this close to the run's end (s) ends with it (the hosts
  /// end at the same wall time, apart by their clocks' offset and their last step).
  static constexpr double kEndMarginS = 1.0;

  /// `source` null: nothing to watch (a bus without peers). `member`: this host's group;
  /// `members`: the groups a coordinator in this process waits for. `scenario` must outlive this.
  PeerLossWatch(const PeerLossSource* source, const Scenario& scenario, std::string member, std::vector<std::string> members);

  /// Lockstep, every loop iteration. RunError naming the group when another group's or the
  /// coordinator's participant dropped (and was not discovered again within kRediscoveryGraceS)
  /// while `host_running` (this host has not acknowledged the final step), or a member's while
  /// `coordinating` (this process's coordinator is not done);
  /// or naming the coordinator kCoordinatorGraceS after it left (dropped or goodbye) while
  /// `host_running`. A group that leaves cleanly has acknowledged the final step or reported its
  /// failure to the coordinator, which then ends the run: only its drop counts.
  void check_lockstep(std::uint64_t step, bool host_running, bool coordinating);
  /// The coordinator went away: no one to report this host's failure to.
  bool coordinator_lost() const { return coordinator_lost_; }

  /// Real time, every loop iteration: another group dropped (not back within kRediscoveryGraceS),
  /// or left more than kEndMarginS before
  /// the run's end (`remaining_s`), goes to `watch` as lost at its time after step 0 (from
  /// `elapsed_s`, now) and is logged once as a degraded run; a group whose every component has a
  /// hot standby in another group is logged as taken over instead.
  void check_realtime(PeerWatch& watch, double elapsed_s, double remaining_s);

  /// Real time, every loop iteration: a group whose loop went silent on run/alive while its
  /// participant is alive (`alive`, LoopSilence) goes to `watch` as lost now, as check_realtime's
  /// losses do (or is logged as taken over by its hot standby).
  void check_silent_loops(PeerWatch& watch, LoopAlive& alive, double elapsed_s, double remaining_s);

  /// "'b'" when every component of `group` has a hot standby in another group (those groups,
  /// quoted); "" when one has none.
  std::string standby_groups_of(const std::string& group) const;

 private:
  struct Drop {
    PeerLoss loss;
    std::string group;
  };
  /// `group` lost at `at_s` (s after step 0), `how`: degraded, or taken over by its standby.
  void report_lost(PeerWatch& watch, const std::string& group, double at_s, const std::string& how) const;
  std::vector<PeerLoss> new_losses();  // since the last call; one atomic load when none
  /// The drops of pending_ older than kRediscoveryGraceS whose participant is still gone; those
  /// discovered again are logged and forgotten.
  std::vector<Drop> confirmed_drops();

  const PeerLossSource* source_;
  const Scenario& scenario_;
  std::string member_;
  std::vector<std::string> others_;   // the scenario's groups other than member_
  std::vector<std::string> members_;  // the coordinator's
  std::size_t seen_ = 0;
  std::vector<Drop> pending_;        // dropped groups within their rediscovery grace
  bool coordinator_lost_ = false;
  std::string coordinator_gone_;      // how the coordinator went, once it did
  std::int64_t coordinator_gone_ns_ = 0;
};

}  // namespace robodds
