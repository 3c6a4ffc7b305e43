// `robodds record`: records topics into an MCAP file as a participant of its own (like `ros2 bag
// record`). Each sample is stored as its serialized payload exactly as on the wire (XCDR1 with its
// encapsulation header; runtime/dds/raw_bus.hpp), never decoded, on one channel per topic (schema
// encoding omgidl with the IDL text the type needs, message encoding cdr). log_time is the
// reception time, publish_time the writer's source timestamp (ns since the epoch).
//
// The DDS callbacks only queue a copy of the bytes; the command's thread writes them, so a slow
// disk never holds a DDS receive thread (nor, through it, a run's writers).
//
// --foxglove-scene adds one derived channel, foxglove/robot_poses (foxglove.PosesInFrame, JSON):
// every robot's newest pose from plant/state, at most once per kScenePeriodNs of the samples' own
// stamps, written by the same thread (system/foxglove/robot_poses.hpp, shared with the bridge and the run's recorder).
#include <chrono>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/dds/raw_bus.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/mcap/mcap_writer.hpp"
#include "runtime/mcap/topic_channels.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "system/foxglove/robot_poses.hpp"
#include "tools/robodds/catalog_topics.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/scene_source.hpp"

namespace robodds {
namespace {

/// A sample waiting to be written.
struct Pending {
  std::size_t topic = 0;  // index into the recorded topics
  std::uint64_t log_time_ns = 0;
  std::uint64_t publish_time_ns = 0;
  std::vector<std::uint8_t> bytes;
};

/// The samples the DDS threads hand over, bounded: past kMaxPendingBytes a sample is dropped and
/// counted (the recorder falls behind rather than growing without limit). The writing thread is
/// woken once kWakeAt samples wait, not for each: a wake per sample (a futex call on the DDS
/// thread, a context switch) was about a quarter of the recorder's CPU beside a 200-robot run
/// (perf), CPU the run's own processes lacked. Fewer waiting samples are written at the loop's
/// next timeout (kPollMs).
class PendingQueue {
 public:
  static constexpr std::size_t kMaxPendingBytes = std::size_t{256} << 20;  // 256 MiB
  static constexpr std::size_t kWakeAt = 256;                              // samples
  static constexpr int kPollMs = 20;

  void push(Pending p) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (bytes_ + p.bytes.size() > kMaxPendingBytes) {
        ++dropped_;
        return;
      }
      bytes_ += p.bytes.size();
      queue_.push_back(std::move(p));
      if (queue_.size() != kWakeAt) {
        return;
      }
    }
    notifier_.notify();
  }
  std::deque<Pending> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::deque<Pending> out;
    out.swap(queue_);
    bytes_ = 0;
    return out;
  }
  std::uint64_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }
  Notifier& notifier() { return notifier_; }

 private:
  mutable std::mutex mutex_;
  std::deque<Pending> queue_;
  std::size_t bytes_ = 0;
  std::uint64_t dropped_ = 0;
  Notifier notifier_;
};

