// The UWB sensor node on the in-memory bus: K x L ranges of a known geometry (noise off) with the
// key and row-major layout of UwbRanges, an empty sample for a pair beyond max_range_m and for a
// lost frame (lockstep: every pair at every due step), links shared by both directions, seeding,
// and a bad array named at configure.
#include "components/uwb_sensor/node/uwb_sensor_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/angle.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(uwb_sensor);

namespace robodds::uwb_sensor {
namespace {

using robodds::testing::NodeHarness;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_uwb_sensor>;

constexpr const char* kNoiseOff = "white_sigma_m: 0, link_bias_sigma_m: 0, common_sigma_m: 0, max_range_m: 20";

// Steps 0..10 at 10 Hz; the sensor runs at 5 Hz (every 2 steps) for robots 1 and 2; robot 3 is
// only a peer.
ScenarioText scenario(const std::string& params) {
  return ScenarioText("uwb_sensor_node", 0.1, 1.0)
      .robots({1, 2, 3})
      .component("{name: uwb, type: uwb_sensor, robots: [1, 2], params: {rate_hz: 5, " + params + "}}");
}

// Robot 1 at the origin facing +x, robot 2 at (3, 4) facing +y, robot 3 far away (100, 0).
idl::RobotState truth(std::uint32_t robot) {
  idl::RobotState s;
  s.robot_id(robot);
  if (robot == 2) {
    s.x(3.0);
    s.y(4.0);
    s.theta(kPi / 2.0);
  } else if (robot == 3) {
    s.x(100.0);
  }
  return s;
}

void feed_static(NodeHarness& h) {
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u, 3u}) {
      h.publish("plant/state", truth(robot), step, step + 1);
    }
  });
}

std::uint64_t key(std::uint32_t robot, std::uint32_t peer) { return (std::uint64_t{robot} << 32) | peer; }

std::vector<idl::UwbRanges> run(NodeHarness& h) {
  feed_static(h);
  const auto& out = h.record<idl::UwbRanges>("sensor/uwb");
  h.run({"uwb"});
  return out;
}

TEST(UwbSensorNode, RangesOfAKnownGeometryInTheKeyLayoutEveryPairEveryDueStep) {
  Harness h(scenario(kNoiseOff));
  const std::vector<idl::UwbRanges> out = run(h);
  std::map<std::uint64_t, std::vector<idl::UwbRanges>> by_pair;
  for (const idl::UwbRanges& m : out) {
    by_pair[idl::instance_key(m)].push_back(m);
  }
  const std::set<std::uint64_t> expected = {key(1, 2), key(1, 3), key(2, 1), key(2, 3)};
  std::set<std::uint64_t> seen;
  for (const auto& [k, samples] : by_pair) {
    seen.insert(k);
    ASSERT_EQ(samples.size(), 6u) << "steps 0, 2, ..., 10, pair " << (k >> 32) << "-" << (k & 0xffffffffu);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      EXPECT_EQ(samples[i].header().step(), 2 * i);
      EXPECT_EQ(samples[i].header().next_step(), 2 * i + 2);
    }
  }
  EXPECT_EQ(seen, expected) << "served robots 1 and 2 to every other scenario robot; robot 3 itself is not served";

  const idl::UwbRanges& r12 = by_pair[key(1, 2)][0];
  ASSERT_EQ(r12.rows(), 4u);
  ASSERT_EQ(r12.cols(), 4u);
  ASSERT_EQ(r12.ranges().size(), 16u);
  // Node 0 of robot 1 (0.25, 0.25); node 1 of robot 2 (-0.25, 0.25) turned by 90 deg: (2.75, 3.75).
  EXPECT_NEAR(r12.ranges()[0 * 4 + 1], std::hypot(2.5, 3.5), 1e-12) << "ranges[k * L + l]: node k of robot_id, l of peer_id";
  // Node 2 of robot 1 (-0.25, -0.25); node 0 of robot 2 (0.25, 0.25) turned: (2.75, 4.25).
  EXPECT_NEAR(r12.ranges()[2 * 4 + 0], std::hypot(3.0, 4.5), 1e-12);
  const idl::UwbRanges& r21 = by_pair[key(2, 1)][0];
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t l = 0; l < 4; ++l) {
      EXPECT_DOUBLE_EQ(r21.ranges()[l * 4 + k], r12.ranges()[k * 4 + l]) << "the other direction is the transpose";
    }
  }
}

