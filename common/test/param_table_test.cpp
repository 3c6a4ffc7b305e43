#include "common/param_table.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace robodds::params {
namespace {

enum class Mode { kFast, kSlow };

Mode mode_from_string(std::string_view text) {
  if (text == "fast") {
    return Mode::kFast;
  }
  if (text == "slow") {
    return Mode::kSlow;
  }
  throw std::invalid_argument("mode: must be fast or slow (got " + std::string(text) + ")");
}

std::string to_string(Mode mode) { return mode == Mode::kFast ? "fast" : "slow"; }

struct Gains {
  double kd = 1.0;
  double ka = 20.0;
};

struct Inner {
  double rate_hz = 100.0;
  int count = 3;
  Gains gains;
  Mode mode = Mode::kSlow;
  void validate() const;
};

const ParamTable<Inner>& inner_table() {
  static const ParamTable<Inner> table = ParamTable<Inner>("A test component.\nSecond line.")
                                             .add("rate_hz", &Inner::rate_hz, "Hz", positive(), "how often")
                                             .add("count", &Inner::count, "", at_least(1), "how many")
                                             .group("gains", "the gains")
                                             .add("gains.kd", &Inner::gains, &Gains::kd, "1/s", finite(), "distance gain")
                                             .add("gains.ka", &Inner::gains, &Gains::ka, "1/s", finite(), "angle gain")
                                             .add_enum("mode", &Inner::mode, mode_from_string, to_string,
                                                       {"fast", "slow"}, "speed");
  return table;
}

struct Outer {
  Inner inner;
  bool flag = true;
  std::vector<std::string> topics{"plant/state", "true"};
  std::vector<Point2> points{{1.5, -2.0}, {3.0, 4.0}};
};

const ParamTable<Outer>& outer_table() {
  static const ParamTable<Outer> table = ParamTable<Outer>("Outer.")
                                             .include(&Outer::inner, inner_table())
                                             .add("flag", &Outer::flag, "", any<bool>(), "a flag")
                                             .add("topics", &Outer::topics, "", any<std::vector<std::string>>(), "names")
                                             .add("points", &Outer::points, "m", any<std::vector<Point2>>(), "[x, y]");
  return table;
}

std::string range_error(const Inner& inner) {
  try {
    inner_table().check_ranges(inner);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ParamTable, RendersTheDefaultsFileWithAlignedComments) {
  EXPECT_EQ(render_params_yaml(inner_table().doc()),
            "# A test component.\n"
            "# Second line.\n"
            "# Generated from the component's parameter table by scripts/regenerate_params.sh; edit the table.\n"
            "rate_hz: 100  # Hz, > 0: how often\n"
            "count: 3      # >= 1: how many\n"
            "gains:        # the gains\n"
            "  kd: 1       # 1/s, finite: distance gain\n"
            "  ka: 20      # 1/s, finite: angle gain\n"
            "mode: slow    # fast | slow: speed\n");
}

TEST(ParamTable, IncludedEntriesKeepTheirKeysAndReadTheOuterDefaults) {
  Outer defaults;
  defaults.inner.rate_hz = 50.0;
  const ParamDoc doc = outer_table().doc(defaults);
  ASSERT_EQ(doc.params.size(), 8u);
  EXPECT_EQ(doc.params[0].key, "rate_hz");
  EXPECT_EQ(doc.params[0].default_yaml, "50");
  EXPECT_EQ(doc.params[6].default_yaml, "[plant/state, \"true\"]");  // "true" would read as a bool
  EXPECT_EQ(doc.params[7].default_yaml, "[[1.5, -2], [3, 4]]");
  EXPECT_EQ(doc.params[7].type, "list of [x, y]");
}

TEST(ParamTable, RangeChecksUseTheParamChecksMessages) {
  EXPECT_EQ(range_error(Inner{}), "");
  Inner bad;
  bad.count = 0;
  EXPECT_EQ(range_error(bad), "count: must be >= 1 (got 0)");
  bad = Inner{};
  bad.rate_hz = -1.0;
  EXPECT_EQ(range_error(bad), "rate_hz: must be > 0 and finite (got -1)");
}

TEST(ParamTable, SetConvertsValuesAndRejectsIntegersThatDoNotFit) {
  Outer outer;
  const auto& entries = outer_table().entries();
  entries[1].set(outer, ParamValue{std::int64_t{7}});
  EXPECT_EQ(outer.inner.count, 7);
  entries[4].set(outer, ParamValue{std::string("fast")});
  EXPECT_EQ(outer.inner.mode, Mode::kFast);
  EXPECT_THROW(entries[4].set(outer, ParamValue{std::string("medium")}), std::invalid_argument);
  try {
    entries[1].set(outer, ParamValue{std::int64_t{1} << 40});
    FAIL() << "accepted 2^40 for an int";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "count: out of range for int (got 1099511627776)");
  }
}

TEST(ParamTable, DescribePrintsOneRowPerParameter) {
  const std::string text = describe_params(inner_table().doc());
  EXPECT_EQ(text.substr(0, text.find('\n')), "KEY       TYPE    DEFAULT  UNIT  RANGE        DESCRIPTION");
  EXPECT_NE(text.find("\ngains.kd  double  1        1/s   finite       distance gain\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nmode      enum    slow     -     fast | slow  speed\n"), std::string::npos) << text;
}

TEST(ParamTable, NestedKeysMustBeContiguous) {
  ParamDoc doc;
  doc.params = {{"a.x", "double", "1", "", "", ""}, {"b", "double", "1", "", "", ""}, {"a.y", "double", "1", "", "", ""}};
  EXPECT_THROW(render_params_yaml(doc), std::invalid_argument);
}

TEST(ParamTable, YamlTextOfSpecialValues) {
  EXPECT_EQ(yaml_text(0.1), "0.1");
  EXPECT_EQ(yaml_text(0.0005), "0.0005");
  EXPECT_EQ(yaml_text(-1e-9), "-0.000000001");
  EXPECT_EQ(yaml_text(1e-12), "1e-12");
  EXPECT_EQ(yaml_text(2.5e20), "2.5e+20");
  EXPECT_EQ(yaml_text(std::string("a b")), "\"a b\"");
  EXPECT_EQ(yaml_text(std::string("first_fix")), "first_fix");
}

}  // namespace
}  // namespace robodds::params
