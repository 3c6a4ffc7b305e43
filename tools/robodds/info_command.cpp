// `robodds info TOPIC`: the topic's type and every writer and reader on the domain with its
// participant, host and QoS, like `ros2 topic info -v` (runtime/dds/discovery.hpp).
// `robodds info FILE.mcap`: topics, schemas, counts, times, rates, chunks, summary and CRC status
// of a recording (runtime/mcap/mcap_info.hpp prints it). A truncated file (a recorder killed with
// SIGKILL) prints what was recovered and exits 0 with a warning; a damaged one (a CRC or a summary
// that disagrees with the records) prints what it could read, one line per problem, and exits 1; a
// file with nothing readable (missing, not MCAP) is one error line, exit 2.
#include <sys/stat.h>

#include <cstdio>
#include <iostream>

#include "runtime/dds/discovery.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/mcap/mcap_info.hpp"
#include "runtime/mcap/mcap_reader.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/topic_report.hpp"

namespace robodds {
namespace {

class InfoCommand : public Command {
 public:
  explicit InfoCommand(CLI::App& app) {
    cmd_ = app.add_subcommand("info",
                              "describe a topic on the domain (type, each writer and reader with its QoS, like ros2 topic info -v) "
                              "or an MCAP recording (topics, types, counts, times, rates, compression, summary)");
    cmd_->add_option("topic_or_file", path_, "a topic name (e.g. plant/state), or an .mcap file")->required();
    cmd_->add_option("--duration", seconds_, "s to listen for a topic's writers and readers")->check(CLI::PositiveNumber);
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    struct stat st{};
    const bool file = path_.size() >= 5 && path_.compare(path_.size() - 5, 5, ".mcap") == 0;
    return file || ::stat(path_.c_str(), &st) == 0 ? describe_file() : describe_topic();
  }

 private:
  int describe_topic() {
    const TopicInfo& info = topic_info(path_);  // an unknown name: did you mean ...?
    const DdsOptions dds = tools_dds(dds_, "robodds-info");
    DiscoveredTopic seen;
    seen.name = info.name;
    seen.type_name = info.type_name;
    for (DiscoveredTopic& t : discover_topics(dds, seconds_)) {
      if (t.name == info.name) {
        seen = std::move(t);
      }
    }
    std::fputs(topic_info_text(seen).c_str(), stdout);
    if (seen.endpoints.empty()) {
      std::fprintf(stderr, "robodds info: no writer or reader of %s seen within %g s %s\n", info.name.c_str(), seconds_,
                   on_domain_text(dds.domain_id).c_str());
    }
    return 0;
  }

  int describe_file() {
    // Counts only: the messages' bytes are not kept, so a file larger than memory is fine.
    const mcap::ReadReport report = mcap::scan_mcap(path_, mcap::OnDamage::kRecover, nullptr);
    std::cout << mcap::format_info(report) << std::flush;
    if (report.truncated_at) std::cerr << "robodds info: warning: " << path_ << ": " << report.recovery() << "\n";
    if (!report.problems.empty()) {
      std::cerr << "robodds info: " << path_ << ": damaged (" << report.problems.size()
                << (report.problems.size() == 1 ? " problem" : " problems") << ", listed above)\n";
      return 1;
    }
    return 0;
  }

  CLI::App* cmd_ = nullptr;
  std::string path_;
  double seconds_ = 2.0;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_info_command(CLI::App& app, const CommandEnv&) { return std::make_unique<InfoCommand>(app); }

}  // namespace robodds
