#include "runtime/bus/step_needs.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>

namespace robodds {
namespace {

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

TEST(StepNeeds, ASensorAtATenthOfThePlantRateNeedsOneStateInTen) {
  const StepNeeds needs = StepNeeds::of_component(10, 0, 0);
  ASSERT_FALSE(needs.all());
  for (std::uint64_t step = 0; step < 100; ++step) {
    EXPECT_EQ(needs.needs(step, step + 1), step % 10 == 0) << "step " << step;
  }
}

TEST(StepNeeds, ReadingLateShiftsTheReadSteps) {
  // Due at k = 0, 10, 20, ..., reading 1 step late: the states of steps 9, 19, ...
  const StepNeeds needs = StepNeeds::of_component(10, 0, 1);
  for (std::uint64_t step = 0; step < 100; ++step) {
    EXPECT_EQ(needs.needs(step, step + 1), step % 10 == 9) << "step " << step;
  }
  // Delays of a period or more wrap around.
  EXPECT_EQ(StepNeeds::of_component(10, 0, 23), StepNeeds::of_component(10, 0, 3));
}

TEST(StepNeeds, ASampleIsNeededWhenItIsTheNewestAtAReadStep) {
  const StepNeeds needs = StepNeeds::of_component(10, 0, 0);
  EXPECT_TRUE(needs.needs(0, 5));    // the newest at step 0
  EXPECT_FALSE(needs.needs(5, 10));  // replaced at 10 before anyone reads it
  EXPECT_TRUE(needs.needs(5, 11));   // the newest at step 10
  EXPECT_TRUE(needs.needs(3, 25));   // a slower writer: every sample
  EXPECT_TRUE(needs.needs(11, kNever));  // the last of its instance
  EXPECT_TRUE(needs.needs(7, 7));    // an inconsistent header: the reader's checks count it
  EXPECT_TRUE(needs.needs(8, 3));
}

TEST(StepNeeds, EveryStepOrEveryCheckpointStepNeedsEverySample) {
  EXPECT_TRUE(StepNeeds::of_component(1, 0, 0).all());
  EXPECT_TRUE(StepNeeds::of_component(0, 0, 0).all());
  EXPECT_TRUE(StepNeeds::of_component(10, 1, 0).all());
  EXPECT_TRUE(StepNeeds{}.needs(3, 4));
}

TEST(StepNeeds, CheckpointStepsAreReadStepsToo) {
  const StepNeeds needs = StepNeeds::of_component(100, 30, 0);
  for (std::uint64_t step = 0; step < 300; ++step) {
    EXPECT_EQ(needs.needs(step, step + 1), step % 100 == 0 || step % 30 == 0) << "step " << step;
  }
}

TEST(StepNeeds, TheUnionNeedsWhatAnySubscriberNeeds) {
  StepNeeds both = StepNeeds::of_component(10, 0, 0);
  both.add(StepNeeds::of_component(4, 0, 1));
  for (std::uint64_t step = 0; step < 100; ++step) {
    EXPECT_EQ(both.needs(step, step + 1), step % 10 == 0 || step % 4 == 3) << "step " << step;
  }
  StepNeeds with_all = StepNeeds::of_component(10, 0, 0);
  with_all.add(StepNeeds{});
  EXPECT_TRUE(with_all.all());
  StepNeeds from_all;
  from_all.add(StepNeeds::of_component(10, 0, 0));
  EXPECT_TRUE(from_all.all());
}

TEST(StepNeeds, FirstReadStepFrom) {
  const StepNeeds needs = StepNeeds::of_component(10, 0, 1);  // 9, 19, 29, ...
  EXPECT_EQ(needs.first_read_step_from(0), 9u);
  EXPECT_EQ(needs.first_read_step_from(9), 9u);
  EXPECT_EQ(needs.first_read_step_from(10), 19u);
  EXPECT_EQ(StepNeeds{}.first_read_step_from(12), 12u);
  EXPECT_EQ(needs.first_read_step_from(kNever - 2), kNever);  // no overflow
}

TEST(StepNeeds, AgreesWithAWalkOverTheReadSteps) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    StepNeeds needs = StepNeeds::of_component(2 + rng() % 20, rng() % 3 == 0 ? 2 + rng() % 50 : 0, rng() % 30);
    needs.add(StepNeeds::of_component(2 + rng() % 20, 0, rng() % 5));
    const auto parsed = StepNeeds::parse(needs.text());
    ASSERT_TRUE(parsed) << needs.text();
    ASSERT_EQ(*parsed, needs);
    for (int sample = 0; sample < 50; ++sample) {
      const std::uint64_t step = rng() % 500;
      const std::uint64_t next = step + 1 + rng() % 40;
      bool walked = false;
      for (std::uint64_t m = step; m < next && !walked; ++m) {
        walked = needs.first_read_step_from(m) == m;
      }
      EXPECT_EQ(needs.needs(step, next), walked) << needs.text() << " [" << step << ", " << next << ")";
    }
  }
}

TEST(StepNeeds, TextRoundTripsAndBadTextIsRefused) {
  StepNeeds needs = StepNeeds::of_component(10, 0, 1);
  needs.add(StepNeeds::of_component(25, 0, 0));
  EXPECT_EQ(needs.text(), "steps 10:9 25:0");
  EXPECT_EQ(StepNeeds::parse("steps 10:9 25:0"), needs);
  EXPECT_EQ(StepNeeds::parse("steps"), StepNeeds{});
  for (const char* bad : {"", "step 10:0", "steps 1:0", "steps 0:0", "steps 10:10", "steps 10", "steps :3", "steps 10:",
                          "steps 10:-1", "steps 10:1:2", "steps 99999999999999999999:0", "steps 10:0 x"}) {
    EXPECT_FALSE(StepNeeds::parse(bad)) << bad;
  }
}

}  // namespace
}  // namespace robodds
