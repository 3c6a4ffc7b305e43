#include "runtime/health/peer_watch.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(PeerWatch, NothingIsJudgedBeforeTheDeadline) {
  PeerWatch watch({"sim", "control"}, 10.0);
  EXPECT_FALSE(watch.check(9.9, {}));
  EXPECT_FALSE(watch.checked());
  EXPECT_EQ(watch.degraded(), "");
}

TEST(PeerWatch, EveryGroupDiscoveredIsNotDegraded) {
  PeerWatch watch({"sim", "control"}, 10.0);
  EXPECT_FALSE(watch.check(10.0, {"robodds-control", "robodds-sim", "robodds-topics"}));
  EXPECT_TRUE(watch.checked());
  EXPECT_EQ(watch.degraded(), "");
}

TEST(PeerWatch, NoParticipantAtAllNamesEveryGroupAndSaysNoneWasSeen) {
  PeerWatch watch({"sim", "control"}, 3.0);
  EXPECT_TRUE(watch.check(3.5, {"someone-else"}));
  const std::string why = watch.degraded();
  EXPECT_NE(why.find("did not discover group(s) 'sim', 'control' within 3 s"), std::string::npos) << why;
  EXPECT_NE(why.find("no participant of the run at all"), std::string::npos) << why;
}

TEST(PeerWatch, APartlyMissingRunNamesTheMissingAndThoseThatCameLate) {
  PeerWatch watch({"sim", "control", "evaluation"}, 3.0);
  EXPECT_TRUE(watch.check(3.0, {"robodds-evaluation"}));
  EXPECT_EQ(watch.degraded().find("no participant of the run at all"), std::string::npos) << watch.degraded();
  EXPECT_FALSE(watch.check(8.0, {"robodds-evaluation", "robodds-control"})) << "degraded once, not again";
  EXPECT_EQ(watch.degraded(), "did not discover group(s) 'sim', 'control' within 3 s of its start (discovered later: 'control')");
}

// A group whose participant was relayed to this host but none of whose topics matched (a Discovery
// Server restarted within its lease: integration.netns_discovery_restart's failure before the
// server got the clients' lease) is discovered but never heard on run/alive: degraded, named.
TEST(PeerWatch, AGroupDiscoveredButNeverHeardIsDegradedAndNamed) {
  PeerWatch watch({"sim", "sensing"}, 10.0);
  const std::vector<std::string> both{"robodds-sim", "robodds-sensing"};
  const std::vector<std::string> only_sim{"sim"};
  EXPECT_TRUE(watch.check(10.0, both, false, &only_sim));
  EXPECT_EQ(watch.degraded(),
            "discovered group(s) 'sensing' but heard nothing from them within 10 s of its start (their participant was seen, none "
            "of their topics matched: e.g. a Discovery Server restarted within its lease)");
  const std::vector<std::string> all{"sim", "sensing"};
  EXPECT_FALSE(watch.check(12.0, both, false, &all)) << "degraded once, not again";
  EXPECT_NE(watch.degraded().find("(discovered later: 'sensing')"), std::string::npos) << watch.degraded();
}

TEST(PeerWatch, WithoutBeatsToGoByDiscoveryAloneCounts) {
  PeerWatch watch({"sim", "sensing"}, 10.0);
  EXPECT_FALSE(watch.check(10.0, {"robodds-sim", "robodds-sensing"}));
  EXPECT_EQ(watch.degraded(), "");
  PeerWatch heard_all({"sim", "sensing"}, 10.0);
  const std::vector<std::string> all{"sensing", "sim"};
  EXPECT_FALSE(heard_all.check(10.0, {"robodds-sim", "robodds-sensing"}, false, &all));
  PeerWatch missing_and_unheard({"sim", "sensing", "control"}, 10.0);
  const std::vector<std::string> none;
  EXPECT_TRUE(missing_and_unheard.check(10.0, {"robodds-sim", "robodds-sensing"}, false, &none));
  EXPECT_EQ(missing_and_unheard.degraded().find("did not discover group(s) 'control' within 10 s of its start; discovered group(s) "
                                                "'sim', 'sensing' but heard nothing"),
            0u)
      << missing_and_unheard.degraded();
}

// A run shorter than the start timeout is judged at its end, and says so (it did not wait 30 s).
TEST(PeerWatch, ARunShorterThanTheDeadlineIsJudgedAtItsEnd) {
  PeerWatch watch({"sim", "control"}, 30.0);
  EXPECT_FALSE(watch.check(6.04, {"robodds-sim"})) << "not at the deadline yet";
  EXPECT_TRUE(watch.check(6.04, {"robodds-sim"}, true));
  EXPECT_EQ(watch.degraded(), "did not discover group(s) 'control' during its run (6 s, shorter than the start timeout of 30 s)");
  PeerWatch everyone({"sim"}, 30.0);
  EXPECT_FALSE(everyone.check(2.0, {"robodds-sim"}, true));
  EXPECT_EQ(everyone.degraded(), "");
}

// Issue 24, finding 6: a group lost during the run is named with the time, once, next to what
// discovery found missing.
TEST(PeerWatch, ALostGroupIsNamedWithItsTimeOnce) {
  PeerWatch watch({"sim", "estimation"}, 3.0);
  EXPECT_TRUE(watch.lost("estimation", 5.2345, "its participant dropped"));
  EXPECT_FALSE(watch.lost("estimation", 6.0, "its participant left")) << "the first loss of a group counts";
  EXPECT_EQ(watch.degraded(), "lost group 'estimation' at 5.23 s after the start (its participant dropped)");
  EXPECT_TRUE(watch.check(3.0, {"robodds-estimation"}));
  EXPECT_EQ(watch.degraded(),
            "did not discover group(s) 'sim' within 3 s of its start; lost group 'estimation' at 5.23 s after the start "
            "(its participant dropped)");
}

TEST(PeerWatch, TheGroupOfAParticipantIsFoundByItsName) {
  EXPECT_EQ(group_of_participant("robodds-estimation", {"sim", "estimation"}), "estimation");
  EXPECT_EQ(group_of_participant("robodds-topics", {"sim", "estimation"}), "");
  EXPECT_EQ(group_of_participant("estimation", {"sim", "estimation"}), "");
}

TEST(PeerWatch, AHostWithoutOtherGroupsWatchesNothing) {
  PeerWatch watch({}, 1.0);
  EXPECT_FALSE(watch.check(5.0, {}));
  EXPECT_EQ(watch.degraded(), "");
}

}  // namespace
}  // namespace robodds
