#include "runtime/bus/key_index.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace robodds {
namespace {

/// Keys of the shapes inputs see: robot ids, (robot_id, target_id) pairs, hashes, and 0.
std::vector<std::uint64_t> sample_keys() {
  std::vector<std::uint64_t> keys{0};
  for (std::uint64_t r = 1; r <= 1000; ++r) {
    keys.push_back(r);
    keys.push_back(r << 32 | 2);
  }
  for (std::uint64_t k = 1; k <= 300; ++k) {
    keys.push_back(k * 0x9E3779B97F4A7C15ULL);  // all hash to one home slot's neighbourhood
    keys.push_back(~k);
  }
  return keys;
}

TEST(KeyIndex, NumbersKeysInInsertionOrderAndFindsEach) {
  KeyIndex index;
  const std::vector<std::uint64_t> keys = sample_keys();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto [number, added] = index.insert(keys[i]);
    EXPECT_TRUE(added) << keys[i];
    EXPECT_EQ(number, i);
  }
  EXPECT_EQ(index.size(), keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    EXPECT_EQ(index.find(keys[i]), i) << keys[i];
  }
}

TEST(KeyIndex, InsertingAKeyAgainKeepsItsNumber) {
  KeyIndex index;
  index.insert(7);
  index.insert(3);
  const auto [number, added] = index.insert(7);
  EXPECT_FALSE(added);
  EXPECT_EQ(number, 0u);
  EXPECT_EQ(index.size(), 2u);
}

TEST(KeyIndex, UnknownKeysAreNotFound) {
  KeyIndex index;
  EXPECT_EQ(index.find(0), KeyIndex::kNone);
  for (std::uint64_t r = 1; r <= 1000; ++r) {
    index.insert(r);
  }
  EXPECT_EQ(index.find(0), KeyIndex::kNone);
  EXPECT_EQ(index.find(1001), KeyIndex::kNone);
  EXPECT_EQ(index.find(1ULL << 32 | 1), KeyIndex::kNone);
}

}  // namespace
}  // namespace robodds
