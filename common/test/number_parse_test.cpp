#include "common/number_parse.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace robodds {
namespace {

TEST(ParseWholeNumber, DigitsOnlyUpToTheLimit) {
  EXPECT_EQ(parse_whole_number("0", 10), 0u);
  EXPECT_EQ(parse_whole_number("10", 10), 10u);
  EXPECT_EQ(parse_whole_number("11", 10), std::nullopt);
  const std::uint64_t max = std::numeric_limits<std::uint64_t>::max();
  EXPECT_EQ(parse_whole_number("18446744073709551615", max), max);
  EXPECT_EQ(parse_whole_number("18446744073709551616", max), std::nullopt);  // overflows
  for (const char* bad : {"", "-1", "+1", " 1", "1 ", "1.0", "7abc", "0x10"}) {
    EXPECT_EQ(parse_whole_number(bad, max), std::nullopt) << bad;
  }
}

TEST(ParseFiniteNumber, TheWholeTextAFiniteNumber) {
  EXPECT_EQ(parse_finite_number("1.5"), 1.5);
  EXPECT_EQ(parse_finite_number("-2e-3"), -2e-3);
  for (const char* bad : {"", "nan", "inf", "-inf", "1e999", "1.5x", "x", "1,5"}) {
    EXPECT_EQ(parse_finite_number(bad), std::nullopt) << bad;
  }
}

}  // namespace
}  // namespace robodds
