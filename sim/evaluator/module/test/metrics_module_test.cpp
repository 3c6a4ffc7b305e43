// summary.json's "mission" from the metrics modules' verdicts (issue 27).
#include "sim/evaluator/module/metrics_module.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

using Verdicts = std::vector<std::optional<std::vector<std::string>>>;

TEST(MissionVerdict, NoModuleJudgingMeansNoMissionField) {
  EXPECT_FALSE(mission_verdict({}).has_value());
  EXPECT_FALSE(mission_verdict(Verdicts{std::nullopt, std::nullopt}).has_value());
}

TEST(MissionVerdict, CompleteOnlyWhenNoJudgingModuleFallsShort) {
  EXPECT_EQ(mission_verdict(Verdicts{std::nullopt, std::vector<std::string>{}}), "complete");
  EXPECT_EQ(mission_verdict(Verdicts{std::vector<std::string>{}, std::vector<std::string>{"estimate never valid"}}),
            "incomplete: estimate never valid");
}

TEST(MissionVerdict, EveryReasonInModuleOrder) {
  EXPECT_EQ(mission_verdict(Verdicts{std::vector<std::string>{"0 of 18 way-points reached", "estimate never valid"}, std::nullopt,
                                     std::vector<std::string>{"phase 2: formation never settled"}}),
            "incomplete: 0 of 18 way-points reached; estimate never valid; phase 2: formation never settled");
}

}  // namespace
}  // namespace robodds::evaluator
