// PeerLossWatch: what a host does when another host of its run goes away (issue 24, finding 6).

#include "runtime/host/peer_loss_watch.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/bus/bus.hpp"

namespace robodds {
namespace {

class FakeLosses : public PeerLossSource {
 public:
  std::size_t peer_loss_count() const override { return losses.size(); }
  std::vector<PeerLoss> peer_losses() const override { return losses; }
  bool participant_alive(const std::string& participant) const override { return alive.count(participant) != 0; }
  /// A loss learnt `age_s` ago (by default past the rediscovery grace: a drop counts at once).
  void add(const std::string& participant, bool dropped, double age_s = 1.0) {
    losses.push_back(PeerLoss{participant, dropped, monotonic_now_ns() - static_cast<std::int64_t>(age_s * 1e9)});
  }
  std::vector<PeerLoss> losses;
  std::set<std::string> alive;
};

Scenario groups_scenario() {
  Scenario s;
  s.components = {{"plant", "plant", {}, {}, ""}, {"sensor", "position_sensor", {}, {}, ""},
                  {"estimator", "pf_estimator", {}, {}, ""}, {"estimator_standby", "pf_estimator", {}, {}, "estimator"}};
  s.groups = {{"sim", {"plant"}}, {"sensing", {"sensor"}}, {"estimation", {"estimator"}}, {"standby", {"estimator_standby"}}};
  return s;
}

std::string error_of(PeerLossWatch& watch, std::uint64_t step, bool host_running, bool coordinating) {
  try {
    watch.check_lockstep(step, host_running, coordinating);
  } catch (const RunError& e) {
    return e.what();
  }
  return "";
}

TEST(PeerLossWatch, LockstepAGroupThatDropsEndsTheRunNamingIt) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  EXPECT_EQ(error_of(watch, 5, true, false), "");
  source.add("robodds-sensing", true);
  EXPECT_EQ(error_of(watch, 42, true, false),
            "lockstep: group 'sensing' lost at step 42: its participant 'robodds-sensing' dropped: no announcement within its "
            "lease (killed, frozen, or its machine or network down)");
}

// A drop whose participant is discovered again within the grace was a stall (this process or the
// peer starved of CPU for longer than the lease), not a death; one still gone after it is lost.
TEST(PeerLossWatch, ADropDiscoveredAgainWithinTheGraceIsAStallNotALoss) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  source.add("robodds-sensing", true, 0.0);
  EXPECT_EQ(error_of(watch, 10, true, false), "") << "within the grace";
  source.alive.insert("robodds-sensing");
  std::this_thread::sleep_for(std::chrono::duration<double>(PeerLossWatch::kRediscoveryGraceS + 0.05));
  EXPECT_EQ(error_of(watch, 11, true, false), "") << "back: not lost";
  PeerWatch peers({}, 30.0);
  FakeLosses later;
  PeerLossWatch realtime(&later, scenario, "sim", {});
  later.add("robodds-sensing", true, 0.0);
  realtime.check_realtime(peers, 5.0, 5.0);
  EXPECT_EQ(peers.degraded(), "") << "within the grace";
  std::this_thread::sleep_for(std::chrono::duration<double>(PeerLossWatch::kRediscoveryGraceS + 0.05));
  realtime.check_realtime(peers, 5.5, 4.5);
  EXPECT_NE(peers.degraded().find("lost group 'sensing' at"), std::string::npos) << "still gone after the grace: lost";
}

TEST(PeerLossWatch, LockstepAGroupThatLeavesCleanlyOrAStrangerIsNoLoss) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  source.add("robodds-sensing", false);  // acknowledged the final step, or reported its failure
  source.add("robodds-topics", true);    // a tool, not a group of the run
  EXPECT_EQ(error_of(watch, 1, true, false), "");
}

TEST(PeerLossWatch, LockstepAfterTheFinalAcknowledgementNothingCounts) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  source.add("robodds-sensing", true);
  source.add("robodds-coordinator", false);
  EXPECT_EQ(error_of(watch, 100, false, false), "");
}

