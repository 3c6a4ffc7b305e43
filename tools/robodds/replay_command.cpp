// `robodds replay FILE.mcap`: publishes a recording's samples on DDS as a participant of its own
// (like `ros2 bag play`): each sample's recorded bytes unchanged (runtime/dds/raw_bus.hpp), on its
// topic with the topic's real-time QoS profile (what `robodds record` wrote in the channel's
// metadata), at the recorded log-time spacing, R times faster (--rate) or as fast as possible
// (--fast). Before the first sample it waits (bounded) for a reader of every replayed topic, and
// at the end for reliable readers to acknowledge (bounded), so a short replay is not lost to
// discovery at either end.
//
// Only robodds' own topics replay: a channel must carry a catalog topic with its omgidl schema
// and cdr messages (sim/replay_source/node/replay_recording.hpp); anything else is one error line.
// Replaying into a lockstep scenario is the `replay_source` component (sim/replay_source/).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"
#include "runtime/dds/discovery.hpp"
#include "runtime/dds/raw_bus.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/mcap/mcap_reader.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "sim/replay_source/node/replay_recording.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/progress.hpp"

namespace robodds {
namespace {

using Clock = std::chrono::steady_clock;

/// Samples per instance each replay writer keeps until its readers acknowledge them: a topic's
/// own depth (1 for commands: the latest one matters) would let a replay drop a recorded message
/// whenever the next one of its robot comes before a loaded reader acknowledged it.
constexpr std::int32_t kReplayHistoryDepth = 256;

/// "a, b, c" of a set's names.
std::string joined(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// One replayed channel.
struct Replayed {
  const TopicInfo* topic = nullptr;
  std::shared_ptr<RawWriter> writer;
  std::uint64_t written = 0;
  std::uint64_t refused = 0;  // write() returned false
};

class ReplayCommand : public Command {
 public:
  ReplayCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("replay", "publish a recording's samples on DDS (a participant of its own, like ros2 bag play)");
    cmd_->add_option("file", path_, "the .mcap file (robodds record / robodds run --record)")->required();
    cmd_->add_option("--rate", rate_, "replay R times the recorded speed (log-time spacing / R)")
        ->check(CLI::Range(1e-3, 1e6));
    cmd_->add_flag("--fast", fast_, "publish as fast as possible (no spacing)");
    cmd_->add_option("--topics", only_, "replay only these topics (comma-separated)")->delimiter(',');
    cmd_->add_option("--exclude", exclude_, "replay every topic but these (comma-separated)")->delimiter(',');
    cmd_->add_option("--start", start_s_, "s after the file's first log time to start at")->check(CLI::Range(0.0, 1e12));
    cmd_->add_option("--end", end_s_, "s after the file's first log time to stop at (default: the end)")
        ->check(CLI::Range(0.0, 1e12));
    cmd_->add_option("--wait-readers", wait_readers_s_,
                     "s to wait for a reader of every replayed topic before the first sample (0 = none)")
        ->check(CLI::Range(0.0, 3600.0));
    cmd_->add_option("--ack-timeout", ack_timeout_s_, "s to wait at the end for reliable readers to acknowledge")
        ->check(CLI::Range(0.0, 3600.0));
    cmd_->add_option("--discovery-time", discovery_s_,
                     "s to listen for other writers of the replayed topics before joining (0 = do not look)")
        ->check(CLI::Range(0.0, 60.0));
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (fast_ && cmd_->count("--rate") != 0) {
      throw ConfigError("--rate and --fast exclude each other");
    }
    if (end_s_ >= 0 && end_s_ < start_s_) {
      throw ConfigError("--end " + number(end_s_) + " is before --start " + number(start_s_));
    }
    // The whole file first: a bad file or option fails before anything joins the domain.
    const mcap::McapContents contents = replay_source::read_recording(path_);
    const mcap::ReadReport& report = contents.report;
    if (report.truncated_at) {
      std::fprintf(stderr, "robodds replay: warning: %s: %s; replaying what was recovered\n", path_.c_str(),
                   report.recovery().c_str());
    }
    std::map<std::uint16_t, Replayed> channels = chosen_channels(report);

    const std::uint64_t first = contents.messages.empty() ? 0 : contents.messages.front().log_time;
    const std::uint64_t from = first + static_cast<std::uint64_t>(start_s_ * 1e9);
    const std::uint64_t to = end_s_ < 0 ? UINT64_MAX : first + static_cast<std::uint64_t>(end_s_ * 1e9);
    std::vector<const mcap::Message*> messages;
    for (const mcap::Message& m : contents.messages) {
      if (channels.count(m.channel_id) != 0 && m.log_time >= from && m.log_time <= to) {
        messages.push_back(&m);
      }
    }

    const DdsOptions dds = tools_dds(dds_, "robodds-replay");
    warn_about_other_writers(dds, channels);
    auto bus = make_raw_bus(dds);
    std::set<std::string> names;
    for (auto& [id, c] : channels) {
      c.writer = bus->writer(c.topic->name, c.topic->type_name, qos_profile_for(*c.topic, TimeMode::kRealtime, false),
                             kReplayHistoryDepth);
      names.insert(c.topic->name);
    }
    std::printf("robodds replay: %s: %zu messages on %zu topics (%s)%s\n", path_.c_str(), messages.size(), channels.size(),
                joined(names).c_str(), fast_ ? ", as fast as possible" : (", at " + number(rate_) + " x recorded speed").c_str());
    std::fflush(stdout);
    wait_for_readers(channels, dds.domain_id);

    const auto start = Clock::now();
    const std::uint64_t base = messages.empty() ? 0 : messages.front()->log_time;
    const double span_s = messages.empty() ? 0.0 : static_cast<double>(messages.back()->log_time - base) * 1e-9;
    ProgressPacer pacer(isatty(STDERR_FILENO) != 0);
    std::uint64_t done = 0;
    for (const mcap::Message* m : messages) {
      if (env_.stop) break;
      if (!fast_) {
        // Log times need not increase (the reader sorts them); spacing is from the first replayed one.
        const double offset_s = static_cast<double>(m->log_time - base) * 1e-9 / rate_;
        const auto due = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(offset_s));
        while (!env_.stop && Clock::now() < due) {
          std::this_thread::sleep_for(std::min<Clock::duration>(due - Clock::now(), std::chrono::milliseconds(100)));
        }
        if (env_.stop) break;
      }
      Replayed& c = channels.at(m->channel_id);
      if (c.writer->write(m->data.data(), m->data.size())) {
        ++c.written;
      } else {
        ++c.refused;
      }
      const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
      if (pacer.due(++done, messages.size(), wall_s)) {
        const double recorded_s = static_cast<double>(m->log_time - base) * 1e-9;
        std::fputs(progress_output("  " + replay_progress_text(done, messages.size(), recorded_s, span_s, wall_s), pacer.terminal(),
                                   done == messages.size())
                       .c_str(),
                   stderr);
      }
    }
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
    const bool acknowledged = wait_for_acknowledgements(channels);

    std::uint64_t written = 0, refused = 0;
    for (const auto& [id, c] : channels) {
      written += c.written;
      refused += c.refused;
    }
    std::printf("robodds replay: %llu messages in %.3f s (recorded span %.3f s)%s%s%s\n",
                static_cast<unsigned long long>(written), elapsed_s, span_s,
                refused > 0 ? (", " + std::to_string(refused) + " refused by DDS").c_str() : "",
                acknowledged ? "" : ", not every reliable reader acknowledged in time",
                env_.stop ? ", stopped by a signal" : "");
    return refused > 0 ? 1 : 0;
  }

