// replay_source: a lockstep run takes some topics from a recording. Each recorded sample carries
// its SampleHeader (step, next_step) as the original producer stamped it; this component decodes
// it (SampleCodec) and publishes it at that step through a normal Output with the recorded
// next_step, so every consumer's lockstep wait, the producer checks and the evaluator see what
// they saw in the recorded run. Being a component, it is the scenario's producer of its topics:
// the one-producer check refuses a scenario that also runs their original producers. For a topic
// keyed by a pair of robots (robot_id, peer_id) it declares the pairs the recording holds, as the
// original producer declared the peers it measured (ComponentContext::publishes_instances()).
#include "sim/replay_source/node/replay_source_node.hpp"

#include <map>
#include <memory>
#include <set>
#include <vector>

#include "common/did_you_mean.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "sim/replay_source/node/replay_recording.hpp"
#include "sim/replay_source/node/replay_source_params.hpp"
#include "sim/replay_source/replay_chain.hpp"

namespace robodds::replay_source {
namespace {

/// One replayed topic: its decoded samples by step, and its output.
class Stream {
 public:
  virtual ~Stream() = default;
  /// Decodes one recorded payload and keeps it for its step; its place in its instance's chain.
  virtual ChainLink add(const std::uint8_t* data, std::size_t size) = 0;
  /// Publishes the samples recorded for `step` (none: nothing), and forgets them.
  virtual void publish(std::uint64_t step) = 0;
};

template <class Msg>
class TypedStream : public Stream {
 public:
  TypedStream(std::string topic, Output<Msg>& out) : topic_(std::move(topic)), out_(out) {}

  ChainLink add(const std::uint8_t* data, std::size_t size) override {
    auto sample = std::static_pointer_cast<Msg>(sample_codec().deserialize(idl::type_name<Msg>(), data, size));
    const ChainLink link{topic_, topic_ + " (" + idl::instance_label(*sample) + ")", sample->header().step(),
                         sample->header().next_step(), idl::instance_key(*sample)};
    by_step_[link.step].push_back(std::move(sample));
    return link;
  }

  void publish(std::uint64_t step) override {
    const auto it = by_step_.find(step);
    if (it == by_step_.end()) return;
    for (const auto& sample : it->second) {
      out_.publish_next_at(*sample, sample->header().next_step());  // step and stamp as recorded
    }
    by_step_.erase(it);
  }

