// CSV text of samples: exact round trip of doubles and exact times.
#include "runtime/sample_format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
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
