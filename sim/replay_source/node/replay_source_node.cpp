// replay_source: a lockstep run takes some topics from a recording. Each recorded sample carries
// its SampleHeader (step, next_step) as the original producer stamped it; this component decodes
// it (SampleCodec) and publishes it at that step through a normal Output with the recorded
// next_step, so every consumer's lockstep wait, the producer checks and the evaluator see what
// they saw in the recorded run. Being a component, it is the scenario's producer of its topics:
// the one-producer check refuses a scenario that also runs their original producers. For a topic
// keyed by a pair of robots (robot_id, peer_id) it declares the pairs the recording holds, as the
// original producer declared the peers it measured (ComponentContext::publishes_instances()).
#include "sim/replay_source/node/replay_source_node.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "common/did_you_mean.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "sim/replay_source/node/recording_cache.hpp"
#include "sim/replay_source/node/replay_recording.hpp"
#include "sim/replay_source/node/replay_source_params.hpp"
#include "sim/replay_source/replay_chain.hpp"

namespace robodds::replay_source {
namespace {

/// What a configure needs of the recording, decoded once per process (RecordingCache): the
/// recording's replayed samples up to the run's last step and the results of its checks.
struct DecodedRecording {
  std::string recovery;                 // a truncated file: what was recovered (ReadReport::recovery())
  std::vector<std::string> late;        // late_topics()
  std::string chain_problem;            // chain_problem() of every replayed sample, up to the run's last step
  std::vector<ChainLink> pair_links;    // of a pair-keyed topic, the first sample of each instance, in log-time order
  // topic -> step -> its samples in log-time order (the decoded Msg of the topic's type); steps
  // after the run's last step are not kept (a short re-run of a long recording).
  std::map<std::string, std::map<std::uint64_t, std::vector<std::shared_ptr<const void>>>> samples;
};

RecordingCache<DecodedRecording>& decoded_recordings() {
  // Two entries: a scenario may replay two recordings (or one with two topic lists).
  static RecordingCache<DecodedRecording> cache(2);
  return cache;
}

/// Decodes one recorded payload of `topic` into `sample`; its place in its instance's chain.
using Decoder = std::function<ChainLink(const std::uint8_t*, std::size_t, std::shared_ptr<const void>&)>;

template <class Msg>
Decoder decoder_of(const std::string& topic) {
  return [topic](const std::uint8_t* data, std::size_t size, std::shared_ptr<const void>& out) {
    auto sample = std::static_pointer_cast<Msg>(sample_codec().deserialize(idl::type_name<Msg>(), data, size));
    ChainLink link{topic, topic + " (" + idl::instance_label(*sample) + ")", sample->header().step(),
                   sample->header().next_step(), idl::instance_key(*sample)};
    out = std::move(sample);
    return link;
  };
}

/// One replayed topic: publishes its decoded samples at their steps.
class Stream {
 public:
  virtual ~Stream() = default;
  /// Publishes the samples recorded for `step` (none: nothing).
  virtual void publish(std::uint64_t step) = 0;
};

template <class Msg>
class TypedStream : public Stream {
 public:
  using BySteps = std::map<std::uint64_t, std::vector<std::shared_ptr<const void>>>;
  TypedStream(Output<Msg>& out, const BySteps& by_step) : out_(out), by_step_(by_step) {}

  void publish(std::uint64_t step) override {
    const auto it = by_step_.find(step);
    if (it == by_step_.end()) return;
    for (const auto& sample : it->second) {
      // A copy: publishing stamps the header, and the decoded sample is shared (RecordingCache).
      Msg msg = *static_cast<const Msg*>(sample.get());
      out_.publish_next_at(msg, msg.header().next_step());  // step and stamp as recorded
    }
  }