 private:
  std::string topic_;
  Output<Msg>& out_;
  std::map<std::uint64_t, std::vector<std::shared_ptr<Msg>>> by_step_;  // in file (log-time) order per step
};

class ReplaySourceNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    name_ = ctx.name();
    if (ctx.mode() != TimeMode::kLockstep) {
      throw ConfigError(name_ + ": replay_source runs in lockstep only (in real time `robodds replay FILE.mcap` publishes a recording)");
    }
    params_ = read_params(ctx.params(), replay_source_param_table());
    last_step_ = ctx.scenario().last_step();
    // Channels are checked here, before anything runs (the index only, no message kept).
    const mcap::ReadReport report = mcap::scan_mcap(params_.file, mcap::OnDamage::kRecover, nullptr);
    if (!report.problems.empty()) {
      throw ConfigError(name_ + ".file: " + report.problems.front() + " (the file is damaged; `robodds info " + params_.file +
                        "` lists every problem)");
    }
    std::set<std::string> in_file;
    for (const mcap::ChannelInfo& c : report.channels) in_file.insert(c.topic);
    for (const std::string& topic : params_.topics) {
      const mcap::ChannelInfo* channel = nullptr;
      for (const mcap::ChannelInfo& c : report.channels) {
        if (c.topic == topic) channel = &c;
      }
      if (channel == nullptr) {
        std::string names;
        for (const std::string& n : in_file) names += (names.empty() ? "" : ", ") + n;
        throw ConfigError(name_ + ".topics: " + params_.file + " has no topic '" + topic + "' (" +
                          (names.empty() ? std::string("it holds no channel") : "its topics: " + names) + ")" +
                          did_you_mean(topic, std::vector<std::string>(in_file.begin(), in_file.end())));
      }
      const TopicInfo& info = replayable_topic(params_.file, report, *channel, "replay_source takes only robodds topics");
      if (streams_.count(topic) != 0) {
        throw ConfigError(name_ + ".topics: " + topic + " is listed twice");
      }
      if (info.key == "robot_id, peer_id") {
        pair_topics_.insert(topic);  // its instances are the pairs the recording holds: declared below
      }
      idl::dispatch_type(info.type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        streams_[topic] = std::make_unique<TypedStream<Msg>>(topic, ctx.advertise<Msg>(topic));
      });
    }
    // Decoded at every configure, the producer check's dry ones included (the launcher installs
    // the sample codec before them): a pair-keyed topic's instances are declared from the samples,
    // and a recording that cannot drive the run stops it before anything starts (exit 2).
    load(ctx);
  }

  void on_step(const StepInfo& info) override {
    for (auto& [topic, stream] : streams_) {
      stream->publish(info.step);
    }
  }

 private:
  void load(ComponentContext& ctx) {
    const mcap::McapContents contents = read_recording(params_.file);
    if (contents.report.truncated_at) {
      log::warn(name_, params_.file + ": " + contents.report.recovery() + "; replaying what was recovered");
    }
    std::map<std::uint16_t, Stream*> by_channel;
    for (const mcap::ChannelInfo& c : contents.report.channels) {
      const auto it = streams_.find(c.topic);
      if (it != streams_.end()) by_channel[c.id] = it->second.get();
    }
    std::vector<ChainLink> links;
    for (const mcap::Message& m : contents.messages) {
      const auto it = by_channel.find(m.channel_id);
      if (it == by_channel.end()) continue;
      try {
        links.push_back(it->second->add(m.data.data(), m.data.size()));
      } catch (const ConfigError& e) {
        throw ConfigError(name_ + ": " + params_.file + ": message " + std::to_string(m.sequence) + " of channel " +
                          std::to_string(m.channel_id) + " does not decode: " + e.what());
      }
    }
    for (const std::string& late : late_topics(links)) {
      // A consumer would wait for the missing first samples until its input timeout: say why first.
      log::warn(name_, params_.file + ": " + late + ", not 0: was the recorder started after the run?");
    }
    std::vector<std::uint32_t> served;
    for (const RobotSpec& r : ctx.robots()) served.push_back(r.id);
    std::vector<std::uint32_t> robots;
    for (const RobotSpec& r : ctx.scenario().robots) robots.push_back(r.id);
    std::string problem = foreign_pair(links, pair_topics_, served, robots);
    // Only the producer of a pair-keyed topic knows its instances before the run (the run's
    // recorder waits for exactly these at each due step): here, the pairs recorded.
    for (auto& [topic, keys] : instances_of(links, pair_topics_)) ctx.publishes_instances(topic, std::move(keys));
    if (problem.empty()) problem = chain_problem(std::move(links), last_step_);
    if (!problem.empty()) {
      throw ConfigError(name_ + ": " + params_.file + " cannot drive this run: " + problem);
    }
  }

  std::string name_;
  ReplaySourceParams params_;
  std::uint64_t last_step_ = 0;
  std::set<std::string> pair_topics_;  // replayed topics keyed (robot_id, peer_id)
  std::map<std::string, std::unique_ptr<Stream>> streams_;  // by topic: a fixed publishing order
};

}  // namespace

std::unique_ptr<Component> make_replay_source_node() { return std::make_unique<ReplaySourceNode>(); }

}  // namespace robodds::replay_source

ROBODDS_REGISTER_COMPONENT(replay_source,
                           "lockstep: publishes topics of an MCAP recording at their recorded steps (re-run an algorithm on recorded data)",
                           robodds::replay_source::make_replay_source_node,
                           robodds::replay_source::replay_source_param_table);