TEST(UwbSensorNode, APairBeyondMaxRangeGetsEmptySamplesInLockstep) {
  Harness h(scenario(kNoiseOff));
  const std::vector<idl::UwbRanges> out = run(h);
  std::size_t far = 0;
  for (const idl::UwbRanges& m : out) {
    if (m.peer_id() == 3) {
      ++far;
      EXPECT_EQ(m.rows(), 0u);
      EXPECT_EQ(m.cols(), 0u);
      EXPECT_TRUE(m.ranges().empty());
      EXPECT_EQ(m.header().next_step(), m.header().step() + 2) << "announces the next due step: consumers never wait";
    } else {
      EXPECT_EQ(m.ranges().size(), 16u);
    }
  }
  EXPECT_EQ(far, 12u) << "robots 1 and 2 to robot 3 at 6 steps";
}

TEST(UwbSensorNode, LostFramesAreEmptySamplesInLockstep) {
  Harness h(scenario(std::string(kNoiseOff) + ", frame_loss_probability: 0.5"));
  const std::vector<idl::UwbRanges> out = run(h);
  std::size_t near = 0;
  std::size_t empty = 0;
  for (const idl::UwbRanges& m : out) {
    if (m.peer_id() != 3) {
      ++near;
      empty += m.ranges().empty() ? 1 : 0;
    }
  }
  EXPECT_EQ(near, 12u) << "every pair at every due step, lost or not";
  EXPECT_GT(empty, 0u) << "p = 0.5 over 12 frames (seeded)";
  EXPECT_LT(empty, 12u);
}

// Noise on: the link bias and the common mode belong to the pair, so with white noise off both
// directions are still each other's transpose; the same seed gives the same ranges, another not.
TEST(UwbSensorNode, BothDirectionsShareTheLinkErrorsAndTheSeedDecides) {
  const std::string params = "white_sigma_m: 0";
  Harness a(scenario(params));
  const std::vector<idl::UwbRanges> first = run(a);
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::vector<double>> ranges;  // (key, step)
  for (const idl::UwbRanges& m : first) {
    ranges[{idl::instance_key(m), m.header().step()}] = m.ranges();
  }
  bool noisy = false;
  for (std::uint64_t step = 0; step <= 10; step += 2) {
    const std::vector<double>& r12 = ranges.at({key(1, 2), step});
    const std::vector<double>& r21 = ranges.at({key(2, 1), step});
    ASSERT_EQ(r12.size(), 16u);
    for (std::size_t k = 0; k < 4; ++k) {
      for (std::size_t l = 0; l < 4; ++l) {
        EXPECT_DOUBLE_EQ(r21[l * 4 + k], r12[k * 4 + l]) << "step " << step;
      }
    }
    noisy |= std::abs(r12[1] - std::hypot(2.5, 3.5)) > 1e-6;
  }
  EXPECT_TRUE(noisy) << "the errors are on";

  Harness b(scenario(params));
  const std::vector<idl::UwbRanges> again = run(b);
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(again[i].ranges(), first[i].ranges()) << "same seed, same ranges";
  }
  Harness c(scenario(params));
  c.scenario().seed = 2;
  const std::vector<idl::UwbRanges> other = run(c);
  ASSERT_EQ(other.size(), first.size());
  EXPECT_NE(other[0].ranges(), first[0].ranges()) << "another seed, other ranges";
}

