#include "sim/evaluator/node/evaluator_params.hpp"

#include "sim/evaluator/node/evaluator_node.hpp"

namespace robodds::evaluator {

const params::ParamTable<EvaluatorParams>& evaluator_param_table() {
  static const params::ParamTable<EvaluatorParams> table =
      params::ParamTable<EvaluatorParams>(
          "Records the listed topics for every served robot into <out>/<topic with / as _>.csv (a row\n"
          "per sample as it is taken) and computes the scenario's metrics as it goes into\n"
          "<out>/summary.json at the end of the run, with \"status\": \"completed\", or when the run\n"
          "fails, with \"status\": \"failed\", the \"reason\" and the metrics of the data so far.")
          .add("topics", &EvaluatorParams::topics, "", params::any<std::vector<std::string>>(),
               "topics to record (each needs a producer per robot; a relative pose topic, one per robot and peer, needs plant/state too)")
          .add("metrics_after_s", &EvaluatorParams::metrics_after_s, "s", params::non_negative(),
               "error statistics ignore samples before this time (filter start-up)");
  return table;
}

}  // namespace robodds::evaluator
