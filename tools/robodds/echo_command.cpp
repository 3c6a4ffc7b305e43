// `robodds echo TOPIC`: prints the samples of one topic, like `ros2 topic echo`: "name: value"
// text (enums by name, booleans as true/false, sequences as lists), or one JSON object or CSV row
// per sample; --robot/--key keep one instance's samples, --field prints some fields.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "common/did_you_mean.hpp"
#include "runtime/base/log.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/echo_sample.hpp"

namespace robodds {
namespace {

class EchoCommand : public Command {
 public:
  EchoCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("echo", "print samples of a topic");
    cmd_->add_option("topic", topic_, "topic name, e.g. plant/state")->required();
    cmd_->add_option("--count", count_, "exit after this many samples (0 = until Ctrl-C)");
    cmd_->add_option("--timeout", timeout_s_, "s; fail if no sample arrives in time (0 = wait forever)");
    cmd_->add_option("--robot", robot_, "only the samples of this robot (the key robot_id)");
    cmd_->add_option("--key", keys_, "NAME=VALUE: only the samples whose key NAME is VALUE, e.g. peer_id=2 (repeatable)");
    cmd_->add_option("--field", fields_, "print only this field, or the fields under it, e.g. header.step (repeatable)");
    CLI::Option* json = cmd_->add_flag("--json", json_, "one JSON object per sample and line (machine-readable)");
    cmd_->add_flag("--csv", csv_, "a CSV header, then one row per sample")->excludes(json);
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    const TopicInfo& info = topic_info(topic_);
    const std::vector<std::string> key_names = info.key == "-" ? std::vector<std::string>{} : listed_names(info.key);
    if (robot_ && std::find(key_names.begin(), key_names.end(), "robot_id") == key_names.end()) {
      throw ConfigError("--robot: " + topic_ + " has no robot_id key (" + (key_names.empty() ? "it is unkeyed" : "its key: " + info.key) + ")");
    }
    std::vector<EchoKeyFilter> filters;
    try {
      if (robot_) {
        filters.push_back(parse_key_filter("robot_id=" + std::to_string(*robot_), key_names));
      }
      for (const std::string& key : keys_) {
        filters.push_back(parse_key_filter(key, key_names));
      }
    } catch (const std::invalid_argument& e) {
      throw ConfigError(topic_ + ": " + e.what());
    }
    const DdsOptions dds = tools_dds(dds_, "robodds-echo");
    // Declared before the bus so that they outlive it: the bus's reader callback uses them.
    Notifier notifier;
    std::mutex mutex;
    std::vector<std::string> lines;
    auto bus = make_dds_bus(dds);
    idl::dispatch_type(info.type_name, [&](auto tag) {
      using Msg = typename decltype(tag)::type;
      try {
        if (!fields_.empty()) {
          select_fields(echo_fields(Msg{}), fields_);  // a field the type does not have: refused before waiting
        }
      } catch (const std::invalid_argument& e) {
        throw ConfigError(topic_ + " (" + info.type_name + "): " + e.what());
      }
      // Missions are transient local: read them with the mission profile to get the last one.
      bus->reader(topic_, info.type_name, monitor_profile_for(info),
                  [&](const void* sample, const SampleMeta&) {
                    const Msg& m = *static_cast<const Msg*>(sample);
                    const EchoFields all = echo_fields(m);
                    if (!matches(all, filters)) {
                      return;
                    }
                    std::string text = format(idl::instance_label(m), fields_.empty() ? all : select_fields(all, fields_));
                    std::lock_guard<std::mutex> lock(mutex);
                    lines.push_back(std::move(text));
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
        throw RunError(nothing_seen(dds.domain_id, filters));
      }
      notifier.wait(seen, std::chrono::milliseconds(100));
    }
    return 0;
  }

 private:
  /// One sample's output, with its newline. Called on the reader's thread, one sample at a time.
  std::string format(const std::string& instance, const EchoFields& fields) {
    if (json_) {
      return echo_json(fields) + "\n";
    }
    if (csv_) {
      std::string out = csv_header_done_ ? "" : echo_csv_header(fields) + "\n";
      csv_header_done_ = true;
      return out + echo_csv_row(fields) + "\n";
    }
    if (fields_.size() == 1 && fields.size() == 1 && fields.front().first == fields_.front()) {
      return echo_inline(fields.front().second) + "\n";  // one field: its bare value, like `ros2 topic echo --field`
    }
    return echo_text(topic_ + " (" + instance + ")", fields);
  }

  /// Why nothing was printed: the domain listened to, the filters, and how to see what is there.
  std::string nothing_seen(int domain, const std::vector<EchoKeyFilter>& filters) const {
    std::string which;
    for (const EchoKeyFilter& f : filters) {
      which += (which.empty() ? " of " : " ") + f.name + "=" + f.value;
    }
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_s_);
    return "no sample" + which + " on " + topic_ + " within " + seconds + " s " + on_domain_text(domain);
  }

  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string topic_;
  int count_ = 0;
  double timeout_s_ = 0.0;
  std::optional<std::uint32_t> robot_;
  std::vector<std::string> keys_;
  std::vector<std::string> fields_;
  bool json_ = false;
  bool csv_ = false;
  bool csv_header_done_ = false;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_echo_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<EchoCommand>(app, env); }

}  // namespace robodds
