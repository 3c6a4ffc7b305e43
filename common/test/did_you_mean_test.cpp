#include "common/did_you_mean.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("stat", "state"), 1u);      // insertion
  EXPECT_EQ(edit_distance("plant_state", "plant/state"), 1u);  // substitution
  EXPECT_EQ(edit_distance("recrod", "record"), 1u);   // adjacent swap is one edit
  EXPECT_EQ(edit_distance("Record", "record"), 0u);   // case does not count
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(ClosestNames, FindsTheParameterBehindItsComponentPrefix) {
  const std::vector<std::string> keys{"controller.k_v", "controller.epsilon_m", "plant.wheel_base_m", "estimator.particles"};
  EXPECT_EQ(closest_names("epsilon", keys), std::vector<std::string>{"controller.epsilon_m"});
  EXPECT_EQ(closest_names("controller.epsilon", keys), std::vector<std::string>{"controller.epsilon_m"});
  EXPECT_EQ(closest_names("epsilon_n", keys), std::vector<std::string>{"controller.epsilon_m"});
  EXPECT_EQ(closest_names("particle", keys), std::vector<std::string>{"estimator.particles"});
}

TEST(ClosestNames, TyposNotOtherWords) {
  const std::vector<std::string> topics{"plant/state", "plant/cmd", "estimate/pose", "sensor/position"};
  EXPECT_EQ(closest_names("plant/stat", topics), std::vector<std::string>{"plant/state"});
  EXPECT_EQ(closest_names("state", topics), std::vector<std::string>{"plant/state"});
  EXPECT_TRUE(closest_names("weather", topics).empty());
  EXPECT_TRUE(closest_names("xy", topics).empty());
  EXPECT_TRUE(closest_names("c", {"a", "b"}).empty());
  EXPECT_TRUE(closest_names("plant/state", topics).empty());  // known: nothing to suggest
  EXPECT_TRUE(closest_names("", topics).empty());
}

TEST(ClosestNames, BestFirstAtMostMax) {
  const std::vector<std::string> names{"abcd", "abce", "abcf", "abcg", "abc"};
  EXPECT_EQ(closest_names("abcx", names, 2), (std::vector<std::string>{"abcd", "abce"}));
  EXPECT_EQ(closest_names("abcx", names).front(), "abcd");
  EXPECT_EQ(closest_names("ab", {"abc", "ab_long_name"}), std::vector<std::string>{"abc"});
}

TEST(ListedNames, SplitsACommaSeparatedList) {
  EXPECT_EQ(listed_names("id, x,y ,  theta"), (std::vector<std::string>{"id", "x", "y", "theta"}));
  EXPECT_TRUE(listed_names("").empty());
}

TEST(DidYouMean, OneFormForOneTwoAndThreeNames) {
  EXPECT_EQ(did_you_mean("recrod", {"run", "record", "replay"}), "; did you mean 'record'?");
  EXPECT_EQ(did_you_mean("ab", {"abc", "abd"}), "; did you mean 'abc' or 'abd'?");
  EXPECT_EQ(did_you_mean("abcx", {"abcd", "abce", "abcf"}), "; did you mean 'abcd', 'abce' or 'abcf'?");
  EXPECT_EQ(did_you_mean("zzz", {"abc"}), "");
}

}  // namespace
}  // namespace robodds
