#include "sim/run_recorder/node/run_recorder_node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "common/did_you_mean.hpp"
#include "runtime/topics/topic_names.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/key_index.hpp"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/config/params.hpp"
#include "runtime/io/batch_writer_thread.hpp"
#include "runtime/io/sample_verdict.hpp"
#include "runtime/mcap/mcap_writer.hpp"
#include "runtime/mcap/topic_channels.hpp"
#include "sim/run_recorder/node/run_recorder_params.hpp"
#include "system/foxglove/robot_poses.hpp"

namespace robodds::run_recorder {
namespace {

/// foxglove_scene (`--record-foxglove-scene`): the derived foxglove/robot_poses channel, written by
/// the writer thread after the plant/state batches in the file's order (so the step path pays
/// nothing and a lockstep run gives the same messages however it is deployed).
struct Scene {
  foxglove::RobotPoses poses;
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
};

/// Where the samples of a step are written: the file and how log times are made.
struct Sink {
  mcap::Writer* writer = nullptr;
  TimeMode mode = TimeMode::kLockstep;
  double step_s = 0.0;
  Scene* scene = nullptr;  // null: no scene channel (the writer thread's)
};

/// The samples one topic gave at one step, written later by the writer thread. A batch is used
/// again once written (WriterThread::push hands a written one back): its sample vector keeps its
/// capacity, so a step allocates nothing and the writer thread frees nothing the step allocated.
class Batch {
 public:
  explicit Batch(std::size_t stream) : stream_(stream) {}
  virtual ~Batch() = default;
  /// `bytes`: the writer thread's buffer, reused for every sample (no allocation per sample).
  virtual void write(const Sink& sink, std::vector<std::uint8_t>& bytes) = 0;
  virtual std::size_t size() const = 0;
  /// Forgets the samples, keeps the storage.
  virtual void clear() = 0;
  /// The recorder's topic stream this batch belongs to (its index).
  std::size_t stream() const { return stream_; }

 private:
  std::size_t stream_;
};

template <class Msg>
class TypedBatch : public Batch {
 public:
  /// `scene_source`: the batch is of foxglove::kSceneSource, from which the scene is drawn.
  TypedBatch(std::size_t stream, const SampleSerializer* serializer, std::uint16_t channel, std::uint32_t* sequence,
             bool scene_source)
      : Batch(stream), serializer_(serializer), channel_(channel), sequence_(sequence), scene_source_(scene_source) {}

  /// Filled by the step before it is queued.
  std::vector<Msg>& samples() { return samples_; }
  /// The order to write samples() in, as indices (empty: as they are).
  std::vector<std::uint32_t>& order() { return order_; }
  void set_taken_ns(std::int64_t taken_ns) { taken_ns_ = taken_ns; }

  void write(const Sink& sink, std::vector<std::uint8_t>& bytes) override {
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Msg& sample = at(i);
      serializer_->serialize(&sample, bytes);
      sink.writer->write(channel_, ++*sequence_, static_cast<std::uint64_t>(log_time_ns(sink, sample)),
                         static_cast<std::uint64_t>(sample.header().stamp_ns()), bytes.data(), bytes.size());
    }
    if constexpr (std::is_same_v<Msg, idl::RobotState>) {
      if (scene_source_ && sink.scene != nullptr) {
        write_scene(sink, *sink.scene);
      }
    }
  }
  std::size_t size() const override { return samples_.size(); }
  void clear() override {
    samples_.clear();
    order_.clear();
  }

 private:
  /// The i-th sample in the file's order.
  const Msg& at(std::size_t i) const { return samples_[order_.empty() ? i : order_[i]]; }

  /// Lockstep: the sim time of the sample's step (ns), as its stamp: the same in every deployment.
  /// Real time: when the recorder took it (at most one of its steps after arrival).
  std::int64_t log_time_ns(const Sink& sink, const Msg& sample) const {
    return sink.mode == TimeMode::kRealtime
               ? taken_ns_
               : static_cast<std::int64_t>(std::llround(static_cast<double>(sample.header().step()) * sink.step_s * 1e9));
  }

