#pragma once
// A host whose loop stopped stepping while its process lives on (a component's step that never
// returns: a deadlock, an endless loop, a blocking call), issue 24 finding 6. Its participant's
// lease is kept alive by Fast DDS's own threads, so PeerLossWatch never sees it go. In real time
// every host across processes says "my loop ran" on run/alive every kBeatPeriodS (LoopAlive);
// this decides, from when each group was last heard, which one went silent. Pure logic: time as
// plain seconds after the run's step 0 on this host's clock.

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace robodds {

class LoopSilence {
 public:
  /// How often a real-time host's loop says it ran (s, wall time).
  static constexpr double kBeatPeriodS = 0.2;
  /// Silence after which a group whose participant is alive counts as lost (s): the participant
  /// lease (1.5 s, deploy/qos) plus PeerLossWatch's rediscovery grace (0.4 s), so a stalled loop
  /// is named within the same 2 s as a dead process, and a process starved of CPU for less than a
  /// lease (which PeerLossWatch forgives as a stall) is not named either.
  static constexpr double kSilenceLimitS = 1.9;
  /// A silence that began this close to the run's end (s) is the group ending with the run.
  static constexpr double kEndMarginS = 1.0;

  struct Silent {
    std::string group;
    double last_heard_s = 0.0;  // s after step 0 (this host's clock), when its last beat arrived
  };

  /// `groups`: the other groups to watch. A group is judged only once it was heard at least once
  /// (one never heard is PeerWatch's: not discovered within the start timeout).
  explicit LoopSilence(std::vector<std::string> groups);

  /// A beat of `group` arrived at `elapsed_s`. Groups not watched are ignored.
  void heard(const std::string& group, double elapsed_s);

  /// The groups silent for more than kSilenceLimitS at `elapsed_s`, each returned once per run,
  /// leaving out those whose silence began within kEndMarginS of the run's end (`end_s`, s after
  /// step 0) and those whose participant is not alive (`participant_alive(group)` false: a dead or
  /// dropped process is PeerLossWatch's to name, with its own reason).
  std::vector<Silent> check(double elapsed_s, double end_s, const std::function<bool(const std::string&)>& participant_alive);

  /// The watched groups heard at least once (PeerWatch: a group whose participant was discovered
  /// but whose loop was never heard shares no topic with this host in practice).
  std::vector<std::string> heard_groups() const;

 private:
  struct Group {
    bool heard = false;
    double last_heard_s = 0.0;
    bool named = false;
  };
  std::map<std::string, Group> groups_;
};

}  // namespace robodds
