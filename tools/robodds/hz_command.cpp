// `robodds hz TOPIC`: the rate at which a topic's samples arrive, like `ros2 topic hz`: every
// second the average rate and the min/max/std dev of the period over the last --window samples,
// wall clock on arrival; --per-key: one figure per instance (robot_id=1, ...).
#include "runtime/base/error.hpp"
#include "runtime/launch/launch.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/topic_report.hpp"
#include "tools/robodds/topic_watch.hpp"

namespace robodds {
namespace {

class HzCommand : public Command {
 public:
  HzCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("hz", "print the rate at which a topic's samples arrive (like ros2 topic hz)");
    cmd_->add_option("topic", topic_, "topic name, e.g. plant/state")->required();
    cmd_->add_option("--window", window_, "samples the figures are taken over (default 10000, as ros2)")->check(CLI::Range(2, 100000000));
    cmd_->add_flag("--per-key", per_key_, "one rate per instance (robot_id=1, robot_id=2, ...)");
    cmd_->add_option("--duration", duration_s_, "s; stop after this long (0 = until Ctrl-C); nothing seen by then: exit 1")
        ->check(CLI::NonNegativeNumber);
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const TopicInfo& info = topic_info(topic_);
    if (per_key_ && info.key == "-") {
      throw ConfigError("--per-key: " + topic_ + " is unkeyed (one instance)");
    }
    TopicReport report;
    report.window = window_;
    report.per_key = per_key_;
    report.duration_s = duration_s_;
    report.tool = "hz";
    report.format = [](const std::string& instance, const ArrivalWindow& window) {
      const auto stats = period_stats(window);
      return stats ? hz_text(instance, *stats) : std::string();
    };
    return watch_and_report(info, tools_dds(dds_, "robodds-hz"), report, env_.stop);
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string topic_;
  std::size_t window_ = 10000;
  bool per_key_ = false;
  double duration_s_ = 0.0;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_hz_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<HzCommand>(app, env); }

}  // namespace robodds
