#include "common/json_writer.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace robodds {
namespace {

TEST(JsonWriter, WritesNestedObjectsDeterministically) {
  JsonWriter w;
  w.begin_object().value("a", 1.5).value("n", std::int64_t{3}).begin_object("o").value("s", "x\"y").end_object()
      .value("v", std::vector<double>{1, 2}).value("b", true).end_object();
  EXPECT_EQ(w.str(), "{\n  \"a\": 1.5,\n  \"n\": 3,\n  \"o\": {\n    \"s\": \"x\\\"y\"\n  },\n  \"v\": [1, 2],\n  \"b\": true\n}\n");
}

TEST(JsonWriter, NonFiniteBecomesNull) {
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
}

}  // namespace
}  // namespace robodds