  /// After this batch's states (one step's, every robot's in lockstep): the robots' newest poses,
  /// stamped and timed as the batch's newest sample (the first in file order among equals), when
  /// that stamp is the first or at least foxglove::kScenePeriodNs after the last scene's (as
  /// `robodds record --foxglove-scene`): every pose is then no newer than its message.
  void write_scene(const Sink& sink, Scene& scene) const {
    const Msg* newest = nullptr;
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Msg& sample = at(i);
      scene.poses.update(sample.robot_id(), sample.x(), sample.y(), sample.theta());
      if (newest == nullptr || sample.header().stamp_ns() > newest->header().stamp_ns()) {
        newest = &sample;
      }
    }
    const std::int64_t stamp = newest->header().stamp_ns();
    if (!scene.poses.due(stamp, foxglove::kScenePeriodNs)) {
      return;
    }
    const std::string json = scene.poses.json(stamp);
    sink.writer->write(scene.channel, ++scene.sequence, static_cast<std::uint64_t>(log_time_ns(sink, *newest)),
                       static_cast<std::uint64_t>(stamp), reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
  }

  const SampleSerializer* serializer_;  // the topic's, used by the writer thread only
  std::uint16_t channel_;
  std::uint32_t* sequence_;  // the topic's, touched by the writer thread only
  std::int64_t taken_ns_ = 0;
  std::vector<Msg> samples_;
  std::vector<std::uint32_t> order_;
  bool scene_source_;
};

/// Serializing, framing and compressing take about four times what taking the samples does
/// (docs/performance.md, "Recording in the run"), so a thread of its own does them
/// (runtime/io/batch_writer_thread.hpp), in the order the steps queued their batches.
using WriterThread = BatchWriterThread<Batch>;
/// Batches (one per topic and step) that may wait for the writer thread.
constexpr std::size_t kMaxQueuedBatches = 4096;

/// The writer thread's work for one batch; `bytes`: one sample's payload at a time, reused.
std::function<void(Batch&)> write_to(Sink sink) {
  return [sink, bytes = std::vector<std::uint8_t>()](Batch& batch) mutable { batch.write(sink, bytes); };
}

class TopicStreamBase {
 public:
  virtual ~TopicStreamBase() = default;
  /// Takes the samples it may write now, instance by instance in key order, each instance's in its
  /// producer's order, as one batch (null: none). An input stream takes what the lockstep rule
  /// lets it read; a local stream those of steps before `step_limit`.
  virtual std::unique_ptr<Batch> collect(std::uint16_t channel, std::int64_t taken_ns, std::uint64_t step_limit) = 0;
  /// A written batch of this stream, to fill next (WriterThread::push).
  virtual void reuse(std::unique_ptr<Batch> batch) = 0;
  virtual std::uint64_t messages() const = 0;
};

/// What both kinds of stream share: the batch they fill next (a new one, or a written one again),
/// the topic's serializer, message count and channel sequence.
template <class Msg>
class BatchingStream : public TopicStreamBase {
 public:
  BatchingStream(std::size_t index, std::unique_ptr<SampleSerializer> serializer, bool scene_source)
      : index_(index), serializer_(std::move(serializer)), scene_source_(scene_source) {}

  void reuse(std::unique_ptr<Batch> batch) override { spare_.reset(static_cast<TypedBatch<Msg>*>(batch.release())); }
  std::uint64_t messages() const override { return messages_; }

 protected:
  /// The batch to fill now: empty, its storage kept from earlier steps.
  TypedBatch<Msg>& next_batch(std::uint16_t channel) {
    if (!spare_) {
      spare_ = std::make_unique<TypedBatch<Msg>>(index_, serializer_.get(), channel, &sequence_, scene_source_);
    }
    return *spare_;
  }
  /// next_batch(), filled, for the writer thread; null when it holds no sample.
  std::unique_ptr<Batch> hand_over(std::int64_t taken_ns) {
    if (!spare_ || spare_->size() == 0) {
      return nullptr;
    }
    messages_ += spare_->size();
    spare_->set_taken_ns(taken_ns);
    return std::move(spare_);
  }

 private:
  std::size_t index_;
  std::unique_ptr<SampleSerializer> serializer_;  // used by the writer thread only
  bool scene_source_;
  std::unique_ptr<TypedBatch<Msg>> spare_;
  std::uint64_t messages_ = 0;
  std::uint32_t sequence_ = 0;  // the channel's, written by the writer thread
};

template <class Msg>
class TopicStream : public BatchingStream<Msg> {
 public:
  TopicStream(std::size_t index, Input<Msg>* input, std::unique_ptr<SampleSerializer> serializer,
              std::vector<std::uint64_t> keys, bool by_robot, bool scene_source)
      : BatchingStream<Msg>(index, std::move(serializer), scene_source), input_(input), keys_(std::move(keys)), by_robot_(by_robot) {}

