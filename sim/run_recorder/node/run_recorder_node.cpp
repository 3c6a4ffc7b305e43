#include "sim/run_recorder/node/run_recorder_node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/config/params.hpp"
#include "runtime/mcap/mcap_writer.hpp"
#include "runtime/mcap/topic_channels.hpp"
#include "sim/run_recorder/node/run_recorder_params.hpp"

namespace robodds::run_recorder {
namespace {

/// What one recorded topic needs each step: where its samples are written.
struct Sink {
  mcap::Writer* writer = nullptr;
  const SampleCodec* codec = nullptr;
  TimeMode mode = TimeMode::kLockstep;
  double step_s = 0.0;
};

class TopicStreamBase {
 public:
  virtual ~TopicStreamBase() = default;
  /// Writes the samples the lockstep rule lets it read now, instance by instance in key order,
  /// each instance's in its producer's order.
  virtual void collect(const Sink& sink, std::uint16_t channel) = 0;
  virtual std::uint64_t messages() const = 0;
};

template <class Msg>
class TopicStream : public TopicStreamBase {
 public:
  TopicStream(Input<Msg>* input, std::string type_name, std::vector<std::uint64_t> keys, bool by_robot)
      : input_(input), type_name_(std::move(type_name)), keys_(std::move(keys)), by_robot_(by_robot) {}

  void collect(const Sink& sink, std::uint16_t channel) override {
    samples_.clear();
    if (by_robot_) {
      input_->take_new_of_robots(keys_, samples_);
    } else {
      input_->take_new(keys_, samples_);
    }
    // Real time: when the recorder took it (at most one of its steps after it arrived).
    const std::int64_t now_ns = sink.mode == TimeMode::kRealtime && !samples_.empty() ? wall_clock_now_ns() : 0;
    for (const Msg& sample : samples_) {
      const std::vector<std::uint8_t> bytes = sink.codec->serialize(type_name_, &sample);
      // Lockstep: the sim time of the sample's step (ns), as its stamp: the same in every deployment.
      const std::int64_t log_ns =
          sink.mode == TimeMode::kRealtime
              ? now_ns
              : static_cast<std::int64_t>(std::llround(static_cast<double>(sample.header().step()) * sink.step_s * 1e9));
      sink.writer->write(channel, ++sequence_, static_cast<std::uint64_t>(log_ns),
                         static_cast<std::uint64_t>(sample.header().stamp_ns()), bytes.data(), bytes.size());
    }
  }
  std::uint64_t messages() const override { return sequence_; }

