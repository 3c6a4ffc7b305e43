#include "sim/evaluator/node/evaluator_node.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <type_traits>
#include <sys/stat.h>

#include "common/angle.hpp"
#include "common/json_writer.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/param_table_reader.hpp"
#include "runtime/registry.hpp"
#include "runtime/sample_format.hpp"
#include "sim/evaluator/node/evaluator_params.hpp"
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

/// What the metrics need of one robot, updated sample by sample: running figures and the few
/// samples still waiting for their match, never the whole history.
struct RobotMetrics {
  explicit RobotMetrics(std::uint64_t from_step)
      : fixes(position_distance, from_step), position(position_distance, from_step),
        heading(heading_difference, from_step) {}
  TrackSummary truth;
  TruthWindow recent_truth;
  MatchedError fixes;     // sensor/position against truth
  MatchedError position;  // estimate/pose against truth
  MatchedError heading;
  WaypointTracker waypoints;
  bool has_command = false;
  double max_abs_omega = 0.0;
  double max_abs_v = 0.0;
};

/// Which metrics consume truth samples: those whose topics are recorded.
struct TruthConsumers {
  bool fixes = false;
  bool estimates = false;
  bool status = false;
};

/// The metrics of all robots, fed with every recorded sample.
class Metrics {
 public:
  Metrics(std::uint64_t from_step, TruthConsumers consumers) : from_step_(from_step), consumers_(consumers) {}

  template <class Msg>
  void observe(const Msg&) {}
  void observe(const idl::RobotState& m) {
    const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
    RobotMetrics& r = robot(m.robot_id());
    r.truth.add(s);
    r.recent_truth.add(s);
  }
  void observe(const idl::PositionMeasurement& m) { robot(m.robot_id()).fixes.add({m.header().step(), m.x(), m.y(), 0.0}); }
  void observe(const idl::PoseEstimate& m) {
    const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
    robot(m.robot_id()).position.add(s);
    robot(m.robot_id()).heading.add(s);
  }
  void observe(const idl::VelocityCommand& m) {
    RobotMetrics& r = robot(m.robot_id());
    r.has_command = true;
    r.max_abs_omega = std::max(r.max_abs_omega, std::abs(m.omega()));
    r.max_abs_v = std::max(r.max_abs_v, std::abs(m.v()));
  }
  void observe(const idl::ControllerStatus& m) {
    robot(m.robot_id()).waypoints.add_status({m.header().step(), m.waypoints_reached(), m.waypoints_total(), m.done(),
                                              m.switched(), m.switch_distance(), m.epsilon()});
  }
  void observe(const idl::WaypointMission& m) {
    Mission mission;
    for (const idl::Waypoint& w : m.waypoints()) {
      mission.push_back({w.x(), w.y()});
    }
    robot(m.robot_id()).waypoints.set_mission(std::move(mission));
  }

  /// Matches what has arrived with truth and forgets the truth nothing waits for any more.
  void match() {
    for (auto& [id, r] : robots_) {
      r.fixes.match(r.recent_truth);
      r.position.match(r.recent_truth);
      r.heading.match(r.recent_truth);
      r.waypoints.match(r.recent_truth);
      std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
      if (consumers_.fixes) {
        needed = std::min(needed, r.fixes.needed_from());
      }
      if (consumers_.estimates) {
        needed = std::min({needed, r.position.needed_from(), r.heading.needed_from()});
      }
      if (consumers_.status) {
        needed = std::min(needed, r.waypoints.needed_from());
      }
      r.recent_truth.drop_before(needed);
    }
  }

  const RobotMetrics* find(std::uint32_t id) const {
    auto it = robots_.find(id);
    return it != robots_.end() ? &it->second : nullptr;
  }

 private:
  RobotMetrics& robot(std::uint32_t id) { return robots_.try_emplace(id, from_step_).first->second; }

  std::uint64_t from_step_;
  TruthConsumers consumers_;
  std::map<std::uint32_t, RobotMetrics> robots_;
};

class RecorderBase {
 public:
  virtual ~RecorderBase() = default;
  /// Creates the CSV file in `dir` and writes its header.
  virtual void open(const std::string& dir) = 0;
  virtual void collect(const std::vector<std::uint64_t>& keys, Metrics& metrics) = 0;
  /// Pushes the rows written so far to the file; RunError if it cannot.
  virtual void flush() = 0;
  virtual const std::string& topic() const = 0;
  virtual std::uint64_t rejected() const = 0;
  virtual std::size_t rows() const = 0;
};

