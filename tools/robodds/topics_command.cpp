// `robodds topics`: the topics seen on the domain, with type and QoS; -v: every writer and reader
// with its participant, host and QoS (like `ros2 topic list -v`).
#include <cstdio>

#include "runtime/dds/discovery.hpp"
#include "runtime/launch/launch.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/topic_report.hpp"

namespace robodds {
namespace {

class TopicsCommand : public Command {
 public:
  explicit TopicsCommand(CLI::App& app) {
    cmd_ = app.add_subcommand("topics", "list the topics seen on the domain with type and QoS");
    cmd_->add_option("--duration", seconds_, "s to listen");
    cmd_->add_flag("-v,--verbose", verbose_, "every writer and reader of each topic: participant, host, QoS");
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const DdsOptions dds = tools_dds(dds_, "robodds-topics");
    const auto topics = discover_topics(dds, seconds_);
    if (verbose_) {
      std::fputs(topics_verbose_text(topics).c_str(), stdout);
    } else {
      std::printf("%-24s %-36s %3s %3s  %-26s %s\n", "topic", "type", "W", "R", "writer QoS", "reader QoS");
      for (const DiscoveredTopic& t : topics) {
        std::printf("%-24s %-36s %3d %3d  %-26s %s\n", t.name.c_str(), t.type_name.c_str(), t.writers, t.readers,
                    t.writer_qos.c_str(), t.reader_qos.c_str());
      }
    }
    if (topics.empty()) {
      std::printf("(no topics seen in %.1f s on DDS domain %d: is anything running there? --domain or $ROBODDS_DOMAIN_ID "
                  "picks the domain, --duration listens longer)\n",
                  seconds_, dds.domain_id);
    }
    return 0;
  }

 private:
  CLI::App* cmd_ = nullptr;
  double seconds_ = 2.0;
  bool verbose_ = false;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_topics_command(CLI::App& app, const CommandEnv&) { return std::make_unique<TopicsCommand>(app); }

}  // namespace robodds
