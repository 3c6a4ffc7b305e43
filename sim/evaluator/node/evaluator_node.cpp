#include "sim/evaluator/node/evaluator_node.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sys/stat.h>

#include "common/angle.hpp"
#include "common/json_writer.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/param_table_reader.hpp"
#include "runtime/registry.hpp"
#include "runtime/sample_format.hpp"
#include "sim/evaluator/node/evaluator_params.hpp"
#include "sim/evaluator/node/health_summary.hpp"
#include "sim/evaluator/track.hpp"
#include "sim/evaluator/waypoint_metrics.hpp"

namespace robodds::evaluator {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;

std::string csv_file_name(std::string topic) {
  for (char& c : topic) {
    if (c == '/') {
      c = '_';
    }
  }
  return topic + ".csv";
}

/// What the metrics need from the recorded samples, per robot.
struct Histories {
  std::map<std::uint32_t, Track> truth;
  std::map<std::uint32_t, Track> fixes;
  std::map<std::uint32_t, Track> estimates;
  std::map<std::uint32_t, double> max_abs_omega;
  std::map<std::uint32_t, double> max_abs_v;
  std::map<std::uint32_t, std::vector<StatusSample>> status;
  std::map<std::uint32_t, std::vector<std::array<double, 2>>> missions;

  template <class Msg>
  void observe(const Msg&) {}
  void observe(const idl::RobotState& m) { truth[m.robot_id()].push_back({m.header().step(), m.x(), m.y(), m.theta()}); }
  void observe(const idl::PositionMeasurement& m) { fixes[m.robot_id()].push_back({m.header().step(), m.x(), m.y(), 0.0}); }
  void observe(const idl::PoseEstimate& m) {
    estimates[m.robot_id()].push_back({m.header().step(), m.x(), m.y(), m.theta()});
  }
  void observe(const idl::VelocityCommand& m) {
    max_abs_omega[m.robot_id()] = std::max(max_abs_omega[m.robot_id()], std::abs(m.omega()));
    max_abs_v[m.robot_id()] = std::max(max_abs_v[m.robot_id()], std::abs(m.v()));
  }
  void observe(const idl::ControllerStatus& m) {
    status[m.robot_id()].push_back({m.header().step(), m.waypoints_reached(), m.waypoints_total(), m.done(), m.switched(),
                                    m.switch_distance(), m.epsilon()});
  }
  void observe(const idl::WaypointMission& m) {
    auto& mission = missions[m.robot_id()];
    mission.clear();
    for (const idl::Waypoint& w : m.waypoints()) {
      mission.push_back({w.x(), w.y()});
    }
  }
};

class RecorderBase {
 public:
  virtual ~RecorderBase() = default;
  virtual void collect(const std::vector<std::uint64_t>& keys, Histories& histories) = 0;
  virtual void write(const std::string& dir) const = 0;
  virtual const std::string& topic() const = 0;
  virtual std::uint64_t rejected() const = 0;
  virtual std::size_t rows() const = 0;
};

template <class Msg>
class Recorder : public RecorderBase {
 public:
  Recorder(std::string topic, Input<Msg>* input) : topic_(std::move(topic)), input_(input) {
    text_ = "t_s," + csv_header<Msg>() + "\n";
  }
  void collect(const std::vector<std::uint64_t>& keys, Histories& histories) override {
    for (std::uint64_t key : keys) {
      for (const Msg& sample : input_->take_new(key)) {
        append_seconds(text_, static_cast<std::int64_t>(sample.header().stamp_ns()));
        text_ += ',';
        append_csv_row(text_, sample);
        text_ += '\n';
        ++rows_;
        histories.observe(sample);
      }
    }
  }
  void write(const std::string& dir) const override {
    const std::string path = dir + "/" + csv_file_name(topic_);
    std::ofstream out(path, std::ios::binary);
    out << text_;
    if (!out) {
      throw RunError("evaluator: cannot write " + path);
    }
  }
  const std::string& topic() const override { return topic_; }
  std::uint64_t rejected() const override { return input_->rejected_count(); }
  std::size_t rows() const override { return rows_; }