// Two instances, one per robot: the link errors are seeded by the pair, not by the instance name,
// so the two directions still measure one link.
TEST(UwbSensorNode, TwoInstancesServingTheTwoRobotsAgreeOnTheirLink) {
  Harness h(ScenarioText("uwb_sensor_two_instances", 0.1, 1.0)
                .robots({1, 2, 3})
                .component("{name: uwb_one, type: uwb_sensor, robots: [1], params: {rate_hz: 5, white_sigma_m: 0}}")
                .component("{name: uwb_two, type: uwb_sensor, robots: [2], params: {rate_hz: 5, white_sigma_m: 0}}"));
  feed_static(h);
  const auto& out = h.record<idl::UwbRanges>("sensor/uwb");
  h.run({"uwb_one", "uwb_two"});
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::vector<double>> ranges;  // (key, step)
  for (const idl::UwbRanges& m : out) {
    ranges[{idl::instance_key(m), m.header().step()}] = m.ranges();
  }
  for (std::uint64_t step = 0; step <= 10; step += 2) {
    const std::vector<double>& r12 = ranges.at({key(1, 2), step});
    const std::vector<double>& r21 = ranges.at({key(2, 1), step});
    ASSERT_EQ(r12.size(), 16u);
    ASSERT_EQ(r21.size(), 16u);
    for (std::size_t k = 0; k < 4; ++k) {
      for (std::size_t l = 0; l < 4; ++l) {
        EXPECT_DOUBLE_EQ(r21[l * 4 + k], r12[k * 4 + l]) << "step " << step;
      }
    }
  }
}

// Real time: nobody waits on next_step, so an out-of-range pair or a lost frame is simply not sent.
TEST(UwbSensorNode, RealTimeSendsNothingForFarPairsAndLostFrames) {
  Harness h(scenario(std::string(kNoiseOff) + ", frame_loss_probability: 0.5"));
  h.set_mode(TimeMode::kRealtime);
  const std::vector<idl::UwbRanges> out = run(h);
  ASSERT_FALSE(out.empty());
  for (const idl::UwbRanges& m : out) {
    EXPECT_NE(m.peer_id(), 3u) << "robot 3 is beyond max_range_m";
    EXPECT_EQ(m.ranges().size(), 16u) << "no empty samples in real time (p = 0.5: lockstep has some, seeded)";
  }
}

// The array is the scenario's fact (facts: uwb_array:), read and checked by the sensor at configure.
TEST(UwbSensorNode, TooFewNodesIsAConfigErrorNamingTheKey) {
  Harness h(scenario(kNoiseOff).fact("uwb_array: {nodes_m: [[0.3, 0], [-0.3, 0]]}"));
  const std::string error = h.run_error<ConfigError>({"uwb"});
  EXPECT_NE(error.find("facts.uwb_array: nodes_m: needs at least 3 nodes"), std::string::npos)
      << "expected a ConfigError, got: " << error;
}

// Every robot carries the scenario's array: a 0.8 m square moves every node to (+-0.4, +-0.4).
TEST(UwbSensorNode, MeasuresWithTheScenariosArray) {
  Harness h(scenario(kNoiseOff).fact("uwb_array: {array_side_m: 0.8}"));
  const std::vector<idl::UwbRanges> out = run(h);
  std::size_t checked = 0;
  for (const idl::UwbRanges& m : out) {
    if (idl::instance_key(m) != key(1, 2)) {
      continue;
    }
    ASSERT_EQ(m.ranges().size(), 16u);
    // Node 0 of robot 1 at (0.4, 0.4) (front-left, facing +x); node 0 of robot 2 (facing +y) at
    // (3, 4) + R(90 deg) (0.4, 0.4) = (2.6, 4.4).
    EXPECT_NEAR(m.ranges()[0], std::hypot(2.2, 4.0), 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 6u);
}

}  // namespace
}  // namespace robodds::uwb_sensor
