#include "runtime/health/loop_silence.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

const auto kAlive = [](const std::string&) { return true; };

TEST(LoopSilence, NamesAGroupSilentBeyondTheLimitOnce) {
  LoopSilence watch({"sensing", "control"});
  watch.heard("sensing", 4.0);
  watch.heard("control", 4.0);
  watch.heard("control", 5.8);
  EXPECT_TRUE(watch.check(5.85, 10.0, kAlive).empty());  // 1.85 s: not beyond the limit yet
  const auto silent = watch.check(5.95, 10.0, kAlive);
  ASSERT_EQ(silent.size(), 1u);
  EXPECT_EQ(silent[0].group, "sensing");
  EXPECT_DOUBLE_EQ(silent[0].last_heard_s, 4.0);
  EXPECT_TRUE(watch.check(7.0, 10.0, kAlive).empty());  // once per run
}

TEST(LoopSilence, RegularBeatsAreNeverSilent) {
  LoopSilence watch({"sensing"});
  for (double t = 0.0; t < 10.0; t += LoopSilence::kBeatPeriodS) {
    watch.heard("sensing", t);
    EXPECT_TRUE(watch.check(t + 0.05, 10.0, kAlive).empty()) << t;
  }
}

TEST(LoopSilence, AGroupNeverHeardIsNotJudged) {
  LoopSilence watch({"sensing"});
  EXPECT_TRUE(watch.check(30.0, 60.0, kAlive).empty());
}

TEST(LoopSilence, ADeadParticipantIsLeftToTheLeaseWatch) {
  LoopSilence watch({"sensing"});
  watch.heard("sensing", 1.0);
  bool alive = false;
  const auto participant_alive = [&alive](const std::string& group) { return group == "sensing" && alive; };
  EXPECT_TRUE(watch.check(5.0, 60.0, participant_alive).empty());
  alive = true;  // discovered again, still silent: a live process whose loop stopped
  EXPECT_EQ(watch.check(5.1, 60.0, participant_alive).size(), 1u);
}

TEST(LoopSilence, ASilenceThatBeganAtTheRunsEndIsItsEnd) {
  LoopSilence watch({"sensing"});
  watch.heard("sensing", 9.2);  // the run ends at 10 s; its host ended with it
  EXPECT_TRUE(watch.check(11.5, 10.0, kAlive).empty());
  LoopSilence early({"sensing"});
  early.heard("sensing", 8.0);  // stopped 2 s before the end
  EXPECT_EQ(early.check(10.0, 10.0, kAlive).size(), 1u);
}

TEST(LoopSilence, GroupsNotWatchedAreIgnored) {
  LoopSilence watch({"sensing"});
  watch.heard("other", 0.0);
  EXPECT_TRUE(watch.check(5.0, 60.0, kAlive).empty());
}

TEST(LoopSilence, HeardGroupsAreTheWatchedOnesABeatArrivedFrom) {
  LoopSilence silence({"sim", "sensing"});
  EXPECT_TRUE(silence.heard_groups().empty());
  silence.heard("sensing", 1.0);
  silence.heard("stranger", 1.0);  // not watched
  EXPECT_EQ(silence.heard_groups(), std::vector<std::string>{"sensing"});
}

}  // namespace
}  // namespace robodds
