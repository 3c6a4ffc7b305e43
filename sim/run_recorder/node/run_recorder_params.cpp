#include "sim/run_recorder/node/run_recorder_params.hpp"

#include "sim/run_recorder/node/run_recorder_node.hpp"

namespace robodds::run_recorder {

const params::ParamTable<RunRecorderParams>& run_recorder_param_table() {
  static const params::ParamTable<RunRecorderParams> table =
      params::ParamTable<RunRecorderParams>(
          "Records the topics the scenario's components publish into one MCAP file (what `robodds run\n"
          "--record FILE` adds to the evaluator's group): each sample as its wire bytes (XCDR1, schema\n"
          "omgidl, one channel per topic), taken through lockstep-gated inputs, so a lockstep run gives\n"
          "the same file co-located and across processes (log_time = the sample's sim step in ns,\n"
          "publish_time = its stamp; in real time log_time = the wall clock when the recorder took it).")
          .add("file", &RunRecorderParams::file, "", params::any<std::string>(), "the MCAP file to write; empty = record nothing")
          .add("compression", &RunRecorderParams::compression, "", params::any<std::string>(), "chunk compression: zstd, lz4 or none")
          .add("topics", &RunRecorderParams::topics, "", params::any<std::vector<std::string>>(),
               "topics to record; empty = every topic a component of the scenario publishes (keyed by robot_id, "
               "(robot_id, target_id) or unkeyed)")
          .add("chunk_kb", &RunRecorderParams::chunk_kb, "KB", params::positive(), "uncompressed records per MCAP chunk")
          .add("foxglove_scene", &RunRecorderParams::foxglove_scene, "", params::any<bool>(),
               "also write foxglove/robot_poses (foxglove.PosesInFrame, JSON) from plant/state, at most every 50 ms "
               "of the samples' stamps (robodds run --record-foxglove-scene)");
  return table;
}

}  // namespace robodds::run_recorder