TEST(PeerLossWatch, LockstepTheCoordinatorFailsWhenAMemberDrops) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "coordinator", {"sim", "sensing"});
  source.add("robodds-estimation", false);
  EXPECT_EQ(error_of(watch, 3, false, true), "") << "a member's goodbye comes with its failure report";
  source.add("robodds-sensing", true);
  EXPECT_NE(error_of(watch, 3, false, true).find("group 'sensing' lost at step 3"), std::string::npos);
}

// The coordinator that leaves is explained by a group loss that arrives just after it when there
// is one; otherwise the host names the coordinator after the grace period.
TEST(PeerLossWatch, LockstepALostCoordinatorWaitsBrieflyForTheGroupThatExplainsIt) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  source.add("robodds-coordinator", false);
  EXPECT_EQ(error_of(watch, 7, true, false), "") << "within the grace period";
  source.add("robodds-sensing", true);
  EXPECT_NE(error_of(watch, 7, true, false).find("group 'sensing' lost"), std::string::npos);
  EXPECT_FALSE(watch.coordinator_lost());

  FakeLosses alone;
  PeerLossWatch other(&alone, scenario, "sim", {});
  alone.add("robodds-run", false);  // the runner of --deploy processes
  EXPECT_EQ(error_of(other, 7, true, false), "");
  std::this_thread::sleep_for(std::chrono::duration<double>(PeerLossWatch::kCoordinatorGraceS + 0.05));
  EXPECT_EQ(error_of(other, 7, true, false),
            "sim: lockstep: the coordinator was lost at step 7: its participant 'robodds-run' left before the run's end (it "
            "failed or was stopped)");
  EXPECT_TRUE(other.coordinator_lost());
}

TEST(PeerLossWatch, RealTimeALostGroupDegradesTheRunWithItsTime) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  PeerWatch peers({"sensing"}, 30.0);
  source.add("robodds-sensing", true);
  watch.check_realtime(peers, 5.5, 4.5);  // learnt 1 s ago: lost at 4.5 s
  EXPECT_EQ(peers.degraded().rfind("lost group 'sensing' at 4.5 s after the start (its participant 'robodds-sensing' dropped", 0), 0u)
      << peers.degraded();
}

TEST(PeerLossWatch, RealTimeAGoodbyeAtTheEndIsTheEndButEarlierALoss) {
  const Scenario scenario = groups_scenario();
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  PeerWatch peers({}, 30.0);
  source.add("robodds-sensing", false);
  watch.check_realtime(peers, 9.6, 0.4);
  EXPECT_EQ(peers.degraded(), "");
  PeerLossWatch early(&source, scenario, "estimation", {});
  early.check_realtime(peers, 3.0, 7.0);  // learnt 1 s ago: lost at 2 s
  EXPECT_NE(peers.degraded().find("lost group 'sensing' at 2 s after the start (its participant 'robodds-sensing' left"),
            std::string::npos)
      << peers.degraded();
}

TEST(PeerLossWatch, RealTimeAGroupCoveredByAHotStandbyIsTakenOverNotLost) {
  const Scenario scenario = groups_scenario();
  EXPECT_EQ(PeerLossWatch(nullptr, scenario, "sim", {}).standby_groups_of("estimation"), "'standby'");
  EXPECT_EQ(PeerLossWatch(nullptr, scenario, "sim", {}).standby_groups_of("sensing"), "");
  FakeLosses source;
  PeerLossWatch watch(&source, scenario, "sim", {});
  PeerWatch peers({}, 30.0);
  source.add("robodds-estimation", true);
  watch.check_realtime(peers, 7.0, 7.0);
  EXPECT_EQ(peers.degraded(), "");
  source.add("robodds-standby", true);  // the standby itself has none
  watch.check_realtime(peers, 8.0, 6.0);
  EXPECT_NE(peers.degraded().find("lost group 'standby'"), std::string::npos) << peers.degraded();
}

TEST(PeerLossWatch, WithoutASourceNothingHappens) {
  const Scenario scenario = groups_scenario();
  PeerLossWatch watch(nullptr, scenario, "sim", {"sensing"});
  EXPECT_EQ(error_of(watch, 1, true, true), "");
}

}  // namespace
}  // namespace robodds