 private:
  static std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }

  /// The channels to replay (--topics / --exclude), each checked to be one of our topics with its
  /// own schema. ConfigError (one line) for an unknown name or a channel that is not ours.
  std::map<std::uint16_t, Replayed> chosen_channels(const mcap::ReadReport& report) const {
    std::set<std::string> in_file;
    for (const mcap::ChannelInfo& c : report.channels) in_file.insert(c.topic);
    for (const auto* list : {&only_, &exclude_}) {
      for (const std::string& name : *list) {
        if (in_file.count(name) == 0) {
          throw ConfigError(std::string(list == &only_ ? "--topics" : "--exclude") + ": unknown topic '" + name + "': not in " +
                            path_ + " (its topics: " + joined(in_file) + ")" +
                            did_you_mean(name, std::vector<std::string>(in_file.begin(), in_file.end())));
        }
      }
    }
    if (!only_.empty() && !exclude_.empty()) {
      throw ConfigError("--topics and --exclude exclude each other");
    }
    std::map<std::uint16_t, Replayed> chosen;
    for (const mcap::ChannelInfo& c : report.channels) {
      const bool wanted = only_.empty() ? std::find(exclude_.begin(), exclude_.end(), c.topic) == exclude_.end()
                                        : std::find(only_.begin(), only_.end(), c.topic) != only_.end();
      if (!wanted) continue;
      const TopicInfo* topic = &replay_source::replayable_topic(path_, report, c, "--exclude " + c.topic + " replays the rest");
      chosen[c.id].topic = topic;
    }
    if (chosen.empty()) {
      throw ConfigError(path_ + (report.channels.empty() ? ": no channel to replay (nothing recovered)" : ": no topic left to replay"));
    }
    return chosen;
  }

