#include "sim/evaluator/node/evaluator_node.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <sys/stat.h>

#include "common/did_you_mean.hpp"
#include "common/json_writer.hpp"
#include "common/replace_file.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/topics/topic_names.hpp"
#include "runtime/config/params.hpp"
#include "runtime/component/registry.hpp"
#include "sim/evaluator/module/metrics_setup.hpp"
#include "sim/evaluator/module/recorder.hpp"
#include "sim/evaluator/node/evaluator_params.hpp"
#include "sim/evaluator/node/health_summary.hpp"
#include "sim/evaluator/node/run_summary.hpp"
#include "sim/evaluator/node/standby_summary.hpp"

namespace robodds::evaluator {
namespace {

/// The core: records the `topics` of the served robots, one CSV each, feeds each sample to the
/// metrics modules' callbacks and writes summary.json, whose "metrics" the modules fill.
class EvaluatorNode : public Component {
 public:
  explicit EvaluatorNode(MetricsModuleRegistry modules) : module_types_(std::move(modules)) {}

  void configure(ComponentContext& ctx) override {
    const EvaluatorParams params = read_params(ctx.params(), evaluator_param_table());
    keys_ = ctx.robot_keys();
    context_ = &ctx;
    csv_writer_.reset();  // before the recorders whose files it writes
    files_open_ = false;
    recorders_.clear();
    modules_.clear();
    MetricsSetup setup(ctx, params.topics, params.metrics_after_s);
    for (const MetricsModuleType& type : module_types_.types()) {
      modules_.push_back(type.create());
      modules_.back()->configure(setup);
    }
    standby_.configure(setup);
    for (const std::string& topic : params.topics) {
      add_recorder(ctx, setup, topic);
    }
    metrics_after_s_ = params.metrics_after_s;
    recording_ = &ctx.record_run();  // and summary.json "hosts" and "inputs" (health_summary.hpp)
  }

  void on_start() override {
    // Real time: the files before the clock starts (opening them took 3-18 ms at step 0 with 200
    // robots, which made steps 0-1 overrun; docs/performance.md). Lockstep: at the first step, so
    // that a run stopped at its start barrier leaves no files.
    if (context_->mode() == TimeMode::kRealtime) {
      open_files();
    }
  }

  void on_step(const StepInfo& info) override {
    if (!started_) {
      // The run's start as a stamp (s): sim time 0 in lockstep, the epoch's wall clock in real time.
      started_ = true;
      start_s_ = static_cast<double>(info.stamp_ns) * 1e-9 - info.time_s;
      standby_.set_gaps_after_s(start_s_ + metrics_after_s_);
    }
    open_files();
    for (auto& recorder : recorders_) {
      recorder->collect();
    }
    for (auto& module : modules_) {
      module->step();
    }
    steps_ = info.step + 1;
  }

  void on_finish(const StepInfo& info) override {
    on_step(info);
    for (auto& module : modules_) {
      module->finish(true);
    }
    if (recording_->output_dir().empty()) {
      return;
    }
    for (const auto& recorder : recorders_) {
      recorder->flush();
    }
    write_summary(RunEnd{});
  }

  /// The run failed: the rows recorded so far stay, summary.json says why and holds the metrics
  /// of the data so far.
  void on_abort(const std::string& reason) override {
    if (recording_ == nullptr || recording_->output_dir().empty()) {
      return;
    }
    ::mkdir(recording_->output_dir().c_str(), 0755);
    for (auto& module : modules_) {
      module->finish(false);
    }
    for (const auto& recorder : recorders_) {
      recorder->flush();
    }
    write_summary(RunEnd{false, reason});
  }

 private:
  /// The recorder of `topic`: the one a module makes for it, else a CSV row per sample of each
  /// served robot (every robot if a module asks) passed to the modules' callbacks.
  void add_recorder(ComponentContext& ctx, MetricsSetup& setup, const std::string& topic) {
    if (const MetricsSetup::RecorderFactory* make = setup.own_recorder(topic)) {
      recorders_.push_back((*make)());
      return;
    }
    const TopicInfo* info = find_topic(topic);
    // Keyed (robot_id, target_id): one stream per robot whatever its target (a mission event moves it).
    const bool by_robot = info != nullptr && info->key == "robot_id, target_id";
    if (info == nullptr || (info->key != "robot_id" && !by_robot)) {
      if (info == nullptr) {  // a typo ('plant/stat') names the topic it missed
        ctx.params().fail("topics: unknown topic '" + topic + "'" + did_you_mean(topic, topic_names()) + " (docs/topics.md lists them)");
      }
      ctx.params().fail("topics: '" + topic + "' is not a per-robot topic (key robot_id or robot_id, target_id) of the catalog, "
                        "nor one a metrics module records (e.g. a relative pose topic, key robot_id, peer_id; see docs/topics.md)");
    }
    std::vector<std::uint64_t> keys = keys_;
    if (setup.records_every_robot(topic)) {
      const std::vector<std::uint32_t> ids = setup.scenario_robots();
      keys.assign(ids.begin(), ids.end());
    }
    idl::dispatch_type(info->type_name, [&](auto tag) {
      using Msg = typename decltype(tag)::type;
      auto* input = &ctx.subscribe<Msg>(topic, by_robot ? Subscription::robot_streams(keys) : Subscription::instances(keys));
      recorders_.push_back(std::make_unique<Recorder<Msg>>(topic, input, keys, by_robot, setup.take_callbacks<Msg>(topic)));
    });
  }

