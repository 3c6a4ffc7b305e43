// `robodds echo TOPIC`: prints the samples of one topic as text.
#include <chrono>
#include <cstdio>
#include <mutex>

#include "runtime/launch/launch.hpp"
#include "runtime/base/log.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/io/sample_format.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class EchoCommand : public Command {
 public:
  EchoCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("echo", "print samples of a topic");
    cmd_->add_option("topic", topic_, "topic name, e.g. plant/state")->required();
    cmd_->add_option("--count", count_, "exit after this many samples (0 = until Ctrl-C)");
    cmd_->add_option("--timeout", timeout_s_, "s; fail if no sample arrives in time (0 = wait forever)");
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const TopicInfo& info = topic_info(topic_);
    // Declared before the bus so that they outlive it: the bus's reader callback uses them.
    Notifier notifier;
    std::mutex mutex;
    std::vector<std::string> lines;
    auto bus = make_dds_bus(tools_dds(dds_, "robodds-echo"));
    idl::dispatch_type(info.type_name, [&](auto tag) {
      using Msg = typename decltype(tag)::type;
      // Missions are transient local: read them with the mission profile to get the last one.
      bus->reader(topic_, info.type_name, monitor_profile_for(info),
                  [&](const void* sample, const SampleMeta&) {
                    const Msg& m = *static_cast<const Msg*>(sample);
                    std::lock_guard<std::mutex> lock(mutex);
                    lines.push_back("--- " + topic_ + " (" + idl::instance_label(m) + ")\n" + to_text(m));
                    notifier.notify();
                  },
                  [&](const std::string& e) { log::warn("echo", topic_ + ": " + e); });
    });
    bus->start();
    int printed = 0;
    const auto start = std::chrono::steady_clock::now();
    while (!env_.stop && (count_ == 0 || printed < count_)) {
      const auto seen = notifier.generation();
      std::vector<std::string> batch;
      {
        std::lock_guard<std::mutex> lock(mutex);
        batch.swap(lines);
      }
      for (const std::string& text : batch) {
        if (count_ != 0 && printed >= count_) {
          break;
        }
        std::fputs(text.c_str(), stdout);
        ++printed;
      }
      std::fflush(stdout);
      if (printed == 0 && timeout_s_ > 0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s_) {
        throw RunError("no sample on " + topic_ + " within " + std::to_string(timeout_s_) + " s");
      }
      notifier.wait(seen, std::chrono::milliseconds(100));
    }
    return 0;
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string topic_;
  int count_ = 0;
  double timeout_s_ = 0.0;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_echo_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<EchoCommand>(app, env); }

}  // namespace robodds
