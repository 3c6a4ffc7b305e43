#include "runtime/bus/instance_spread.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace robodds {
namespace {

TEST(WritersForRobots, OneWriterPerStartedGroupOf32) {
  EXPECT_EQ(writers_for_robots(0), 1u);
  EXPECT_EQ(writers_for_robots(1), 1u);
  EXPECT_EQ(writers_for_robots(kRobotsPerLockstepWriter), 1u);
  EXPECT_EQ(writers_for_robots(kRobotsPerLockstepWriter + 1), 2u);
  EXPECT_EQ(writers_for_robots(200), 7u);
  EXPECT_EQ(writers_for_robots(1000), 32u);
  EXPECT_EQ(writers_for_robots(10, 4), 3u);
}

TEST(InstanceSpread, DealsNewInstancesInTurnAndKeepsEachOnItsWriter) {
  InstanceSpread spread(3);
  // Keys in a scrambled first-write order: the n-th NEW key goes to writer n mod 3.
  const std::vector<std::uint64_t> keys{907, 11, 5, 5000000000ULL, 42, 7};
  std::vector<std::size_t> first;
  for (std::uint64_t key : keys) {
    first.push_back(spread.writer_of(key));
  }
  EXPECT_EQ(first, (std::vector<std::size_t>{0, 1, 2, 0, 1, 2}));
  // Later writes of the same instances, in another order, keep their writer.
  for (std::size_t i = keys.size(); i-- > 0;) {
    EXPECT_EQ(spread.writer_of(keys[i]), first[i]) << keys[i];
  }
  EXPECT_EQ(spread.writer_of(99), 0u) << "the 7th new instance";
}

TEST(InstanceSpread, SharesAreEqualWithin1) {
  InstanceSpread spread(writers_for_robots(200));
  std::vector<std::size_t> load(spread.writers(), 0);
  for (std::uint64_t robot = 1; robot <= 200; ++robot) {
    ++load[spread.writer_of(robot * 0x9E3779B97F4A7C15ULL)];
  }
  EXPECT_LE(*std::max_element(load.begin(), load.end()) - *std::min_element(load.begin(), load.end()), 1u);
  EXPECT_LE(*std::max_element(load.begin(), load.end()), kRobotsPerLockstepWriter);
}

TEST(InstanceSpread, OneWriterTakesEverything) {
  InstanceSpread spread(1);
  EXPECT_EQ(spread.writer_of(1), 0u);
  EXPECT_EQ(spread.writer_of(2), 0u);
  EXPECT_EQ(InstanceSpread(0).writers(), 1u) << "0 writers is read as 1";
}

}  // namespace
}  // namespace robodds