/// Writes each sample of its topic as a CSV row when it is taken (not opened: no file).
template <class Msg>
class Recorder : public RecorderBase {
 public:
  Recorder(std::string topic, Input<Msg>* input) : topic_(std::move(topic)), input_(input) {}
  void open(const std::string& dir) override {
    path_ = dir + "/" + csv_file_name(topic_);
    file_.open(path_, std::ios::binary | std::ios::trunc);
    file_ << "t_s," << csv_header<Msg>() << '\n';
    if (!file_) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }
  void collect(const std::vector<std::uint64_t>& keys, Metrics& metrics) override {
    text_.clear();
    for (std::uint64_t key : keys) {
      for (const Msg& sample : input_->take_new(key)) {
        append_seconds(text_, static_cast<std::int64_t>(sample.header().stamp_ns()));
        text_ += ',';
        append_csv_row(text_, sample);
        text_ += '\n';
        ++rows_;
        metrics.observe(sample);
      }
    }
    if (file_.is_open()) {
      file_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
    }
  }
  void flush() override {
    if (file_.is_open() && !file_.flush()) {
      throw RunError("evaluator: cannot write " + path_);
    }
  }
  const std::string& topic() const override { return topic_; }
  std::uint64_t rejected() const override { return input_->rejected_count(); }
  std::size_t rows() const override { return rows_; }

 private:
  std::string topic_;
  Input<Msg>* input_;
  std::string path_;
  std::ofstream file_;  // buffered: rows reach the disk in blocks, and at flush()
  std::string text_;    // the rows of one collect()
  std::size_t rows_ = 0;
};

/// How the run ended, for summary.json's "status" (and "reason" when it failed).
struct RunEnd {
  bool completed = true;
  std::string reason;
};

class EvaluatorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const EvaluatorParams params = read_params(p, evaluator_param_table());
    keys_ = ctx.robot_keys();
    context_ = &ctx;
    TruthConsumers consumers;
    for (const std::string& topic : params.topics) {
      const TopicInfo* info = find_topic(topic);
      if (info == nullptr || info->key != "robot_id") {
        p.fail("topics: '" + topic + "' is not a per-robot topic of the catalog (see docs/topics.md)");
      }
      idl::dispatch_type(info->type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        consumers.fixes |= std::is_same_v<Msg, idl::PositionMeasurement>;
        consumers.estimates |= std::is_same_v<Msg, idl::PoseEstimate>;
        consumers.status |= std::is_same_v<Msg, idl::ControllerStatus>;
        auto* input = &ctx.subscribe<Msg>(topic, Subscription::instances(keys_));
        recorders_.push_back(std::make_unique<Recorder<Msg>>(topic, input));
      });
    }
    const auto from_step = static_cast<std::uint64_t>(std::llround(params.metrics_after_s / ctx.step_s()));
    metrics_ = std::make_unique<Metrics>(from_step, consumers);
  }

  void on_step(const StepInfo& info) override {
    if (!files_open_ && !context_->output_dir().empty()) {
      // At the first step, not at configure: a run that never starts leaves no files.
      files_open_ = true;
      ::mkdir(context_->output_dir().c_str(), 0755);
      for (auto& recorder : recorders_) {
        recorder->open(context_->output_dir());
      }
    }
    for (auto& recorder : recorders_) {
      recorder->collect(keys_, *metrics_);
    }
    metrics_->match();
    steps_ = info.step + 1;
  }

  void on_finish(const StepInfo& info) override {
    on_step(info);
    if (context_->output_dir().empty()) {
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
    if (context_ == nullptr || context_->output_dir().empty()) {
      return;
    }
    ::mkdir(context_->output_dir().c_str(), 0755);
    for (const auto& recorder : recorders_) {
      recorder->flush();
    }
    write_summary(RunEnd{false, reason});
  }

 private:
  /// summary.json: one function per section. Written to a temporary file and renamed, so that
  /// it is whole or absent even if the process dies meanwhile.
  void write_summary(const RunEnd& end) const {
    JsonWriter json;
    json.begin_object();
    write_status_section(json, end);
    json.value("scenario", context_->scenario().name);
    json.value("steps", static_cast<std::int64_t>(steps_));
    json.value("step_s", context_->step_s());
    write_metrics_section(json);
    write_run_section(json);
    json.end_object();
    const std::string path = context_->output_dir() + "/summary.json";
    const std::string temporary = path + ".tmp";
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      out << json.str();
      if (!out.flush()) {
        throw RunError("evaluator: cannot write " + temporary);
      }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
      throw RunError("evaluator: cannot rename " + temporary + " to " + path + ": " + std::strerror(errno));
    }
  }

  /// "status": "completed", or "failed" with the error line that ended the run as "reason".
  static void write_status_section(JsonWriter& json, const RunEnd& end) {
    json.value("status", end.completed ? "completed" : "failed");
    if (!end.completed) {
      json.value("reason", end.reason);
    }
  }

  /// Deterministic figures of the recorded data (in lockstep, the same on every run).
  void write_metrics_section(JsonWriter& json) const {
    json.begin_object("metrics");
    PooledRmse fix_rmse;
    PooledRmse estimate_rmse;
    PooledRmse heading_rmse_rad;
    json.begin_object("robots");
    for (std::uint64_t key : keys_) {
      const auto id = static_cast<std::uint32_t>(key);
      json.begin_object(std::to_string(id));
      const RobotMetrics* r = metrics_->find(id);
      if (r != nullptr && !r->truth.empty()) {
        const PoseSample& last = r->truth.last();
        json.value("path_length_m", r->truth.path_length());
        json.value("final_x_m", last.x).value("final_y_m", last.y).value("final_theta_rad", last.theta);
        json.value("state_samples", static_cast<std::int64_t>(r->truth.count()));
        if (r->fixes.seen()) {
          const ErrorStats e = r->fixes.stats();
          json.value("measurement_rmse_m", e.rmse).value("measurement_samples", static_cast<std::int64_t>(e.count));
          fix_rmse.add(e);
        }
        if (r->position.seen()) {
          const ErrorStats e = r->position.stats();
          const ErrorStats h = r->heading.stats();
          json.value("pf_rmse_m", e.rmse).value("heading_rmse_deg", h.rmse * kDegPerRad);
          estimate_rmse.add(e);
          heading_rmse_rad.add(h);
        }
        write_waypoint_metrics(json, *r);
      }
      json.end_object();
    }
    json.end_object();
    if (keys_.size() == 1) {
      // One robot (the paper's setting): its way-point figures at the top level too.
      const RobotMetrics* r = metrics_->find(static_cast<std::uint32_t>(keys_[0]));
      if (r != nullptr && r->waypoints.has_status()) {
        write_waypoint_metrics(json, *r);
      }
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

  void write_waypoint_metrics(JsonWriter& json, const RobotMetrics& r) const {
    if (!r.waypoints.has_status() || !r.waypoints.has_mission()) {
      return;
    }
    const WaypointMetrics m = r.waypoints.metrics(r.truth.empty() ? nullptr : &r.truth.last(), context_->step_s());
    json.value("waypoints_reached", static_cast<std::int64_t>(m.waypoints_reached));
    json.value("waypoints_total", static_cast<std::int64_t>(m.waypoints_total));
    json.value("time_to_final_s", m.time_to_final_s);
    json.value("switch_distance_estimate_m", m.switch_distance_estimate_m);
    json.value("switch_distance_true_m", m.switch_distance_true_m);
    json.value("final_error_true_m", m.final_error_true_m);
    json.value("epsilon", m.epsilon_m);
    if (r.has_command) {
      json.value("max_abs_omega", r.max_abs_omega);
      json.value("max_abs_v", r.max_abs_v);
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::unique_ptr<RecorderBase>> recorders_;
  std::unique_ptr<Metrics> metrics_;
  const ComponentContext* context_ = nullptr;  // owned by the host, which keeps it while it runs us
  std::uint64_t steps_ = 0;  // steps whose samples were taken (the last one + 1)
  bool files_open_ = false;
};

}  // namespace

std::unique_ptr<Component> make_evaluator_node() { return std::make_unique<EvaluatorNode>(); }

}  // namespace robodds::evaluator

ROBODDS_REGISTER_COMPONENT(evaluator, "records topics to CSV and writes summary.json",
                           robodds::evaluator::make_evaluator_node,
                           robodds::evaluator::evaluator_param_table);
