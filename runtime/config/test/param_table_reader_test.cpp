#include "runtime/config/param_table_reader.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/error_of.hpp"

namespace robodds {
namespace {

using test_support::write_test_file;

struct Example {
  double rate_hz = 100.0;
  int count = 3;
  bool flag = true;
  std::vector<std::string> topics{"plant/state", "plant/cmd"};
  std::vector<params::Point2> points{{60.0, 20.0}, {75.5, -15.0}};
};

const params::ParamTable<Example>& example_table() {
  static const params::ParamTable<Example> table =
      params::ParamTable<Example>("Example.")
          .add("rate_hz", &Example::rate_hz, "Hz", params::positive(), "rate")
          .add("count", &Example::count, "", params::at_least(1), "count")
          .add("flag", &Example::flag, "", params::any<bool>(), "flag")
          .add("topics", &Example::topics, "", params::any<std::vector<std::string>>(), "topics")
          .add("points", &Example::points, "m", params::any<std::vector<params::Point2>>(), "points");
  return table;
}

std::string error_of(const std::function<void()>& f) { return test_support::error_of<ConfigError>(f); }

FlatParams defaults() { return default_params(example_table().doc(), "defaults of example"); }

TEST(ParamTableReader, DefaultsAloneGiveTheStructsDefaults) {
  ParamReader reader("example", defaults());
  const Example read = read_params(reader, example_table());
  EXPECT_EQ(read.rate_hz, 100.0);
  EXPECT_EQ(read.count, 3);
  EXPECT_TRUE(read.flag);
  EXPECT_EQ(read.topics, Example{}.topics);
  EXPECT_EQ(read.points, Example{}.points);
  EXPECT_NO_THROW(reader.check_all_read());
}

TEST(ParamTableReader, TheRenderedDefaultsFileReadsBackAsTheDefaults) {
  const std::string file = write_test_file("example.params.yaml", params::render_params_yaml(example_table().doc()));
  ParamReader reader("example", merge_params(defaults(), load_param_file(file)));
  const Example read = read_params(reader, example_table());
  EXPECT_EQ(read.rate_hz, 100.0);
  EXPECT_EQ(read.topics, Example{}.topics);
  EXPECT_EQ(read.points, Example{}.points);
}

TEST(ParamTableReader, OverridesWinAndErrorsNameTheirFile) {
  const std::string file = write_test_file("s.yaml", "count: 7\nflag: false\n");
  ParamReader reader("example", merge_params(defaults(), load_param_file(file)));
  const Example read = read_params(reader, example_table());
  EXPECT_EQ(read.count, 7);
  EXPECT_FALSE(read.flag);

  const std::string bad = write_test_file("s.yaml", "count: 0\n");
  ParamReader bad_reader("example", merge_params(defaults(), load_param_file(bad)));
  EXPECT_EQ(error_of([&] { read_params(bad_reader, example_table()); }), bad + ": count: must be >= 1 (got 0)");

  const std::string wrong_type = write_test_file("s.yaml", "rate_hz: fast\n");
  ParamReader type_reader("example", merge_params(defaults(), load_param_file(wrong_type)));
  EXPECT_EQ(error_of([&] { read_params(type_reader, example_table()); }),
            wrong_type + ": rate_hz: expected a number, got 'fast'");
}

TEST(ParamTableReader, UnknownOverrideNamesTheKnownKeys) {
  const std::string file = write_test_file("s.yaml", "rate: 7\n");
  EXPECT_EQ(error_of([&] { merge_params(defaults(), load_param_file(file)); }),
            file + ": rate: unknown parameter; did you mean 'rate_hz'? (known: count, flag, points, rate_hz, topics)");
}

}  // namespace
}  // namespace robodds