 private:
  std::string topic_;
  Input<Msg>* input_;
  std::string text_;
  std::size_t rows_ = 0;
};

class EvaluatorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const EvaluatorParams params = read_params(p, evaluator_param_table());
    const std::vector<std::string>& topics = params.topics;
    metrics_after_s_ = params.metrics_after_s;
    keys_ = ctx.robot_keys();
    for (const std::string& topic : topics) {
      const TopicInfo* info = find_topic(topic);
      if (info == nullptr || info->key != "robot_id") {
        p.fail("topics: '" + topic + "' is not a per-robot topic of the catalog (see docs/topics.md)");
      }
      idl::dispatch_type(info->type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        auto* input = &ctx.subscribe<Msg>(topic, Subscription::instances(keys_));
        recorders_.push_back(std::make_unique<Recorder<Msg>>(topic, input));
      });
    }
    context_ = &ctx;
    ctx.request_run_health();  // summary.json "hosts" and "inputs" (health_summary.hpp)
  }

  void on_step(const StepInfo&) override {
    for (auto& recorder : recorders_) {
      recorder->collect(keys_, histories_);
    }
  }

  void on_finish(const StepInfo& info) override {
    on_step(info);
    if (context_->output_dir().empty()) {
      return;
    }
    ::mkdir(context_->output_dir().c_str(), 0755);
    for (const auto& recorder : recorders_) {
      recorder->write(context_->output_dir());
    }
    write_summary(info);
  }

 private:
  void write_summary(const StepInfo& info) const {
    const auto from_step = static_cast<std::uint64_t>(std::llround(metrics_after_s_ / context_->step_s()));
    JsonWriter json;
    json.begin_object();
    json.value("scenario", context_->scenario().name);
    json.value("steps", static_cast<std::int64_t>(info.step + 1));
    json.value("step_s", context_->step_s());
    json.begin_object("metrics");
    PooledRmse fix_rmse;
    PooledRmse estimate_rmse;
    PooledRmse heading_rmse_rad;
    json.begin_object("robots");
    for (std::uint64_t key : keys_) {
      const auto id = static_cast<std::uint32_t>(key);
      json.begin_object(std::to_string(id));
      auto truth = histories_.truth.find(id);
      if (truth != histories_.truth.end() && !truth->second.empty()) {
        const PoseSample& last = truth->second.back();
        json.value("path_length_m", path_length(truth->second));
        json.value("final_x_m", last.x).value("final_y_m", last.y).value("final_theta_rad", last.theta);
        json.value("state_samples", static_cast<std::int64_t>(truth->second.size()));
        auto fixes = histories_.fixes.find(id);
        if (fixes != histories_.fixes.end()) {
          const ErrorStats e = position_error(truth->second, fixes->second, from_step);
          json.value("measurement_rmse_m", e.rmse).value("measurement_samples", static_cast<std::int64_t>(e.count));
          fix_rmse.add(e);
        }
        auto est = histories_.estimates.find(id);
        if (est != histories_.estimates.end()) {
          const ErrorStats e = position_error(truth->second, est->second, from_step);
          const ErrorStats h = heading_error(truth->second, est->second, from_step);
          json.value("pf_rmse_m", e.rmse).value("heading_rmse_deg", h.rmse * kDegPerRad);
          estimate_rmse.add(e);
          heading_rmse_rad.add(h);
        }
        write_waypoint_metrics(json, id, truth->second);
      }
      json.end_object();
    }
    json.end_object();
    if (keys_.size() == 1 && histories_.status.count(static_cast<std::uint32_t>(keys_[0])) != 0) {
      // One robot (the paper's setting): its way-point figures at the top level too.
      const auto id = static_cast<std::uint32_t>(keys_[0]);
      write_waypoint_metrics(json, id, histories_.truth.at(id));
    }
    if (!fix_rmse.empty()) {
      json.value("measurement_rmse_m", fix_rmse.rmse());
    }
    if (!estimate_rmse.empty()) {
      json.value("pf_rmse_m", estimate_rmse.rmse());
    }
    if (!heading_rmse_rad.empty()) {
      json.value("heading_rmse_deg", heading_rmse_rad.rmse() * kDegPerRad);
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
    write_run_section(json);
    write_health_sections(json, context_->run_figures());
    json.end_object();
    const std::string path = context_->output_dir() + "/summary.json";
    std::ofstream out(path, std::ios::binary);
    out << json.str();
    if (!out) {
      throw RunError("evaluator: cannot write " + path);
    }
  }

  /// How the run went on the wall clock (kept apart from "metrics", which are deterministic).
  /// A host started on its own knows no deployment and writes none.
  void write_run_section(JsonWriter& json) const {
    if (context_->deploy_label().empty()) {
      return;
    }
    const RunFigures& run = context_->run_figures();
    const double ticks_per_s = run.wall_time_s > 0 ? static_cast<double>(run.ticks) / run.wall_time_s : 0.0;
    json.begin_object("run");
    json.value("deploy", context_->deploy_label());
    json.value("mode", context_->mode() == TimeMode::kRealtime ? "realtime" : "lockstep");
    json.value("wall_time_s", std::round(run.wall_time_s * 1e6) / 1e6);  // us, like the runner's log
    json.value("ticks", static_cast<std::int64_t>(run.ticks));
    json.value("ticks_per_s", std::round(ticks_per_s * 10.0) / 10.0);
    json.end_object();
  }

  void write_waypoint_metrics(JsonWriter& json, std::uint32_t id, const Track& truth) const {
    auto status = histories_.status.find(id);
    auto mission = histories_.missions.find(id);
    if (status == histories_.status.end() || mission == histories_.missions.end()) {
      return;
    }
    const WaypointMetrics m = waypoint_metrics(truth, status->second, mission->second, context_->step_s());
    json.value("waypoints_reached", static_cast<std::int64_t>(m.waypoints_reached));
    json.value("waypoints_total", static_cast<std::int64_t>(m.waypoints_total));
    json.value("time_to_final_s", m.time_to_final_s);
    json.value("switch_distance_estimate_m", m.switch_distance_estimate_m);
    json.value("switch_distance_true_m", m.switch_distance_true_m);
    json.value("final_error_true_m", m.final_error_true_m);
    json.value("epsilon", m.epsilon_m);
    auto omega = histories_.max_abs_omega.find(id);
    if (omega != histories_.max_abs_omega.end()) {
      json.value("max_abs_omega", omega->second);
      json.value("max_abs_v", histories_.max_abs_v.at(id));
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::unique_ptr<RecorderBase>> recorders_;
  Histories histories_;
  const ComponentContext* context_ = nullptr;  // owned by the host, which keeps it while it runs us
  double metrics_after_s_ = 0.0;  // s, EvaluatorParams::metrics_after_s
};

}  // namespace

std::unique_ptr<Component> make_evaluator_node() { return std::make_unique<EvaluatorNode>(); }

}  // namespace robodds::evaluator

ROBODDS_REGISTER_COMPONENT(evaluator, "records topics to CSV and writes summary.json",
                           robodds::evaluator::make_evaluator_node,
                           robodds::evaluator::evaluator_param_table);
