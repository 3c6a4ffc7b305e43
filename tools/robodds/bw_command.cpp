// `robodds bw TOPIC`: the bandwidth a topic takes, like `ros2 topic bw`: every second the bytes
// per second and the mean/min/max size of its serialized payloads (as on the wire, with the
// 4-byte encapsulation header) over the last --window samples.
#include "runtime/launch/launch.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/topic_report.hpp"
#include "tools/robodds/topic_watch.hpp"

namespace robodds {
namespace {

class BwCommand : public Command {
 public:
  BwCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("bw", "print the bandwidth a topic takes and its message sizes (like ros2 topic bw)");
    cmd_->add_option("topic", topic_, "topic name, e.g. plant/state")->required();
    cmd_->add_option("--window", window_, "samples the figures are taken over (default 100, as ros2)")->check(CLI::Range(2, 100000000));
    cmd_->add_option("--duration", duration_s_, "s; stop after this long (0 = until Ctrl-C); nothing seen by then: exit 1")
        ->check(CLI::NonNegativeNumber);
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const TopicInfo& info = topic_info(topic_);
    TopicReport report;
    report.window = window_;
    report.duration_s = duration_s_;
    report.tool = "bw";
    report.format = [](const std::string&, const ArrivalWindow& window) {
      const auto stats = size_stats(window);
      return stats ? bw_text(*stats) : std::string();
    };
    return watch_and_report(info, tools_dds(dds_, "robodds-bw"), report, env_.stop);
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string topic_;
  std::size_t window_ = 100;
  double duration_s_ = 0.0;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_bw_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<BwCommand>(app, env); }

}  // namespace robodds