  std::unique_ptr<Batch> collect(std::uint16_t channel, std::int64_t taken_ns, std::uint64_t /*step_limit*/) override {
    std::vector<Msg>& samples = this->next_batch(channel).samples();
    if (by_robot_) {
      input_->take_new_of_robots(keys_, samples);
    } else {
      input_->take_new(keys_, samples);
    }
    return this->hand_over(taken_ns);
  }

 private:
  Input<Msg>* input_;
  std::vector<std::uint64_t> keys_;
  bool by_robot_;
};

/// A topic of a co-located lockstep run, observed on the bus (ComponentContext::observe_local()):
/// every sample its components write, kept by step in write order until the step is over, then
/// written in the order an input stream gives (the file is byte-identical to a recording across
/// processes: integration.run_record, integration.run_record_papers). Only the samples of the
/// instances an input stream would take are kept, and only those that pass an input's checks.
/// The step path copies each sample once and moves none: the generated IDL types' copy and move
/// are out-of-line member-by-member calls, which a sort or a partition would repeat per sample.
template <class Msg>
class LocalStream : public BatchingStream<Msg> {
 public:
  LocalStream(std::size_t index, std::unique_ptr<SampleSerializer> serializer, const std::vector<std::uint64_t>& keys,
              bool by_robot, bool scene_source)
      : BatchingStream<Msg>(index, std::move(serializer), scene_source), by_robot_(by_robot) {
    for (std::uint64_t key : keys) {
      wanted_.insert(key);
    }
  }

  /// Inside the writer's write(), on the step's thread.
  void on_sample(const Msg& sample, const SampleMeta& meta) {
    const std::uint64_t key = idl::instance_key(sample);
    if (wanted_.find(by_robot_ ? key >> 32 : key) == KeyIndex::kNone || delivery_check(sample, meta, TimeMode::kLockstep)) {
      return;  // not an instance the recording takes, or refused (the run's own inputs count it)
    }
    bucket(sample.header().step()).push_back(sample);
  }

  std::unique_ptr<Batch> collect(std::uint16_t channel, std::int64_t taken_ns, std::uint64_t step_limit) override {
    if (pending_.empty() || pending_.front().step >= step_limit) {
      return nullptr;
    }
    TypedBatch<Msg>& batch = this->next_batch(channel);
    std::vector<Msg>& samples = batch.samples();
    std::size_t steps = 0;
    while (!pending_.empty() && pending_.front().step < step_limit) {
      std::vector<Msg>& done = pending_.front().samples;
      if (samples.empty()) {
        samples.swap(done);  // the batch takes the step's storage; the step gets the batch's (empty)
      } else {
        samples.insert(samples.end(), done.begin(), done.end());  // more than one step: only at a run's end
        done.clear();
      }
      spare_samples_.push_back(std::move(done));
      pending_.pop_front();
      ++steps;
    }
    order(samples, steps > 1, batch.order());
    return this->hand_over(taken_ns);
  }

 private:
  struct StepSamples {
    std::uint64_t step = 0;
    std::vector<Msg> samples;  // in write order
  };

  /// The samples of `step`; a new step's storage is one a batch gave back.
  std::vector<Msg>& bucket(std::uint64_t step) {
    auto it = pending_.end();
    while (it != pending_.begin() && std::prev(it)->step > step) {
      --it;  // an older step than the newest: a sample for a step before (not from the plant loop)
    }
    if (it != pending_.begin() && std::prev(it)->step == step) {
      return std::prev(it)->samples;
    }
    StepSamples fresh{step, {}};
    if (!spare_samples_.empty()) {
      fresh.samples = std::move(spare_samples_.back());
      spare_samples_.pop_back();
    }
    return pending_.insert(it, std::move(fresh))->samples;
  }

  /// An input stream's order, as indices into `samples` (left empty when it is theirs already):
  /// by instance key (by robot: robot, then step when a batch holds several, then key), each
  /// instance's samples in write order.
  void order(const std::vector<Msg>& samples, bool several_steps, std::vector<std::uint32_t>& order) const {
    ranks_.clear();
    for (const Msg& sample : samples) {
      const std::uint64_t key = idl::instance_key(sample);
      ranks_.push_back(Rank{by_robot_ ? key >> 32 : key, several_steps ? sample.header().step() : 0, key});
    }
    if (std::is_sorted(ranks_.begin(), ranks_.end())) {
      return;
    }
    order.resize(samples.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) {
      order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(), [this](std::uint32_t a, std::uint32_t b) { return ranks_[a] < ranks_[b]; });
  }