  /// Real time has one producer per topic instance: a writer already on the domain (a running
  /// system, another replay) and this replay would be two. Named, not refused: the readers' rule
  /// decides (docs/architecture.md, "One producer per instance and hot standby").
  void warn_about_other_writers(const DdsOptions& dds, const std::map<std::uint16_t, Replayed>& channels) const {
    if (discovery_s_ <= 0) return;
    std::set<std::string> replayed;
    for (const auto& [id, c] : channels) replayed.insert(c.topic->name);
    for (const DiscoveredTopic& t : discover_topics(dds, discovery_s_)) {
      if (replayed.count(t.name) == 0 || t.writers == 0) continue;
      std::set<std::string> who(t.writer_participants.begin(), t.writer_participants.end());
      std::fprintf(stderr,
                   "robodds replay: warning: %s already has a writer on domain %d (participant %s): the run's one-producer "
                   "rule will refuse one of them (readers of a scenario run take only the producer it assigns)\n",
                   t.name.c_str(), dds.domain_id, ("'" + joined(who) + "'").c_str());
    }
  }

  void wait_for_readers(const std::map<std::uint16_t, Replayed>& channels, int domain) const {
    if (wait_readers_s_ <= 0) return;
    std::printf("robodds replay: waiting up to %s s (--wait-readers) for a reader of each topic\n", number(wait_readers_s_).c_str());
    std::fflush(stdout);
    const auto start = Clock::now();
    const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_readers_s_));
    std::set<std::string> missing;
    do {
      missing.clear();
      for (const auto& [id, c] : channels) {
        if (c.writer->matched_readers() == 0) missing.insert(c.topic->name);
      }
      if (missing.empty()) {
        std::printf("robodds replay: every topic has a reader (after %.2f s)\n",
                    std::chrono::duration<double>(Clock::now() - start).count());
        std::fflush(stdout);
        return;
      }
      if (env_.stop) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    } while (Clock::now() < deadline);
    std::fprintf(stderr,
                 "robodds replay: warning: no reader of %s on DDS domain %d after %s s (--wait-readers; `robodds topics --domain %d` "
                 "lists the readers there); replaying anyway\n",
                 joined(missing).c_str(), domain, number(wait_readers_s_).c_str(), domain);
  }

  /// Reliable readers acknowledge every sample (best-effort ones never hold it up), within the
  /// --ack-timeout shared by every writer.
  bool wait_for_acknowledgements(const std::map<std::uint16_t, Replayed>& channels) const {
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(ack_timeout_s_));
    bool all = true;
    for (const auto& [id, c] : channels) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      all = c.writer->wait_acknowledged(std::max(left, std::chrono::milliseconds(0))) && all;
    }
    return all;
  }

  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string path_;
  double rate_ = 1.0;
  bool fast_ = false;
  std::vector<std::string> only_, exclude_;
  double start_s_ = 0.0;
  double end_s_ = -1.0;  // < 0: to the end
  double wait_readers_s_ = 5.0;
  double ack_timeout_s_ = 5.0;
  double discovery_s_ = 1.5;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_replay_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<ReplayCommand>(app, env);
}

}  // namespace robodds
