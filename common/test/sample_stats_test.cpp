#include "common/sample_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace robodds::stats {
namespace {

TEST(StudentT975, TableAndExpansion) {
  EXPECT_DOUBLE_EQ(student_t_975(1), 12.7062);
  EXPECT_DOUBLE_EQ(student_t_975(9), 2.2622);
  EXPECT_NEAR(student_t_975(31), 2.0395, 1e-4);
  EXPECT_NEAR(student_t_975(99), 1.9842, 1e-4);
  EXPECT_THROW(student_t_975(0), std::invalid_argument);
}

TEST(Summarize, FiveValues) {
  const SampleSummary s = summarize({1.0, 2.0, 3.0, 4.0, 10.0});
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.mean, 4.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_NEAR(s.stddev, 3.5355339, 1e-7);  // sqrt(50 / 4)
  EXPECT_NEAR(s.ci95, 2.7764 * 3.5355339 / std::sqrt(5.0), 1e-6);
}

TEST(Summarize, OneValueHasNoSpread) {
  const SampleSummary s = summarize({2.5});
  EXPECT_EQ(s.count, 1u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.min, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 2.5);
  EXPECT_DOUBLE_EQ(s.stddev, 0.0);
  EXPECT_DOUBLE_EQ(s.ci95, 0.0);
}

TEST(Summarize, EmptyIsAnError) { EXPECT_THROW(summarize({}), std::invalid_argument); }

}  // namespace
}  // namespace robodds::stats