 private:
  Input<Msg>* input_;
  std::string type_name_;
  std::vector<std::uint64_t> keys_;
  bool by_robot_;
  std::vector<Msg> samples_;  // reused step after step
  std::uint32_t sequence_ = 0;
};

/// How the recorder waits for a topic's instances, from its key: one per robot that has a
/// producer, one per robot whatever its target, or the one instance of an unkeyed topic. Other
/// keys (a pair of robots, a string) name instances that only the producer knows before the run:
/// the gate cannot wait for them, so such topics are not recorded.
enum class Gate { kRobots, kRobotStreams, kUnkeyed, kUnsupported };

Gate gate_of(const TopicInfo& topic) {
  if (topic.key == "robot_id") {
    return Gate::kRobots;
  }
  if (topic.key == "robot_id, target_id") {
    return Gate::kRobotStreams;
  }
  if (topic.key == "-") {
    return Gate::kUnkeyed;
  }
  return Gate::kUnsupported;
}

class RunRecorderNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    const RunRecorderParams params = read_params(ctx.params(), run_recorder_param_table());
    options_.compression = mcap::parse_compression(params.compression, ctx.name() + ".compression");
    options_.chunk_size_bytes = static_cast<std::uint64_t>(params.chunk_kb * 1024.0);
    options_.validate();
    file_ = params.file;
    mode_ = ctx.mode();
    step_s_ = ctx.step_s();
    streams_.clear();
    topics_.clear();
    const AssignedProducers* producers = ctx.assigned_producers();
    if (file_.empty() || producers == nullptr) {
      return;  // nothing to record, or configured only to find what the scenario publishes
    }
    std::set<std::string> names;
    const bool every = params.topics.empty();
    if (every) {
      for (const auto& [topic, robots] : *producers) {
        names.insert(topic);
      }
    }
    for (const std::string& name : params.topics) {
      if (find_topic(name) == nullptr) {
        ctx.params().fail("topics: unknown topic '" + name + "' (`robodds record --list` lists the topics)");
      }
      if (producers->count(name) == 0) {
        ctx.params().fail("topics: no component of the scenario publishes '" + name + "'");
      }
      names.insert(name);
    }
    // std::set: topics in name order, the order of their channels and of each step's samples.
    std::vector<std::string> skipped;
    for (const std::string& name : names) {
      const TopicInfo& topic = topic_info(name);
      const Gate gate = gate_of(topic);
      if (gate == Gate::kUnsupported) {
        if (!every) {
          ctx.params().fail("topics: '" + name + "' is keyed (" + topic.key +
                            "): its instances are not known before the run, so a lockstep recording cannot wait for them");
        }
        skipped.push_back(name);
        continue;
      }
      std::vector<std::uint64_t> keys;
      for (const auto& [robot, components] : producers->at(name)) {
        keys.push_back(robot);  // std::map: robot ids in order
      }
      idl::dispatch_type(topic.type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        const Subscription subscription =
            gate == Gate::kRobotStreams ? Subscription::robot_streams(keys) : Subscription::instances(keys);
        Input<Msg>* input = &ctx.subscribe<Msg>(name, subscription);
        streams_.push_back(std::make_unique<TopicStream<Msg>>(input, topic.type_name, keys, gate == Gate::kRobotStreams));
      });
      topics_.push_back(&topic);
    }
    if (!skipped.empty()) {
      std::string list;
      for (const std::string& name : skipped) {
        list += (list.empty() ? "" : ", ") + name;
      }
      log::info(ctx.name(), "not recorded (keyed by a pair of robots or a string: instances unknown before the run): " + list);
    }
    codec_ = &sample_codec();  // installed where DDS was set up; a ConfigError here, before the run, if not
    name_ = ctx.name();
  }

  void on_start() override {
    if (mode_ == TimeMode::kRealtime) {
      open();  // before the wall clock's first step: creating the file must not make step 0 late
    }
  }

  void on_step(const StepInfo&) override {
    open();
    const Sink sink{writer_.get(), codec_, mode_, step_s_};
    for (std::size_t i = 0; i < streams_.size(); ++i) {
      streams_[i]->collect(sink, channels_[i]);
    }
  }

  void on_finish(const StepInfo& info) override {
    on_step(info);
    close();
  }

  /// A failed run: the samples so far stay, in a complete file.
  void on_abort(const std::string&) override { close(); }

 private:
  /// Creates the file with its schemas and channels, once; not at configure (a run that never
  /// starts writes nothing; `robodds run` checked the path is writable before the run).
  void open() {
    if (writer_ || streams_.empty()) {
      return;
    }
    writer_ = std::make_unique<mcap::Writer>(file_, options_);
    channels_ = mcap::add_topic_channels(*writer_, topics_);
  }

  void close() {
    if (!writer_) {
      return;
    }
    writer_->close();
    std::uint64_t messages = 0;
    for (const auto& stream : streams_) {
      messages += stream->messages();
    }
    log::info(name_, std::to_string(topics_.size()) + " topics, " + std::to_string(messages) + " messages, " +
                         std::to_string(writer_->file_bytes()) + " bytes -> " + file_);
    writer_.reset();
    streams_.clear();
  }

  mcap::WriterOptions options_;
  std::string file_;
  std::string name_;
  TimeMode mode_ = TimeMode::kLockstep;
  double step_s_ = 0.0;
  const SampleCodec* codec_ = nullptr;
  std::vector<const TopicInfo*> topics_;
  std::vector<std::unique_ptr<TopicStreamBase>> streams_;  // parallel to topics_
  std::vector<std::uint16_t> channels_;                    // parallel to topics_
  std::unique_ptr<mcap::Writer> writer_;
};

}  // namespace

std::unique_ptr<Component> make_run_recorder_node() { return std::make_unique<RunRecorderNode>(); }

}  // namespace robodds::run_recorder

ROBODDS_REGISTER_COMPONENT(run_recorder, "records the topics the scenario publishes into an MCAP file (robodds run --record)",
                           robodds::run_recorder::make_run_recorder_node,
                           robodds::run_recorder::run_recorder_param_table);
