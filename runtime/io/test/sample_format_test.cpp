// CSV text of samples: exact round trip of doubles and exact times.
#include "runtime/io/sample_format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds.h"

namespace robodds {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream stream(line);
  for (std::string cell; std::getline(stream, cell, ',');) {
    cells.push_back(cell);
  }
  return cells;
}

TEST(AppendSeconds, FormatsNanosecondsExactly) {
  std::string out;
  append_seconds(out, 0);
  EXPECT_EQ(out, "0.000000000");
  out.clear();
  append_seconds(out, 12340000000LL);
  EXPECT_EQ(out, "12.340000000");
  out.clear();
  append_seconds(out, 1);
  EXPECT_EQ(out, "0.000000001");
  out.clear();
  append_seconds(out, -1500000000LL);
  EXPECT_EQ(out, "-1.500000000");
}

TEST(AppendSeconds, EveryDigitOfTheFractionAndTheExtremes) {
  const std::pair<std::int64_t, const char*> cases[] = {
      {999999999LL, "0.999999999"},
      {1000000001LL, "1.000000001"},
      {123456789012LL, "123.456789012"},
      {-20000000LL, "-0.020000000"},
      {std::numeric_limits<std::int64_t>::max(), "9223372036.854775807"},
      {std::numeric_limits<std::int64_t>::min(), "-9223372036.854775808"},
  };
  for (const auto& [ns, text] : cases) {
    std::string out = "x";
    append_seconds(out, ns);
    EXPECT_EQ(out, std::string("x") + text) << ns;
  }
}

// Integers are spelled as std::to_string spells them (the CSVs stay byte-identical).
TEST(AppendValue, IntegersAsToString) {
  for (const std::int64_t value : {std::int64_t{0}, std::int64_t{-1}, std::int64_t{42}, std::int64_t{-1234567890123},
                                   std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()}) {
    std::string out;
    detail::append_value(out, value);
    EXPECT_EQ(out, std::to_string(value));
  }
  for (const std::uint64_t value : {std::uint64_t{0}, std::uint64_t{7}, std::numeric_limits<std::uint64_t>::max()}) {
    std::string out;
    detail::append_value(out, value);
    EXPECT_EQ(out, std::to_string(value));
  }
  for (const std::uint32_t value : {std::uint32_t{0}, std::uint32_t{4}, std::numeric_limits<std::uint32_t>::max()}) {
    std::string out;
    detail::append_value(out, value);
    EXPECT_EQ(out, std::to_string(value));
  }
  std::string out;
  detail::append_value(out, std::int32_t{-17});
  EXPECT_EQ(out, "-17");
}

TEST(AppendCsvRow, DoublesRoundTripExactly) {
  const std::vector<std::string> header = split(csv_header<idl::VelocityCommand>());
  const auto v_column = static_cast<std::size_t>(std::find(header.begin(), header.end(), "v") - header.begin());
  ASSERT_LT(v_column, header.size());
  for (double value : {0.1, 1.0 / 3.0, -2.5e-300, 123456789.123456789, std::nextafter(1.0, 2.0),
                       std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min()}) {
    idl::VelocityCommand cmd;
    cmd.v(value);
    std::string row;
    append_csv_row(row, cmd);
    const std::vector<std::string> cells = split(row);
    ASSERT_EQ(cells.size(), header.size()) << row;
    EXPECT_EQ(std::strtod(cells[v_column].c_str(), nullptr), value) << cells[v_column];
  }
}

TEST(AppendCsvRow, ShortestTextForSimpleValues) {
  std::string out;
  detail::append_value(out, 0.1);
  EXPECT_EQ(out, "0.1");
}

}  // namespace
}  // namespace robodds