 private:
  Output<Msg>& out_;
  const BySteps& by_step_;  // in the DecodedRecording the node holds
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
    // Read and decoded once per process (every configure needs it: a pair-keyed topic's instances
    // are declared from the samples, and a recording that cannot drive the run stops it before
    // anything starts, exit 2), the producer check's dry configures included (the launcher
    // installs the sample codec before them).
    std::string what = "last step " + std::to_string(last_step_) + ", topics";
    for (const std::string& topic : params_.topics) what += " " + topic;
    decoded_ = decoded_recordings().get(params_.file, what, [this] { return decode(); });
    for (const std::string& topic : params_.topics) {
      const TopicInfo& info = topic_info(topic);  // checked by decode()
      if (info.key == "robot_id, peer_id") {
        pair_topics_.insert(topic);  // its instances are the pairs the recording holds: declared below
      }
      const auto samples = decoded_->samples.find(topic);
      const auto& by_step = samples == decoded_->samples.end() ? no_samples_ : samples->second;
      idl::dispatch_type(info.type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        streams_[topic] = std::make_unique<TypedStream<Msg>>(ctx.advertise<Msg>(topic), by_step);
      });
    }
    check(ctx);
  }

  void on_step(const StepInfo& info) override {
    for (auto& [topic, stream] : streams_) {
      stream->publish(info.step);
    }
  }