  struct Rank {
    std::uint64_t stream;    // the instance key, or the robot id (by robot)
    std::uint64_t step;      // 0 unless the batch holds several steps
    std::uint64_t key;       // the instance key
    bool operator<(const Rank& o) const {
      return stream != o.stream ? stream < o.stream : step != o.step ? step < o.step : key < o.key;
    }
  };

  KeyIndex wanted_;  // instance keys, or robot ids (by_robot_)
  bool by_robot_;
  std::deque<StepSamples> pending_;             // by step, ascending: written, not yet taken
  std::vector<std::vector<Msg>> spare_samples_;  // emptied storage for the next steps
  mutable std::vector<Rank> ranks_;              // order()'s, kept for its storage
};

/// How the recorder waits for a topic's instances, from its key: one per robot that has a
/// producer, one per robot whatever its target, the instances its producers declared at configure
/// (a pair of robots: ComponentContext::publishes_instances()), or the one instance of an unkeyed
/// topic. A topic keyed otherwise (a string) whose producers declared nothing names instances only
/// the producer knows: the gate cannot wait for them, so it is not recorded.
enum class Gate { kRobots, kRobotStreams, kDeclared, kUnkeyed, kUnsupported };

Gate gate_of(const TopicInfo& topic, const ProducedInstances* declared) {
  if (topic.key == "robot_id") {
    return Gate::kRobots;
  }
  if (topic.key == "robot_id, target_id") {
    return Gate::kRobotStreams;
  }
  if (topic.key == "-") {
    return Gate::kUnkeyed;
  }
  if (declared != nullptr) {
    const auto it = declared->find(topic.name);
    if (it != declared->end() && !it->second.empty()) {
      return Gate::kDeclared;
    }
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
        ctx.params().fail("topics (robodds run --record-topics): unknown topic '" + name + "'" + did_you_mean(name, topic_names()) +
                          " (`robodds record --list` lists the topics)");
      }
      if (producers->count(name) == 0) {
        ctx.params().fail("topics (robodds run --record-topics): no component of the scenario publishes '" + name + "'");
      }
      names.insert(name);
    }
    scene_ = params.foxglove_scene;
    if (scene_ && names.count(foxglove::kSceneSource) == 0) {
      ctx.params().fail(std::string("foxglove_scene (robodds run --record-foxglove-scene) draws the robots from ") + foxglove::kSceneSource +
                        (every ? ": no component of the scenario publishes it" : ": add it to --record-topics"));
    }
    // Installed where DDS was set up; a ConfigError here, before the run, if not.
    const SampleCodec& codec = sample_codec();
    // A co-located lockstep run: every sample is written in this process, on the step's thread, so
    // the recorder observes the bus instead of reading it through inputs (the same file, less CPU
    // on the step). Across processes and in real time, lockstep-gated inputs order what arrives.
    const bool observe_local = mode_ == TimeMode::kLockstep && ctx.single_process();
    // std::set: topics in name order, the order of their channels and of each step's samples.
    std::vector<std::string> skipped;
    for (const std::string& name : names) {
      const TopicInfo& topic = topic_info(name);
      const Gate gate = gate_of(topic, ctx.produced_instances());
      if (gate == Gate::kUnsupported) {
        if (!every) {
          ctx.params().fail("topics: '" + name + "' is keyed (" + topic.key +
                            ") and its producers declare no instances: a lockstep recording cannot wait for them");
        }
        skipped.push_back(name);
        continue;
      }
      std::vector<std::uint64_t> keys;
      if (gate == Gate::kDeclared) {
        keys = ctx.produced_instances()->at(name);  // ascending: the order of each step's samples
      } else {
        for (const auto& [robot, components] : producers->at(name)) {
          keys.push_back(robot);  // std::map: robot ids in order
        }
      }
      idl::dispatch_type(topic.type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        const bool by_robot = gate == Gate::kRobotStreams;
        const bool scene_source = scene_ && name == foxglove::kSceneSource;
        if (observe_local) {
          auto stream = std::make_unique<LocalStream<Msg>>(streams_.size(), codec.serializer(topic.type_name), keys, by_robot,
                                                           scene_source);
          LocalStream<Msg>* raw = stream.get();
          ctx.observe_local<Msg>(name, [raw](const Msg& sample, const SampleMeta& meta) { raw->on_sample(sample, meta); });
          streams_.push_back(std::move(stream));
          return;
        }
        const Subscription subscription =
            gate == Gate::kRobotStreams ? Subscription::robot_streams(keys) : Subscription::instances(keys);
        Input<Msg>* input = &ctx.subscribe<Msg>(name, subscription);
        streams_.push_back(std::make_unique<TopicStream<Msg>>(streams_.size(), input, codec.serializer(topic.type_name),
                                                             keys, by_robot, scene_source));
      });
      topics_.push_back(&topic);
    }
    if (!skipped.empty()) {
      std::string list;
      for (const std::string& name : skipped) {
        list += (list.empty() ? "" : ", ") + name;
      }
      log::info(ctx.name(), "not recorded (keyed, and their producers declare no instances before the run): " + list);
    }
    name_ = ctx.name();
  }

  void on_start() override {
    if (mode_ == TimeMode::kRealtime) {
      open();  // before the wall clock's first step: creating the file must not make step 0 late
    }
  }

  void on_step(const StepInfo& info) override { collect_all(info.step); }

  void on_finish(const StepInfo& info) override {
    collect_all(info.step + 1);  // the last step included
    close();
  }

  /// A failed run: the samples so far stay, in a complete file.
  void on_abort(const std::string&) override {
    try {
      close();
    } catch (const std::exception& e) {
      log::warn(name_, e.what());  // the run failed already: its reason stays the first error
    }
  }

 private:
  /// Queues each topic's batch of what it may write now; local streams: steps before `step_limit`.
  void collect_all(std::uint64_t step_limit) {
    open();
    if (!writer_thread_) {
      return;
    }
    const std::int64_t taken_ns = mode_ == TimeMode::kRealtime ? wall_clock_now_ns() : 0;
    // Local streams take the steps before this one (all written: the host runs step by step).
    for (std::size_t i = 0; i < streams_.size(); ++i) {
      if (std::unique_ptr<Batch> batch = streams_[i]->collect(channels_[i], taken_ns, step_limit)) {
        if (std::unique_ptr<Batch> written = writer_thread_->push(std::move(batch))) {
          streams_[i]->reuse(std::move(written));
        }
      }
    }
  }

  /// Creates the file with its schemas and channels, once; not at configure (a run that never
  /// starts writes nothing; `robodds run` checked the path is writable before the run).
  void open() {
    if (writer_ || streams_.empty()) {
      return;
    }
    writer_ = std::make_unique<mcap::Writer>(file_, options_);
    channels_ = mcap::add_topic_channels(*writer_, topics_);
    Scene* scene = nullptr;
    if (scene_) {  // after the topics' schemas and channels: their ids stay those of a file without it
      scene_state_ = std::make_unique<Scene>();
      scene_state_->channel = foxglove::add_robot_poses_channel(*writer_);
      scene = scene_state_.get();
    }
    writer_thread_ = std::make_unique<WriterThread>("run_recorder", write_to(Sink{writer_.get(), mode_, step_s_, scene}),
                                                   kMaxQueuedBatches);
  }

  void close() {
    if (!writer_) {
      return;
    }
    std::string failure;
    try {
      std::unique_ptr<WriterThread> thread = std::move(writer_thread_);
      thread->finish();  // everything queued written
    } catch (const RunError& e) {
      failure = e.what();
    }
    writer_->close();  // a whole file of what was written, also after a failure
    std::uint64_t messages = 0;
    for (const auto& stream : streams_) {
      messages += stream->messages();
    }
    log::info(name_, std::to_string(topics_.size()) + " topics, " + std::to_string(messages) + " messages, " +
                         std::to_string(writer_->file_bytes()) + " bytes -> " + file_);
    writer_.reset();
    scene_state_.reset();
    streams_.clear();
    if (!failure.empty()) {
      throw RunError(failure);
    }
  }

  mcap::WriterOptions options_;
  std::string file_;
  bool scene_ = false;  // foxglove_scene
  std::string name_;
  TimeMode mode_ = TimeMode::kLockstep;
  double step_s_ = 0.0;
  std::vector<const TopicInfo*> topics_;
  std::vector<std::unique_ptr<TopicStreamBase>> streams_;  // parallel to topics_
  std::vector<std::uint16_t> channels_;                    // parallel to topics_
  std::unique_ptr<mcap::Writer> writer_;
  std::unique_ptr<Scene> scene_state_;           // the writer thread's while it runs
  std::unique_ptr<WriterThread> writer_thread_;  // after writer_ and scene_state_: stopped before they go
};

}  // namespace

std::unique_ptr<Component> make_run_recorder_node() { return std::make_unique<RunRecorderNode>(); }

}  // namespace robodds::run_recorder

ROBODDS_REGISTER_COMPONENT(run_recorder, "records the topics the scenario publishes into an MCAP file (robodds run --record)",
                           robodds::run_recorder::make_run_recorder_node,
                           robodds::run_recorder::run_recorder_param_table);