  /// Creates the output folder and each recorder's file, once; not at configure: a run that never
  /// starts leaves no files.
  void open_files() {
    if (files_open_ || recording_->output_dir().empty()) {
      return;
    }
    files_open_ = true;
    ::mkdir(recording_->output_dir().c_str(), 0755);
    csv_writer_ = make_csv_writer();
    for (auto& recorder : recorders_) {
      recorder->open(recording_->output_dir(), *csv_writer_);
    }
  }

  /// summary.json: one function per section. Written to a temporary file and renamed, so that
  /// it is whole or absent even if the process dies meanwhile.
  void write_summary(const RunEnd& end) const {
    JsonWriter json;
    json.begin_object();
    write_status_section(json, end, recording_->figures());
    if (end.completed) {
      // Issue 27: a run that completed may still have missed its mission; say why (a failed run
      // says why in "reason").
      std::vector<std::optional<std::vector<std::string>>> verdicts;
      for (const auto& module : modules_) {
        verdicts.push_back(module->mission_shortfalls());
      }
      if (const std::optional<std::string> mission = mission_verdict(verdicts)) {
        json.value("mission", *mission);
      }
    }
    json.value("scenario", context_->scenario().name);
    if (!context_->scenario().description.empty()) {
      json.value("description", context_->scenario().description);  // the plots' subtitle (sim/report)
    }
    json.value("steps", static_cast<std::int64_t>(steps_));
    json.value("step_s", context_->step_s());
    json.value("metrics_after_s", metrics_after_s_);  // s: where the errors start (the plots' RMSEs count from it too)
    write_metrics_section(json);
    write_run_section(json, *recording_, context_->mode());
    standby_.write(json, keys_, start_s_);
    write_health_sections(json, recording_->figures());
    json.end_object();
    const std::string error = replace_file(recording_->output_dir() + "/summary.json", json.str());
    if (!error.empty()) {
      throw RunError("evaluator: " + error);
    }
  }

  /// Deterministic figures of the recorded data (in lockstep, the same on every run): each
  /// module's per robot, at the top level for a single robot, and its own; then the samples
  /// recorded and rejected per topic.
  void write_metrics_section(JsonWriter& json) const {
    json.begin_object("metrics");
    json.begin_object("robots");
    for (std::uint64_t key : keys_) {
      json.begin_object(std::to_string(key));
      for (const auto& module : modules_) {
        module->write_robot(json, static_cast<std::uint32_t>(key));
      }
      json.end_object();
    }
    json.end_object();
    if (keys_.size() == 1) {
      for (const auto& module : modules_) {
        module->write_single_robot(json, static_cast<std::uint32_t>(keys_[0]));
      }
    }
    for (const auto& module : modules_) {
      module->write_metrics(json);
    }
    json.begin_object("samples");
    for (const auto& recorder : recorders_) {
      json.value(recorder->topic(), static_cast<std::int64_t>(recorder->rows()));
    }
    json.end_object();
    json.begin_object("rejected_samples");
    for (const auto& recorder : recorders_) {
      json.value(recorder->topic(), static_cast<std::int64_t>(recorder->rejected()));
    }
    json.end_object();
    json.end_object();
  }

  MetricsModuleRegistry module_types_;
  std::vector<std::unique_ptr<MetricsModule>> modules_;  // by summary rank
  std::vector<std::uint64_t> keys_;
  std::vector<std::unique_ptr<RecorderBase>> recorders_;  // in the order of `topics`
  // Formats and writes the recorders' rows off the step (a lockstep step waits for the evaluator:
  // with 200 robots the rows were half its step, docs/performance.md). After recorders_: it is
  // stopped, everything queued written, before the files it writes go.
  std::unique_ptr<CsvWriter> csv_writer_;
  StandbySummary standby_;
  const ComponentContext* context_ = nullptr;  // owned by the host, which keeps it while it runs us
  const RunRecording* recording_ = nullptr;     // this component records the run (context_->record_run())
  std::uint64_t steps_ = 0;  // steps whose samples were taken (the last one + 1)
  bool files_open_ = false;
  bool started_ = false;         // the first step was seen (start_s_ is known)
  double start_s_ = 0.0;         // the run's start as a stamp (s)
  double metrics_after_s_ = 0.0;
};

}  // namespace

std::unique_ptr<Component> make_evaluator_node_with_modules(MetricsModuleRegistry modules) {
  return std::make_unique<EvaluatorNode>(std::move(modules));
}

std::unique_ptr<Component> make_evaluator_node() {
  MetricsModuleRegistry modules;
  register_builtin_metrics_modules(modules);
  return make_evaluator_node_with_modules(std::move(modules));
}

}  // namespace robodds::evaluator

ROBODDS_REGISTER_COMPONENT(evaluator, "records topics to CSV and writes summary.json",
                           robodds::evaluator::make_evaluator_node,
                           robodds::evaluator::evaluator_param_table);