 private:
  /// Reads the file once, decoding the replayed topics' messages as they are read (the others are
  /// checked, not kept; a sample after the run's last step only for its place in the chain), then
  /// checks the file and its channels: what a failed decode means is known only then.
  std::shared_ptr<const DecodedRecording> decode() const {
    const std::set<std::string> wanted(params_.topics.begin(), params_.topics.end());
    auto out = std::make_shared<DecodedRecording>();
    /// How a channel's messages are read: by the decoder of its catalog topic, or not at all.
    struct Plan {
      Decoder decode;  // empty: not replayed
      std::map<std::uint64_t, std::vector<std::shared_ptr<const void>>>* by_step = nullptr;
      bool pair = false;
    };
    std::map<std::uint16_t, Plan> plans;  // by channel id
    /// One decoded message, in file order.
    struct Read {
      std::uint64_t log_time;
      ChainLink link;
      std::shared_ptr<const void> sample;  // empty after the run's last step
      const Plan* plan;
    };
    std::vector<Read> read;
    std::optional<std::pair<std::uint64_t, std::string>> failure;  // the first in log-time order: (log time, why)
    const mcap::ReadReport report = mcap::scan_mcap(params_.file, mcap::OnDamage::kRecover, [&](const mcap::MessageView& v) {
      auto plan = plans.find(v.channel_id);
      if (plan == plans.end()) {
        Plan p;
        const TopicInfo* topic = wanted.count(v.channel->topic) != 0 ? find_topic(v.channel->topic) : nullptr;
        if (topic != nullptr) {  // not ours: refused after the scan
          idl::dispatch_type(topic->type_name, [&](auto tag) { p.decode = decoder_of<typename decltype(tag)::type>(topic->name); });
          p.by_step = &out->samples[topic->name];
          p.pair = topic->key == "robot_id, peer_id";
        }
        plan = plans.emplace(v.channel_id, std::move(p)).first;
      }
      if (!plan->second.decode) return;
      std::shared_ptr<const void> sample;
      try {
        ChainLink link = plan->second.decode(v.data, v.size, sample);
        if (link.step > last_step_) sample.reset();  // a short re-run of a long recording keeps only its steps
        read.push_back(Read{v.log_time, std::move(link), std::move(sample), &plan->second});
      } catch (const ConfigError& e) {
        if (!failure || v.log_time < failure->first) {
          failure.emplace(v.log_time, name_ + ": " + params_.file + ": message " + std::to_string(v.sequence) + " of channel " +
                                          std::to_string(v.channel_id) + " does not decode: " + e.what());
        }
      }
    });
    if (!report.problems.empty()) {
      throw ConfigError(name_ + ".file: " + report.problems.front() + " (the file is damaged; `robodds info " + params_.file +
                        "` lists every problem)");
    }
    std::set<std::string> in_file;
    for (const mcap::ChannelInfo& c : report.channels) in_file.insert(c.topic);
    std::set<std::string> checked;
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
      replayable_topic(params_.file, report, *channel, "replay_source takes only robodds topics");
      if (!checked.insert(topic).second) {
        throw ConfigError(name_ + ".topics: " + topic + " is listed twice");
      }
    }
    if (failure) throw ConfigError(failure->second);
    out->recovery = report.recovery();
    // In log-time order, as recorded (equal times keep file order): each step's samples are
    // published in that order.
    if (!std::is_sorted(read.begin(), read.end(), [](const Read& x, const Read& y) { return x.log_time < y.log_time; })) {
      std::stable_sort(read.begin(), read.end(), [](const Read& x, const Read& y) { return x.log_time < y.log_time; });
    }
    std::vector<ChainLink> links;
    links.reserve(read.size());
    std::set<std::pair<const void*, std::uint64_t>> pairs_seen;  // (its topic's samples, key): a topic may have two channels
    for (Read& r : read) {
      if (r.sample) (*r.plan->by_step)[r.link.step].push_back(std::move(r.sample));
      if (r.plan->pair && pairs_seen.emplace(r.plan->by_step, r.link.key).second) {
        out->pair_links.push_back(r.link);  // foreign_pair() names the first sample of a foreign pair
      }
      links.push_back(std::move(r.link));
    }
    read = {};
    out->late = late_topics(links);
    out->chain_problem = chain_problem(links, last_step_);
    return out;
  }

  /// The recording's warnings and checks, and the pairs it declares, at every configure.
  void check(ComponentContext& ctx) {
    if (!decoded_->recovery.empty()) {
      log::warn(name_, params_.file + ": " + decoded_->recovery + "; replaying what was recovered");
    }
    for (const std::string& late : decoded_->late) {
      // A consumer would wait for the missing first samples until its input timeout: say why first.
      log::warn(name_, params_.file + ": " + late + ", not 0: was the recorder started after the run?");
    }
    std::vector<std::uint32_t> served;
    for (const RobotSpec& r : ctx.robots()) served.push_back(r.id);
    std::vector<std::uint32_t> robots;
    for (const RobotSpec& r : ctx.scenario().robots) robots.push_back(r.id);
    std::string problem = foreign_pair(decoded_->pair_links, pair_topics_, served, robots);
    // Only the producer of a pair-keyed topic knows its instances before the run (the run's
    // recorder waits for exactly these at each due step): here, the pairs recorded.
    for (auto& [topic, keys] : instances_of(decoded_->pair_links, pair_topics_)) ctx.publishes_instances(topic, std::move(keys));
    if (problem.empty()) problem = decoded_->chain_problem;
    if (!problem.empty()) {
      throw ConfigError(name_ + ": " + params_.file + " cannot drive this run: " + problem);
    }
  }

  std::string name_;
  ReplaySourceParams params_;
  std::uint64_t last_step_ = 0;
  std::shared_ptr<const DecodedRecording> decoded_;
  std::set<std::string> pair_topics_;  // replayed topics keyed (robot_id, peer_id)
  std::map<std::string, std::unique_ptr<Stream>> streams_;  // by topic: a fixed publishing order
  const std::map<std::uint64_t, std::vector<std::shared_ptr<const void>>> no_samples_;  // a topic with no message
};

}  // namespace

std::unique_ptr<Component> make_replay_source_node() { return std::make_unique<ReplaySourceNode>(); }

}  // namespace robodds::replay_source

ROBODDS_REGISTER_COMPONENT(replay_source,
                           "lockstep: publishes topics of an MCAP recording at their recorded steps (re-run an algorithm on recorded data)",
                           robodds::replay_source::make_replay_source_node,
                           robodds::replay_source::replay_source_param_table);
