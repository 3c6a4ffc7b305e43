#include "runtime/config/params.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/param_checks.hpp"
#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"
#include "tests/support/error_of.hpp"

namespace robodds {
namespace {

using test_support::write_test_file;

std::string error_of(const std::function<void()>& f) { return test_support::error_of<ConfigError>(f); }

TEST(Params, ReadsTypedValuesAndNestedKeys) {
  const std::string file = write_test_file("p1.yaml", "rate_hz: 10\nname: abc\nflag: true\ngains: {kd: 1.5}\nlist: [1, 2]\npts: [[1, 2], [3, 4]]\n");
  ParamReader r("c", load_param_file(file));
  EXPECT_DOUBLE_EQ(r.get_double("rate_hz"), 10.0);
  EXPECT_EQ(r.get_string("name"), "abc");
  EXPECT_TRUE(r.get_bool("flag"));
  EXPECT_DOUBLE_EQ(r.get_double("gains.kd"), 1.5);
  EXPECT_EQ(r.get_double_list("list").size(), 2u);
  EXPECT_DOUBLE_EQ(r.get_point_list("pts")[1][0], 3.0);
  EXPECT_NO_THROW(r.check_all_read());
}

TEST(Params, MissingKeyNamesFileAndKey) {
  const std::string file = write_test_file("p2.yaml", "a: 1\n");
  ParamReader r("c", load_param_file(file));
  const std::string message = error_of([&] { r.get_double("b"); });
  EXPECT_NE(message.find(file), std::string::npos) << message;
  EXPECT_NE(message.find("b: missing"), std::string::npos) << message;
}

TEST(Params, WrongTypeNamesKeyAndValue) {
  const std::string file = write_test_file("p3.yaml", "a: hello\n");
  ParamReader r("c", load_param_file(file));
  const std::string message = error_of([&] { r.get_double("a"); });
  EXPECT_NE(message.find("a: expected a number, got 'hello'"), std::string::npos) << message;
}

TEST(Params, NonFiniteIsRejected) {
  const std::string file = write_test_file("p4.yaml", "a: .nan\n");
  ParamReader r("c", load_param_file(file));
  EXPECT_NE(error_of([&] { r.get_double("a"); }).find("must be finite"), std::string::npos);
}

TEST(Params, SetAssignmentsBecomeOverridesFromSet) {
  const FlatParams p = parse_param_assignments({"controller.epsilon_m=0.01", "evaluator.topics=[a, b]", "c.k=x=y"});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p.at("controller.epsilon_m").yaml, "0.01");
  EXPECT_EQ(p.at("controller.epsilon_m").file, "--set");
  EXPECT_EQ(p.at("evaluator.topics").yaml, "[a, b]");
  EXPECT_EQ(p.at("c.k").yaml, "x=y");  // the first '=' splits
}

TEST(Params, MalformedSetAssignmentNamesIt) {
  for (const char* bad : {"epsilon=0.1", "controller.epsilon_m", ".k=1", "c.=1", "c.k="}) {
    try {
      parse_param_assignments({bad});
      ADD_FAILURE() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--set '") + bad + "'"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parse_param_assignments({"c.k=1", "c.k=2"}), ConfigError);
}

TEST(Params, SplitParamAssignmentIsShapeOnly) {
  using Split = std::optional<std::pair<std::string, std::string>>;
  EXPECT_EQ(split_param_assignment("c.k=1,2"), Split(std::make_pair(std::string("c.k"), std::string("1,2"))));
  EXPECT_EQ(split_param_assignment("c.k="), Split(std::make_pair(std::string("c.k"), std::string())));
  for (const char* bad : {"c.k", "k=1", ".k=1", "c.=1", ""}) {
    EXPECT_EQ(split_param_assignment(bad), std::nullopt) << bad;
  }
}

TEST(Params, UnknownOverrideNamesOverrideFile) {
  FlatParams defaults{{"a", {"1", "defaults.yaml"}}};
  FlatParams overrides{{"typo", {"2", "scenario.yaml"}}};
  const std::string message = error_of([&] { merge_params(defaults, overrides); });
  EXPECT_NE(message.find("scenario.yaml: typo: unknown parameter (known: a)"), std::string::npos) << message;
}

TEST(Params, OverrideWinsAndKeepsItsFile) {
  FlatParams defaults{{"a", {"1", "defaults.yaml"}}};
  FlatParams overrides{{"a", {"-3", "scenario.yaml"}}};
  ParamReader r("c", merge_params(defaults, overrides));
  EXPECT_DOUBLE_EQ(r.get_double("a"), -3.0);
  const std::string message = error_of([&] { r.fail("a: must be > 0"); });
  EXPECT_EQ(message, "scenario.yaml: a: must be > 0");
}

TEST(Params, CheckReportsAThrowingCheckWithTheKeysFile) {
  FlatParams defaults{{"a", {"1", "defaults.yaml"}}};
  FlatParams overrides{{"a", {"-3", "scenario.yaml"}}};
  ParamReader r("c", merge_params(defaults, overrides));
  const double a = r.get_double("a");
  EXPECT_EQ(error_of([&] { r.check([&] { param_checks::require_positive("a", a); }); }),
            "scenario.yaml: a: must be > 0 and finite (got -3)");
  EXPECT_EQ(error_of([&] { r.check([] {}); }), "");
}

TEST(Params, UnreadKeyIsReported) {
  ParamReader r("plant", FlatParams{{"a", {"1", "d.yaml"}}, {"b", {"2", "d.yaml"}}});
  r.get_double("a");
  EXPECT_NE(error_of([&] { r.check_all_read(); }).find("d.yaml: b: unknown parameter for plant"), std::string::npos);
}

TEST(Params, NegativeUnsignedIsRejected) {
  ParamReader r("c", FlatParams{{"n", {"-1", "d.yaml"}}});
  EXPECT_NE(error_of([&] { r.get_uint("n"); }).find("non-negative"), std::string::npos);
}

TEST(Params, MissingAndMalformedFiles) {
  EXPECT_NE(error_of([] { load_param_file("/nonexistent/x.yaml"); }).find("cannot open"), std::string::npos);
  const std::string bad = write_test_file("bad.yaml", "a: [1, 2\n");
  EXPECT_NE(error_of([&] { load_param_file(bad); }).find("invalid YAML"), std::string::npos);
}

}  // namespace
}  // namespace robodds