/// FILE.mcap, or with a size limit FILE_0.mcap, FILE_1.mcap, ... (`part` inserted before the
/// extension, if any).
std::string part_path(const std::string& out, bool split, std::size_t part) {
  if (!split) {
    return out;
  }
  const auto slash = out.rfind('/');
  const auto dot = out.rfind('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  const std::string suffix = "_" + std::to_string(part);
  return has_extension ? out.substr(0, dot) + suffix + out.substr(dot) : out + suffix;
}

/// The MCAP files of one recording: the open part, its schema and channel ids, and the next part
/// once the open one passes the size limit.
class McapParts {
 public:
  /// `scene`: each part also holds the foxglove/robot_poses channel (write_scene()).
  McapParts(std::string out, std::uint64_t max_bytes, mcap::WriterOptions options, const std::vector<const TopicInfo*>& topics,
            bool scene)
      : out_(std::move(out)), max_bytes_(max_bytes), options_(std::move(options)), topics_(topics), scene_(scene) {
    open_part();
  }

  void write(const Pending& p) { write_on(channels_[p.topic], p.log_time_ns, p.publish_time_ns, p.bytes.data(), p.bytes.size()); }

  /// A foxglove.PosesInFrame message (JSON text) on the scene channel.
  void write_scene(std::uint64_t log_time_ns, std::uint64_t publish_time_ns, const std::string& json) {
    write_on(scene_channel_, log_time_ns, publish_time_ns, reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
  }

  void close() {
    writer_->close();
  }

  std::size_t parts() const { return part_ + 1; }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t bytes() const { return bytes_done_ + writer_->file_bytes(); }
  std::string first_path() const { return part_path(out_, max_bytes_ > 0, 0); }

 private:
  struct Channel {
    std::uint16_t id = 0;
    std::uint32_t sequence = 0;  // per channel and part, from 1
  };

  void write_on(Channel& channel, std::uint64_t log_time_ns, std::uint64_t publish_time_ns, const std::uint8_t* data,
                std::size_t size) {
    writer_->write(channel.id, ++channel.sequence, log_time_ns, publish_time_ns, data, size);
    ++messages_;
    if (max_bytes_ > 0 && writer_->file_bytes() > max_bytes_) {
      writer_->close();
      bytes_done_ += writer_->file_bytes();
      ++part_;
      open_part();
    }
  }

  /// A part holds every schema and channel, so each file reads on its own.
  void open_part() {
    writer_ = std::make_unique<mcap::Writer>(part_path(out_, max_bytes_ > 0, part_), options_);
    channels_.assign(topics_.size(), Channel{});
    const std::vector<std::uint16_t> ids = mcap::add_topic_channels(*writer_, topics_);
    for (std::size_t i = 0; i < topics_.size(); ++i) {
      channels_[i].id = ids[i];
    }
    scene_channel_ = Channel{};
    if (scene_) {
      scene_channel_.id = foxglove::add_robot_poses_channel(*writer_);
    }
  }

  std::string out_;
  std::uint64_t max_bytes_;
  mcap::WriterOptions options_;
  std::vector<const TopicInfo*> topics_;
  std::unique_ptr<mcap::Writer> writer_;
  bool scene_;
  std::vector<Channel> channels_;
  Channel scene_channel_;
  std::size_t part_ = 0;
  std::uint64_t messages_ = 0;
  std::uint64_t bytes_done_ = 0;  // of the closed parts
};

class RecordCommand : public Command {
 public:
  RecordCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("record", "record topics into an MCAP file (a participant of its own, like ros2 bag record)");
    cmd_->add_option("topics", topics_, "topic names, e.g. plant/state sensor/position (or --all)");
    cmd_->add_flag("--all", all_, "record every topic of the topic catalog");
    cmd_->add_flag("--list", list_, "print the topics it can record (name, type, QoS profile) and exit");
    cmd_->add_option("--out", out_, "the MCAP file to write (created or truncated)");
    cmd_->add_option("--duration", duration_s_, "s of wall-clock time to record (0 = until Ctrl-C / SIGTERM)")
        ->check(CLI::Range(0.0, 1e9));
    cmd_->add_option("--max-size", max_size_mb_, "MB per file: split into FILE_0.mcap, FILE_1.mcap, ... (0 = one file)")
        ->check(CLI::Range(0.0, 1e9));
    cmd_->add_option("--compression", compression_, "chunk compression: zstd, lz4 or none");
    cmd_->add_option("--chunk-size", chunk_kb_,
                     "KB of records per chunk: a chunk is written when full, so a killed recorder loses at most "
                     "the open one")
        ->check(CLI::Range(1.0, 1e6));
    cmd_->add_flag("--foxglove-scene", foxglove_scene_,
                   "also write foxglove/robot_poses: every robot's pose from plant/state as a foxglove.PosesInFrame "
                   "(JSON), at most every 50 ms of the samples' stamps, which Foxglove's 3D panel draws as it is");
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (list_) {
      for (const TopicInfo& topic : topic_catalog()) {
        std::printf("%-34s %-36s %s\n", topic.name.c_str(), topic.type_name.c_str(), monitor_profile_for(topic).c_str());
      }
      return 0;
    }
    const std::vector<const TopicInfo*> topics = chosen_topics();
    if (out_.empty()) {
      throw ConfigError("--out FILE.mcap is required");
    }
    mcap::WriterOptions options;
    options.compression = mcap::parse_compression(compression_, "--compression");
    options.chunk_size_bytes = static_cast<std::uint64_t>(chunk_kb_ * 1024);
    options.validate();
    // topics.size(): no sample is the scene's source.
    const std::size_t scene_topic = foxglove_scene_ ? require_scene_source(topics, "the topics") : topics.size();
    // The file first: an unwritable --out fails before anything joins the domain.
    McapParts parts(out_, static_cast<std::uint64_t>(max_size_mb_ * 1e6), options, topics, foxglove_scene_);
    SceneFeed scene("record");
    const auto write = [&](const Pending& p) {
      parts.write(p);
      if (p.topic != scene_topic) {
        return;
      }
      if (const auto json = scene.take(p.bytes.data(), p.bytes.size(), static_cast<std::int64_t>(p.publish_time_ns))) {
        parts.write_scene(p.log_time_ns, p.publish_time_ns, *json);
      }
    };

    PendingQueue queue;  // declared before the bus: its callbacks push into it
    const DdsOptions dds = tools_dds(dds_, "robodds-record");
    auto bus = make_raw_bus(dds);
    for (std::size_t i = 0; i < topics.size(); ++i) {
      const TopicInfo& topic = *topics[i];
      // Missions are transient local: read them with the mission profile to get the last one
      // (as `robodds echo`); every other topic with `monitor`, which matches writers of every profile.
      bus->reader(topic.name, topic.type_name, monitor_profile_for(topic),
                  [&queue, i](const RawSample& s) {
                    queue.push(Pending{i, static_cast<std::uint64_t>(s.reception_time_ns),
                                       static_cast<std::uint64_t>(s.source_time_ns),
                                       std::vector<std::uint8_t>(s.data, s.data + s.size)});
                  },
                  [name = topic.name](const std::string& e) { log::warn("record", name + ": " + e); });
    }
    bus->start();
    std::printf("robodds record: %zu topics -> %s (%s)\n", topics.size(), parts.first_path().c_str(), compression_.c_str());
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    const auto done = [&] {
      return env_.stop || (duration_s_ > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= duration_s_);
    };
    while (!done()) {
      const auto seen = queue.notifier().generation();
      for (const Pending& p : queue.take()) {
        write(p);
      }
      queue.notifier().wait(seen, std::chrono::milliseconds(PendingQueue::kPollMs));
    }
    // The file is finished before the DDS entities are torn down: Fast DDS 2.9.1 may block there
    // (bounded by the shutdown watchdog: exit 3, docs/deployment.md "Troubleshooting"), and
    // what was recorded must not depend on it. Samples that arrive after the stop are not written.
    for (const Pending& p : queue.take()) {
      write(p);
    }
    parts.close();
    std::printf("robodds record: %llu messages, %llu bytes in %zu file%s%s\n",
                static_cast<unsigned long long>(parts.messages()), static_cast<unsigned long long>(parts.bytes()),
                parts.parts(), parts.parts() == 1 ? "" : "s",
                queue.dropped() > 0 ? (", " + std::to_string(queue.dropped()) + " samples dropped (the writer fell behind)").c_str()
                                    : "");
    if (parts.messages() == 0) {
      std::printf("robodds record: no sample of these topics %s\n", on_domain_text(dds.domain_id).c_str());
    }
    std::fflush(stdout);
    bus->close_readers();
    return 0;
  }

 private:
  std::vector<const TopicInfo*> chosen_topics() const {
    if (all_ == !topics_.empty()) {
      throw ConfigError("name the topics to record or give --all (not both)");
    }
    return catalog_topics(topics_, "");
  }

  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::vector<std::string> topics_;
  bool all_ = false;
  bool list_ = false;
  std::string out_;
  double duration_s_ = 0.0;
  double max_size_mb_ = 0.0;
  std::string compression_ = "zstd";
  double chunk_kb_ = 1024.0;  // the writer's default, 1 MiB
  bool foxglove_scene_ = false;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_record_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<RecordCommand>(app, env);
}

}  // namespace robodds
