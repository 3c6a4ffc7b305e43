// The registry keeps the modules in summary order (rank, then name) and refuses a name twice.
#include "sim/evaluator/module/metrics_module_registry.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace robodds::evaluator {
namespace {

class EmptyModule : public MetricsModule {
 public:
  void configure(MetricsSetup& /*setup*/) override {}
};

MetricsModuleType type(const std::string& name, int rank) {
  return {name, "test", "sim/evaluator/module/test", rank, [] { return std::make_unique<EmptyModule>(); }, {}};
}

TEST(MetricsModuleRegistry, KeepsTheModulesByRankThenName) {
  MetricsModuleRegistry registry;
  registry.add(type("zeta", 10));
  registry.add(type("beta", 30));
  registry.add(type("alpha", 30));
  registry.add(type("omega", 20));
  std::vector<std::string> names;
  for (const MetricsModuleType& t : registry.types()) {
    names.push_back(t.name);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"zeta", "omega", "alpha", "beta"}));
}

TEST(MetricsModuleRegistry, RefusesANameTwiceAndATypeWithoutFactory) {
  MetricsModuleRegistry registry;
  registry.add(type("waypoints", 10));
  EXPECT_THROW(registry.add(type("waypoints", 50)), std::logic_error);
  EXPECT_THROW(registry.add({"no_factory", "test", "sim/evaluator/module/test", 60, nullptr, {}}), std::logic_error);
}

}  // namespace
}  // namespace robodds::evaluator
