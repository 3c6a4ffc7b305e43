#pragma once
// A metrics module: the figures of one mission kind (a paper's way-points, circumnavigation,
// relative poses, ...) computed from the recorded topics as they arrive, written into
// summary.json's "metrics". The evaluator's core (node/evaluator_node.cpp) records the topics
// and calls every registered module (metrics_module_registry.hpp); each module lives in its own
// folder under sim/evaluator/metrics/ and includes no other module.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/json_writer.hpp"
#include "sim/evaluator/module/metrics_setup.hpp"

namespace robodds::evaluator {

class MetricsModule {
 public:
  virtual ~MetricsModule() = default;
  /// Before the run: attaches callbacks to the recorded topics it consumes (setup.on<Msg>()). A
  /// module whose topics are not recorded attaches nothing and writes nothing; a topic set it
  /// cannot evaluate is a ConfigError (setup.fail()).
  virtual void configure(MetricsSetup& setup) = 0;
  /// At each step, after every recorder took the step's samples (the callbacks ran).
  virtual void step() {}
  /// Once, when the run is over (`completed`) or failed, before the files are flushed:
  /// evaluates what is left.
  virtual void finish(bool /*completed*/) {}
  /// Its keys of summary.json metrics.robots.<robot>, for each served robot.
  virtual void write_robot(JsonWriter& /*json*/, std::uint32_t /*robot*/) const {}
  /// With a single served robot (the papers' setting): its keys at the top level of "metrics".
  virtual void write_single_robot(JsonWriter& /*json*/, std::uint32_t /*robot*/) const {}
  /// Its keys of "metrics" itself (pooled figures, a paper's sections).
  virtual void write_metrics(JsonWriter& /*json*/) const {}
  /// Its verdict on the mission it evaluates (summary.json "mission", issue 27): nullopt when it
  /// judges none (its topics are not recorded); empty when the mission was accomplished; else one
  /// short reason per shortfall ("1 of 18 way-points reached", "phase 2: formation never settled").
  /// Called after finish().
  virtual std::optional<std::vector<std::string>> mission_shortfalls() const { return std::nullopt; }
};

/// summary.json's "mission" from the modules' verdicts (MetricsModule::mission_shortfalls()):
/// nullopt when no module judges a mission; "complete" when none falls short; else
/// "incomplete: " and every reason, "; "-separated, in module order.
std::optional<std::string> mission_verdict(const std::vector<std::optional<std::vector<std::string>>>& verdicts);

}  // namespace robodds::evaluator
