// The completeness check of a recording for a lockstep re-run (replay_chain.hpp).
#include "sim/replay_source/replay_chain.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace robodds::replay_source {
namespace {

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

TEST(ChainProblem, AWholeRecordingHasNone) {
  EXPECT_EQ(chain_problem({{"a", "a", 0, 10}, {"a", "a", 10, 20}, {"a", "a", 20, 30}, {"m", "m", 0, kNever}}, 25), "");
  EXPECT_EQ(chain_problem({{"a", "a", 10, 20}, {"a", "a", 0, 10}}, 15), "") << "order in the file does not matter";
  EXPECT_EQ(chain_problem({}, 100), "");
}

TEST(ChainProblem, ALostSampleIsNamed) {
  EXPECT_EQ(chain_problem({{"sensor/position", "sensor/position (robot_id=1)", 0, 10}, {"sensor/position", "sensor/position (robot_id=1)", 20, 30}}, 25),
            "sensor/position (robot_id=1): the sample of step 0 announces step 10 but the next one recorded is of step 20 "
            "(samples were lost while recording)");
}

TEST(ChainProblem, TwoSamplesOfOneStep) {
  EXPECT_EQ(chain_problem({{"a", "a", 0, 10}, {"a", "a", 0, 10}}, 5), "a: two samples of step 0 (two runs in one file?)");
}

TEST(ChainProblem, ARunLongerThanTheRecording) {
  EXPECT_EQ(chain_problem({{"a", "a", 0, 10}, {"a", "a", 10, 20}}, 20),
            "a: the recording ends at step 10 but the run goes to step 20 (shorten the run with --duration or record longer)");
  EXPECT_EQ(chain_problem({{"a", "a", 0, 10}, {"a", "a", 10, 20}}, 19), "") << "the announced step is past the run's end";
}

TEST(ChainProblem, AnInstanceThatEndsInsideTheRecordingEnded) {
  // Robot 1's range to target 1 stops at step 10 (it moved to target 2); the recording goes on.
  EXPECT_EQ(chain_problem({{"r", "r (1,1)", 0, 10}, {"r", "r (1,2)", 10, 20}, {"r", "r (1,2)", 20, 30}}, 25), "");
}

TEST(ChainProblem, OfSeveralTheFirstStreamByNameIsNamed) {
  // Given in any order: "a (10)" sorts before "a (2)" by name, so its problem is the one named.
  const std::vector<ChainLink> links = {{"a", "a (2)", 0, 10},  {"a", "a (2)", 20, 30},  {"a", "a (10)", 30, 40},
                                        {"a", "a (10)", 0, 10}, {"a", "a (10)", 10, 20}};
  EXPECT_EQ(chain_problem(links, 25),
            "a (10): the sample of step 10 announces step 20 but the next one recorded is of step 30 "
            "(samples were lost while recording)");
}

TEST(LateTopics, ATopicWithoutAStepZeroSampleIsNamed) {
  EXPECT_EQ(late_topics({{"p", "p (1)", 0, 10}, {"o", "o (1)", 37, 38}, {"o", "o (2)", 40, 41}}),
            (std::vector<std::string>{"o: its first recorded sample is of step 37"}));
  EXPECT_TRUE(late_topics({{"p", "p (1)", 0, 10}, {"p", "p (2)", 50, 60}}).empty()) << "one instance at step 0 is enough";
}

constexpr std::uint64_t pair(std::uint64_t robot, std::uint64_t peer) { return robot << 32 | peer; }

ChainLink uwb(std::uint64_t robot, std::uint64_t peer, std::uint64_t step) {
  const std::string label = "robot_id=" + std::to_string(robot) + " peer_id=" + std::to_string(peer);
  return {"sensor/uwb", "sensor/uwb (" + label + ")", step, step + 2, pair(robot, peer)};
}

TEST(InstancesOf, EachPairOfTheTopicsOnceAscending) {
  const std::vector<ChainLink> links = {uwb(2, 3, 0), uwb(1, 2, 0), uwb(2, 3, 2), uwb(1, 2, 2),
                                        {"sensor/odometry", "o", 0, 5, 1}};
  const auto instances = instances_of(links, {"sensor/uwb", "estimate/relative_pose"});
  ASSERT_EQ(instances.size(), 1u) << "a topic without links maps to nothing, a topic not asked for is left out";
  EXPECT_EQ(instances.at("sensor/uwb"), (std::vector<std::uint64_t>{pair(1, 2), pair(2, 3)}));
  EXPECT_TRUE(instances_of(links, {}).empty());
}

TEST(ForeignPair, PairsOfTheScenarioRobotsHaveNone) {
  EXPECT_EQ(foreign_pair({uwb(1, 2, 0), uwb(2, 1, 0), uwb(3, 1, 0)}, {"sensor/uwb"}, {1, 2, 3}, {1, 2, 3}), "");
  EXPECT_EQ(foreign_pair({{"sensor/odometry", "o", 0, 5, 9}}, {"sensor/uwb"}, {1}, {1}), "") << "only the pair topics";
}

TEST(ForeignPair, APeerOrRobotTheScenarioDoesNotHaveIsNamed) {
  EXPECT_EQ(foreign_pair({uwb(1, 2, 0), uwb(1, 3, 0)}, {"sensor/uwb"}, {1, 2}, {1, 2}),
            "sensor/uwb (robot_id=1 peer_id=3): robot 3 is not a robot of the scenario (its robots: 1, 2)");
  EXPECT_EQ(foreign_pair({uwb(4, 1, 0)}, {"sensor/uwb"}, {1, 2}, {1, 2}),
            "sensor/uwb (robot_id=4 peer_id=1): robot 4 is not a robot of the scenario (its robots: 1, 2)");
}

TEST(ForeignPair, ARobotTheReplayDoesNotServeIsNamed) {
  EXPECT_EQ(foreign_pair({uwb(1, 2, 0), uwb(2, 1, 0)}, {"sensor/uwb"}, {1}, {1, 2}),
            "sensor/uwb (robot_id=2 peer_id=1): robot 2 is not one of the replay's robots (1)");
}

}  // namespace
}  // namespace robodds::replay_source
