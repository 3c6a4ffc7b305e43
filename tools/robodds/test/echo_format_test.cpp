#include "tools/robodds/echo_format.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace robodds {
namespace {

EchoValue number(const std::string& text, bool finite = true) { return EchoValue{EchoValue::Kind::number, text, finite, {}, {}}; }
EchoValue text(const std::string& t) { return EchoValue{EchoValue::Kind::text, t, true, {}, {}}; }
EchoValue boolean(bool b) { return EchoValue{EchoValue::Kind::boolean, b ? "true" : "false", true, {}, {}}; }
EchoValue list(std::vector<EchoValue> items) { return EchoValue{EchoValue::Kind::list, "", true, std::move(items), {}}; }
EchoValue record(EchoFields fields) { return EchoValue{EchoValue::Kind::record, "", true, {}, std::move(fields)}; }

/// A controller status and a mission in one: a key, a nested header, an enum, a boolean, a NaN,
/// a fixed array, a string with a comma and a sequence of structs.
EchoFields sample() {
  return {{"robot_id", number("1")},
          {"header.step", number("42")},
          {"header.stamp_ns", number("420000000")},
          {"state", text("ESTIMATE_STALE")},
          {"done", boolean(false)},
          {"alpha", number("nan", false)},
          {"p[0]", number("0.5")},
          {"p[1]", number("-2")},
          {"note", text("a, \"b\"")},
          {"waypoints", list({record({{"x", number("60")}, {"y", number("20")}}), record({{"x", number("75")}, {"y", number("15")}})})}};
}

TEST(EchoText, EnumsByNameBooleansAsWordsSequencesAsLists) {
  EXPECT_EQ(echo_text("controller/status (robot_id=1)", sample()),
            "--- controller/status (robot_id=1)\n"
            "  robot_id: 1\n"
            "  header.step: 42\n"
            "  header.stamp_ns: 420000000\n"
            "  state: ESTIMATE_STALE\n"
            "  done: false\n"
            "  alpha: nan\n"
            "  p[0]: 0.5\n"
            "  p[1]: -2\n"
            "  note: a, \"b\"\n"
            "  waypoints: [{x: 60, y: 20}, {x: 75, y: 15}]\n");
  EXPECT_EQ(echo_inline(list({number("1"), number("2")})), "[1, 2]");
  EXPECT_EQ(echo_inline(list({})), "[]");
}

TEST(EchoJson, OneNestedObjectPerSample) {
  EXPECT_EQ(echo_json(sample()),
            R"({"robot_id":1,"header":{"step":42,"stamp_ns":420000000},"state":"ESTIMATE_STALE","done":false,)"
            R"("alpha":null,"p":[0.5,-2],"note":"a, \"b\"","waypoints":[{"x":60,"y":20},{"x":75,"y":15}]})");
  EXPECT_EQ(echo_json({}), "{}");
}

TEST(EchoCsv, HeaderAndRowsQuotedWhereTheyHoldCommas) {
  EXPECT_EQ(echo_csv_header(sample()), "robot_id,header.step,header.stamp_ns,state,done,alpha,p[0],p[1],note,waypoints");
  EXPECT_EQ(echo_csv_row(sample()), "1,42,420000000,ESTIMATE_STALE,false,nan,0.5,-2,\"a, \"\"b\"\"\",\"[{x: 60, y: 20}, {x: 75, y: 15}]\"");
}

TEST(EchoSelect, AFieldOrEverythingUnderIt) {
  const EchoFields header = select_fields(sample(), {"header"});
  ASSERT_EQ(header.size(), 2u);
  EXPECT_EQ(header[0].first, "header.step");
  EXPECT_EQ(header[1].first, "header.stamp_ns");
  EXPECT_EQ(select_fields(sample(), {"header.step"}).size(), 1u);
  EXPECT_EQ(select_fields(sample(), {"p"}).size(), 2u);
  const EchoFields two = select_fields(sample(), {"state", "robot_id"});  // in the sample's order
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].first, "robot_id");
}

TEST(EchoSelect, AnUnknownFieldNamesTheClosest) {
  try {
    select_fields(sample(), {"stat"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--field 'stat': no such field; did you mean 'state'? (fields: robot_id, ", 0), 0u) << e.what();
  }
  EXPECT_THROW(select_fields(sample(), {"heade.step"}), std::invalid_argument);
  EXPECT_THROW(select_fields(sample(), {"header.ste"}), std::invalid_argument);  // not a prefix at a '.'
}

TEST(EchoKeyFilter, KeepsTheSamplesOfTheNamedInstance) {
  const std::vector<std::string> keys{"robot_id", "peer_id"};
  EXPECT_TRUE(matches(sample(), {parse_key_filter("robot_id=1", keys)}));
  EXPECT_FALSE(matches(sample(), {parse_key_filter("robot_id=2", keys)}));
  EXPECT_FALSE(matches(sample(), {parse_key_filter("peer_id=1", keys)}));  // no such field in the sample
  EXPECT_TRUE(matches(sample(), {}));
  try {
    parse_key_filter("robotid=1", keys);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--key 'robotid=1': 'robotid' is no key of the topic; did you mean 'robot_id'? (keys: robot_id, peer_id)");
  }
  EXPECT_THROW(parse_key_filter("robot_id", keys), std::invalid_argument);
  EXPECT_THROW(parse_key_filter("robot_id=", keys), std::invalid_argument);
}

}  // namespace
}  // namespace robodds
