#include "sim/evaluator/node/evaluator_node.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <type_traits>
#include <sys/stat.h>

#include "common/angle.hpp"
#include "common/json_writer.hpp"
#include "common/number_text.hpp"
#include "common/replace_file.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/config/params.hpp"
#include "runtime/component/registry.hpp"
#include "sim/evaluator/node/csv_recorder.hpp"
#include "sim/evaluator/node/evaluator_params.hpp"
#include "sim/evaluator/node/sample_metrics.hpp"
#include "sim/evaluator/node/health_summary.hpp"
#include "sim/evaluator/node/relative_recorder.hpp"
#include "sim/evaluator/node/timing_summary.hpp"
#include "sim/evaluator/motion_extremes.hpp"
#include "sim/evaluator/track.hpp"
#include "sim/evaluator/waypoint_metrics.hpp"
#include "system/robot_facts.hpp"

namespace robodds::evaluator {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;

/// Why a run that reached its end is degraded: every host that ran without some of its peers
/// (HostHealth::degraded) and every host whose report never came; empty: none.
std::string degraded_reason(const RunFigures& figures) {
  std::string reason;
  for (const HostHealth& host : figures.hosts) {
    if (!host.degraded.empty()) {
      reason += (reason.empty() ? "" : "; ") + std::string("host '") + host.member + "' " + host.degraded;
    }
  }
  for (const std::string& member : figures.hosts_not_heard) {
    reason += (reason.empty() ? "" : "; ") + std::string("host '") + member + "' did not report (run/health): it may have run alone or not at all";
  }
  return reason;
}

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
    recorders_.clear();
    TruthConsumers consumers;
    std::vector<std::string> stages;  // paper 3: the stages of the relative pose topics
    const bool relative = std::any_of(params.topics.begin(), params.topics.end(),
                                      [](const std::string& topic) { return relative_stage_of(topic) != nullptr; });
    for (const std::string& topic : params.topics) {
      const TopicInfo* info = find_topic(topic);
      // Keyed (robot_id, target_id): one stream per robot whatever its target (a mission event moves it).
      const bool by_robot = info != nullptr && info->key == "robot_id, target_id";
      if (const char* stage = relative_stage_of(topic)) {
        add_relative_topic(ctx, topic, stage, params.topics);
        stages.emplace_back(stage);
        continue;
      }
      if (info == nullptr || (info->key != "robot_id" && !by_robot)) {
        p.fail("topics: '" + topic + "' is not a per-robot topic (key robot_id or robot_id, target_id) of the catalog, "
               "nor a relative pose topic (key robot_id, peer_id; see docs/topics.md)");
      }
      // With relative topics, the truth of every robot (the peers' too): plant/state of all.
      const std::vector<std::uint64_t>& keys = topic == "plant/state" && relative ? all_robot_keys() : keys_;
      idl::dispatch_type(info->type_name, [&](auto tag) {
        using Msg = typename decltype(tag)::type;
        consumers.fixes |= std::is_same_v<Msg, idl::PositionMeasurement>;
        consumers.estimates |= std::is_same_v<Msg, idl::PoseEstimate>;
        consumers.status |= std::is_same_v<Msg, idl::ControllerStatus>;
        auto* input = &ctx.subscribe<Msg>(topic, by_robot ? Subscription::robot_streams(keys) : Subscription::instances(keys));
        recorders_.push_back(std::make_unique<Recorder<Msg>>(topic, input, keys, by_robot));
      });
    }
    const auto from_step = static_cast<std::uint64_t>(std::llround(params.metrics_after_s / ctx.step_s()));
    metrics_ = std::make_unique<Metrics>(from_step, consumers);
    std::map<std::uint32_t, double> wheel_base_m;
    for (const RobotSpec& robot : ctx.scenario().robots) {
      wheel_base_m[robot.id] = system::robot_body(ctx.scenario(), robot.id).wheel_base_m;
    }
    metrics_->set_motion(ctx.step_s(), std::move(wheel_base_m), model::RobotBody{}.wheel_base_m);
    if (!stages.empty()) {
      metrics_->enable_relative(params.metrics_after_s);
      for (const std::string& stage : stages) {
        metrics_->relative()->expect_stage(stage);
      }
    }
    configure_paper2(params.topics);
    metrics_after_s_ = params.metrics_after_s;
    for (const ComponentSpec& component : ctx.scenario().components) {
      standby_ |= !component.standby_for.empty() && consumers.estimates;
    }
    ctx.request_run_health();  // summary.json "hosts" and "inputs" (health_summary.hpp)
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
      metrics_->set_gaps_after_s(start_s_ + metrics_after_s_);
    }
    open_files();
    for (auto& recorder : recorders_) {
      recorder->collect(*metrics_);
    }
    metrics_->match();
    settle(false);
    steps_ = info.step + 1;
  }

  void on_finish(const StepInfo& info) override {
    on_step(info);
    settle(true);
    metrics_->finish();
    if (b_is_default_ && metrics_->circumnavigation() != nullptr) {  // once a run (configure may run twice)
      log::info(context_->name(), "range_accel_over_b_fraction: the scenario declares no facts.range_accel_bound_mps2, b = " +
                                      shortest_text(metrics_->circumnavigation()->b()) + " (its default)");
    }
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
    settle(true);
    for (const auto& recorder : recorders_) {
      recorder->flush();
    }
    metrics_->finish();
    write_summary(RunEnd{false, reason});
  }

 private:
  /// Creates the output folder and each recorder's file, once; not at configure: a run that never
  /// starts leaves no files.
  void open_files() {
    if (files_open_ || context_->output_dir().empty()) {
      return;
    }
    files_open_ = true;
    ::mkdir(context_->output_dir().c_str(), 0755);
    for (auto& recorder : recorders_) {
      recorder->open(context_->output_dir());
    }
  }

  /// Paper 3: records relative pose topic `topic` of stage `stage` (relative_recorder.hpp),
  /// subscribed for every pair (served robot i, other robot j of the scenario).
  void add_relative_topic(ComponentContext& ctx, const std::string& topic, const char* stage,
                          const std::vector<std::string>& topics) {
    if (all_robot_keys().size() < 2) {
      ctx.params().fail("topics: '" + topic + "' is a relative pose topic (key robot_id, peer_id), but scenario '" +
                        ctx.scenario().name + "' has a single robot: there is no peer to estimate");
    }
    if (std::find(topics.begin(), topics.end(), "plant/state") == topics.end()) {
      ctx.params().fail("topics: '" + topic + "' needs plant/state in topics too (the true poses its errors "
                        "are measured against)");
    }
    const std::vector<std::uint64_t> pairs = relative_pair_keys(keys_, robot_ids());
    auto* input = &ctx.subscribe<idl::RelativePoseEstimate>(topic, Subscription::instances(pairs));
    recorders_.push_back(std::make_unique<RelativeRecorder>(topic, stage, input, pairs, ctx.step_s()));
  }

  /// Every robot id of the scenario.
  std::vector<std::uint32_t> robot_ids() const {
    std::vector<std::uint32_t> ids;
    for (const RobotSpec& robot : context_->scenario().robots) {
      ids.push_back(robot.id);
    }
    return ids;
  }
  std::vector<std::uint64_t> all_robot_keys() const {
    const std::vector<std::uint32_t> ids = robot_ids();
    return std::vector<std::uint64_t>(ids.begin(), ids.end());
  }

  /// After the step's samples are taken: the relative recorders write what the truth now
  /// allows (`final`: everything), then the truth no one waits for is dropped.
  void settle(bool final) {
    std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
    for (auto& recorder : recorders_) {
      recorder->settle(*metrics_, final);
      needed = std::min(needed, recorder->truth_needed_from());
    }
    metrics_->relative_truth().drop_before(needed);
  }

  /// The paper-2 metrics, when plant/state and mission/target are recorded: b is the scenario's
  /// shared fact range_accel_bound_mps2 (the bound on |r''| the mission is designed for), else
  /// its default.
  void configure_paper2(const std::vector<std::string>& topics) {
    const auto recorded = [&topics](const char* topic) {
      return std::find(topics.begin(), topics.end(), topic) != topics.end();
    };
    if (!recorded("plant/state") || !recorded("mission/target")) {
      return;
    }
    const system::RangeAccelBound bound = system::range_accel_bound(context_->scenario());
    const double b = bound.mps2;
    b_is_default_ = !bound.declared;
    metrics_->enable_circumnavigation(context_->step_s(), b, recorded("observer/range_rate"),
                                      recorded("observer/range_rate_linear"));
  }

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
    write_standby_section(json);
    write_health_sections(json, context_->run_figures());
    json.end_object();
    const std::string error = replace_file(context_->output_dir() + "/summary.json", json.str());
    if (!error.empty()) {
      throw RunError("evaluator: " + error);
    }
  }

  /// "standby", only when the scenario has a hot standby (ComponentSpec::standby_for) and
  /// estimate/pose is recorded: per robot the longest gap between estimate/pose samples after
  /// metrics_after_s, the hand-over time (handover.hpp), and its ends in s since the run's start.
  void write_standby_section(JsonWriter& json) const {
    if (!standby_) {
      return;
    }
    const auto round6 = [](double s) { return std::round(s * 1e6) / 1e6; };
    json.begin_object("standby");
    json.value("topic", std::string("estimate/pose"));
    json.begin_object("robots");
    for (std::uint64_t key : keys_) {
      const RobotMetrics* r = metrics_->find(static_cast<std::uint32_t>(key));
      const Gap gap = r != nullptr ? r->estimate_gaps.longest() : Gap{};
      json.begin_object(std::to_string(key));
      json.value("handover_s", round6(gap.length_s));
      json.value("from_s", round6(gap.length_s > 0.0 ? gap.from_s - start_s_ : 0.0));
      json.value("to_s", round6(gap.length_s > 0.0 ? gap.to_s - start_s_ : 0.0));
      json.value("samples", static_cast<std::int64_t>(r != nullptr ? r->estimate_gaps.samples() : 0));
      json.end_object();
    }
    json.end_object();
    json.end_object();
  }

  /// "status": "completed"; "degraded" when the run reached its end but a host ran without some of
  /// its peers or did not report (the "reason" names each); "failed" with the error line that
  /// ended the run as "reason".
  void write_status_section(JsonWriter& json, const RunEnd& end) const {
    if (!end.completed) {
      json.value("status", "failed");
      json.value("reason", end.reason);
      return;
    }
    const std::string degraded = degraded_reason(context_->run_figures());
    json.value("status", degraded.empty() ? "completed" : "degraded");
    if (!degraded.empty()) {
      json.value("reason", degraded);
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
      if (r != nullptr) {
        write_motion_metrics(json, *r);
      }
      json.end_object();
    }
    json.end_object();
    if (keys_.size() == 1) {
      // One robot (the paper's setting): its way-point and motion figures at the top level too.
      const RobotMetrics* r = metrics_->find(static_cast<std::uint32_t>(keys_[0]));
      if (r != nullptr && r->waypoints.has_status()) {
        write_waypoint_metrics(json, *r);
      }
      if (r != nullptr) {
        write_motion_metrics(json, *r);
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
    write_paper2_metrics(json);
    write_relative_metrics(json);
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

  /// How the run went on the wall clock (kept apart from "metrics", which are deterministic),
  /// with the components' compute times per stage ("timing").
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
    if (context_->mode() == TimeMode::kLockstep) {
      json.value("lockstep_window", static_cast<std::int64_t>(context_->lockstep_window()));
    }
    json.value("wall_time_s", std::round(run.wall_time_s * 1e6) / 1e6);  // us, like the runner's log
    json.value("ticks", static_cast<std::int64_t>(run.ticks));
    json.value("ticks_per_s", std::round(ticks_per_s * 10.0) / 10.0);
    write_thirds(json, run);
    write_timing_section(json, run);  // the components' compute times (timing_summary.hpp)
    json.end_object();
  }

  /// Lockstep: "ticks_per_s_by_third": [first, middle, last third of the run's steps] on this
  /// host's wall clock from its first tick (start-up left out); a long run whose cost per step
  /// grows shows a falling list.
  void write_thirds(JsonWriter& json, const RunFigures& run) const {
    if (run.thirds_done_at_s.size() != 3 || run.ticks < 3) {
      return;
    }
    const double bounds[4] = {run.thirds_done_at_s[0], run.thirds_done_at_s[1], run.thirds_done_at_s[2], run.wall_time_s};
    const double third_steps[3] = {static_cast<double>(run.ticks / 3), static_cast<double>(run.ticks * 2 / 3 - run.ticks / 3),
                                   static_cast<double>(run.ticks - run.ticks * 2 / 3)};
    std::vector<double> rates;
    for (int i = 0; i < 3; ++i) {
      const double wall_s = bounds[i + 1] - bounds[i];
      rates.push_back(wall_s > 0 ? std::round(third_steps[i] / wall_s * 10.0) / 10.0 : 0.0);
    }
    json.value("ticks_per_s_by_third", rates);
  }

  /// Paper 2 (issue 10): "phase1", "phase2", ... {settle_time_s, radius_rmse_m, spacing_rmse_deg},
  /// "observer": {"sta": {...}, "linear": {...}} for each recorded observer topic, and
  /// range_accel_over_b_fraction. A figure without data is left out.
  void write_paper2_metrics(JsonWriter& json) const {
    const CircumnavigationMetrics* m = metrics_->circumnavigation();
    if (m == nullptr) {
      return;
    }
    const auto optional = [&json](const char* key, const std::optional<double>& v) {
      if (v) {
        json.value(key, *v);
      }
    };
    const CircumnavigationSummary s = m->summary();
    for (std::size_t i = 0; i < s.phases.size(); ++i) {
      const PhaseMetrics& phase = s.phases[i];
      json.begin_object("phase" + std::to_string(i + 1));
      json.value("start_s", phase.start_s);
      json.value("settle_time_s", phase.settle_time_s);
      optional("radius_rmse_m", phase.radius_rmse_m);
      optional("spacing_rmse_deg", phase.spacing_rmse_deg);
      json.end_object();
    }
    const bool any_observer = m->expects(ObserverKind::kSta) || m->expects(ObserverKind::kLinear);
    if (any_observer) {
      json.begin_object("observer");
    }
    for (std::size_t k = 0; k < kObserverKinds; ++k) {
      const auto kind = static_cast<ObserverKind>(k);
      if (!m->expects(kind)) {
        continue;
      }
      const ObserverMetrics& o = s.observers[k];
      json.begin_object(observer_kind_name(kind));
      optional("transient_rmse_mps", o.transient_rmse_mps);
      optional("steady_rmse_mps", o.steady_rmse_mps);
      if (kind == ObserverKind::kSta) {
        json.value("convergence_s", o.convergence_s);
      }
      optional("max_error_after_restart_mps", o.max_error_after_restart_mps);
      json.value("restarts", static_cast<std::int64_t>(o.restarts));
      json.value("matched_samples", static_cast<std::int64_t>(o.matched));
      json.end_object();
    }
    if (any_observer) {
      json.end_object();
    }
    optional("range_accel_over_b_fraction", s.range_accel_over_b_fraction);
    json.value("range_accel_b", m->b());
  }

  /// Paper 3 (issue 11): "stages": {"<stage>": {position_error_m_mean, position_error_m_std,
  /// heading_error_deg_mean, heading_error_deg_std, epochs, invalid_epochs}} for each recorded
  /// relative pose topic, pooled over its (robot, peer) pairs; means and stds only with epochs.
  void write_relative_metrics(JsonWriter& json) const {
    const RelativePoseMetrics* m = metrics_->relative();
    if (m == nullptr) {
      return;
    }
    json.begin_object("stages");
    for (const auto& [name, stage] : m->stages()) {
      json.begin_object(name);
      if (stage.epochs > 0) {
        json.value("position_error_m_mean", stage.position_error_m_mean);
        json.value("position_error_m_std", stage.position_error_m_std);
        json.value("heading_error_deg_mean", stage.heading_error_deg_mean);
        json.value("heading_error_deg_std", stage.heading_error_deg_std);
      }
      json.value("epochs", static_cast<std::int64_t>(stage.epochs));
      json.value("invalid_epochs", static_cast<std::int64_t>(stage.invalid_epochs));
      json.end_object();
    }
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
  }

  /// Issue 12: the extremes of what the plant applied (plant/state) and, apart, of what the
  /// controller commanded (plant/cmd), over the whole run; and when estimate/pose first said
  /// valid (-1: never). Each only when its topic is recorded.
  void write_motion_metrics(JsonWriter& json, const RobotMetrics& r) const {
    const auto extremes = [&json](const MotionExtremesTracker& t, const std::string& which) {
      if (!t.seen()) {
        return;
      }
      const MotionExtremes& e = t.extremes();
      json.value("max_abs_v_" + which + "_mps", e.max_abs_v_mps);
      json.value("max_abs_omega_" + which + "_radps", e.max_abs_omega_radps);
      json.value("max_abs_wheel_speed_" + which + "_mps", e.max_abs_wheel_speed_mps);
      json.value("max_abs_accel_" + which + "_mps2", e.max_abs_accel_mps2);
      json.value("max_abs_angular_accel_" + which + "_radps2", e.max_abs_angular_accel_radps2);
    };
    extremes(r.applied, "applied");
    extremes(r.commanded, "commanded");
    if (r.position.seen()) {
      json.value("time_to_valid_s", r.first_valid_step ? static_cast<double>(*r.first_valid_step) * context_->step_s() : -1.0);
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::unique_ptr<RecorderBase>> recorders_;
  std::unique_ptr<Metrics> metrics_;
  const ComponentContext* context_ = nullptr;  // owned by the host, which keeps it while it runs us
  std::uint64_t steps_ = 0;  // steps whose samples were taken (the last one + 1)
  bool files_open_ = false;
  bool started_ = false;         // the first step was seen (start_s_ is known)
  bool standby_ = false;         // the scenario has a hot standby: write "standby"
  double start_s_ = 0.0;         // the run's start as a stamp (s)
  double metrics_after_s_ = 0.0;
  bool b_is_default_ = false;    // paper 2: the scenario declares no range_accel_bound_mps2, b is its default
};

}  // namespace

std::unique_ptr<Component> make_evaluator_node() { return std::make_unique<EvaluatorNode>(); }

}  // namespace robodds::evaluator

ROBODDS_REGISTER_COMPONENT(evaluator, "records topics to CSV and writes summary.json",
                           robodds::evaluator::make_evaluator_node,
                           robodds::evaluator::evaluator_param_table);
