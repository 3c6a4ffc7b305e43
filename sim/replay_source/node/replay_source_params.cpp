#include "sim/replay_source/node/replay_source_params.hpp"

#include <stdexcept>

namespace robodds::replay_source {
namespace {

params::Check<std::string> a_file() {
  return {"an MCAP file", [](std::string_view key, const std::string& file) {
            if (file.empty()) throw std::invalid_argument(std::string(key) + ": name the recording to replay (an .mcap file)");
          }};
}

params::Check<std::vector<std::string>> some_topics() {
  return {"at least one topic", [](std::string_view key, const std::vector<std::string>& topics) {
            if (topics.empty()) throw std::invalid_argument(std::string(key) + ": name the topics to take from the recording");
          }};
}

}  // namespace

const params::ParamTable<ReplaySourceParams>& replay_source_param_table() {
  static const params::ParamTable<ReplaySourceParams> table =
      params::ParamTable<ReplaySourceParams>(
          "Lockstep only: publishes the listed topics from a recording (robodds record beside a lockstep\n"
          "run, or robodds run --record), each sample at the step its header names, decoded and sent\n"
          "through a normal output with its recorded next_step, so consumers run as in the recorded run.\n"
          "The scenario's one-producer check counts it as the producer of those topics.")
          .add("file", &ReplaySourceParams::file, "", a_file(), "the MCAP recording (relative to the working directory)")
          .add("topics", &ReplaySourceParams::topics, "", some_topics(), "topics to publish from it, e.g. [sensor/position, sensor/odometry]");
  return table;
}

}  // namespace robodds::replay_source
