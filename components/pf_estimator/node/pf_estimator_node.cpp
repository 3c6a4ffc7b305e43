// Adapter: Odometry/PositionMeasurement -> ParticleFilter -> PoseEstimate.
#include "components/pf_estimator/node/pf_estimator_node.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "components/pf_estimator/node/pf_estimator_params.hpp"
#include "components/pf_estimator/particle_filter.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"

namespace robodds::pf_estimator {
namespace {

class PfEstimatorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const PfEstimatorNodeParams node_params = read_params(p, pf_estimator_param_table());
    PfParams params = node_params.filter;
    if (node_params.valid_max_heading_std_rad == 0.0) {
      // Validity by the position alone: the heading is not judged, also not against the fixes' track.
      params.track_check_window_fixes = 0;
    }
    const double rate_hz = node_params.rate_hz;
    p.validate(node_params);
    const ValidityLimits limits{node_params.valid_max_position_std_m, node_params.valid_max_heading_std_rad,
                                node_params.valid_keep_max_heading_std_rad};
    ctx.set_rate_hz(rate_hz, "rate_hz");
    input_timeout_s_ = node_params.input_timeout_s;
    ctx.require_longer_than_period("input_timeout_s", input_timeout_s_);
    // Each sensor must deliver within the timeout (issue 27: a 1 Hz fix against 0.5 s was accepted).
    ctx.limits_age_of("sensor/odometry", "input_timeout_s", input_timeout_s_, /*realtime_only=*/true);
    ctx.limits_age_of("sensor/position", "input_timeout_s", input_timeout_s_, /*realtime_only=*/true);
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    extrapolate_ = node_params.extrapolate_to_step;
    for (const RobotSpec& robot : ctx.robots()) {
      filters_.emplace(robot.id, std::make_unique<ParticleFilter>(params, ctx.seed_for("robot" + std::to_string(robot.id))));
      validity_.emplace(robot.id, ValidityTracker(limits));
    }
    const auto keys = ctx.robot_keys();
    odometry_ = &ctx.subscribe<idl::Odometry>("sensor/odometry", Subscription::instances(keys));
    fixes_ = &ctx.subscribe<idl::PositionMeasurement>("sensor/position", Subscription::instances(keys));
    out_ = &ctx.advertise<idl::PoseEstimate>("estimate/pose");
    compute_times_ = &ctx.compute_times();
  }

  void on_step(const StepInfo& info) override {
    ScopedComputeTimer timer(*compute_times_, "pf");  // summary.json run.timing.pf: every filter's step
    for (auto& [id, filter] : filters_) {
      const std::vector<idl::Odometry> odometry = odometry_->take_new(id);
      const std::vector<idl::PositionMeasurement> fixes = fixes_->take_new(id);
      // Merge by step: odometry of step s covers the motion up to s, so it goes before a fix of s.
      std::size_t next_odometry = 0;
      for (const idl::PositionMeasurement& fix : fixes) {
        for (; next_odometry < odometry.size() && odometry[next_odometry].header().step() <= fix.header().step(); ++next_odometry) {
          predict(*filter, odometry[next_odometry]);
        }
        if (!filter->initialized()) {
          if (filter->params().init_mode == InitMode::kFirstFix) {
            filter->initialize_around(fix.x(), fix.y());
            continue;  // the first fix seeds the cloud; it is not also used as an update
          }
          filter->initialize_uniform();
        }
        filter->update(fix.x(), fix.y());
      }
      for (; next_odometry < odometry.size(); ++next_odometry) {
        predict(*filter, odometry[next_odometry]);
      }
      if (!odometry.empty()) {
        last_odometry_[id] = odometry.back();
      }
      // The cloud only changes with new odometry or fixes: its estimate is reused otherwise (it costs a
      // pass with sin/cos over M particles), moved on to this step along the last odometry's arc.
      if (!odometry.empty() || !fixes.empty() || estimates_.count(id) == 0) {
        estimates_[id] = filter_estimate(*filter, validity_.at(id));
      }
      published_[id] = to_message(id, estimates_.at(id), age_of_odometry(id, info));
      if (realtime_ && !inputs_fresh(id)) {
        // Safe behaviour: a filter without fresh sensors says so, and its consumers stop.
        idl::PoseEstimate stale = published_[id];
        stale.valid(false);
        stale.inputs_stale(true);  // not the filter's doubt: no gap for a controller to ride through (issue 27)
        out_->publish(stale);
      } else {
        out_->publish(published_[id]);
      }
    }
  }

 private:
  /// Real time: both sensors delivered within input_timeout_s, by this process's receive time.
  bool inputs_fresh(std::uint32_t id) const {
    return odometry_->fresh(id, input_timeout_s_) && fixes_->fresh(id, input_timeout_s_);
  }

  /// Seconds from the last odometry sample to this step (issue 27: the estimate's age), at most one
  /// sample interval (the next sample is due then); 0 without odometry or with extrapolation off.
  double age_of_odometry(std::uint32_t id, const StepInfo& info) const {
    const auto last = last_odometry_.find(id);
    if (!extrapolate_ || last == last_odometry_.end()) {
      return 0.0;
    }
    const double age_s = 1e-9 * static_cast<double>(info.stamp_ns - last->second.header().stamp_ns());
    return std::clamp(age_s, 0.0, std::max(0.0, last->second.dt_s()));
  }

  static void predict(ParticleFilter& filter, const idl::Odometry& odometry) {
    if (filter.initialized() && odometry.dt_s() > 0.0) {
      filter.predict(odometry.v(), odometry.omega(), odometry.dt_s(), odometry.var_omega());
    }
  }

  /// The filter's estimate and its validity now. `validity`: the filter's own judgement (not the
  /// real-time staleness override: stale inputs say nothing about what the cloud knows).
  struct Judged {
    bool initialized = false;
    PoseEstimate estimate;
    bool valid = false;
    std::size_t restarts = 0;
    double fix_noise_std_m = 0.0;  // m, per axis: what the filter gates and weighs the fixes with
  };
  static Judged filter_estimate(const ParticleFilter& filter, ValidityTracker& validity) {
    Judged j;
    if (filter.initialized()) {
      j.initialized = true;
      j.estimate = filter.estimate();
      // The spread alone is no proof (a heading given as known has none): the measurements must
      // have confirmed the belief first (issue 27).
      j.valid = validity.next(j.estimate, filter.confirmed(), filter.recovery_count());
      j.restarts = filter.recovery_count();
      j.fix_noise_std_m = filter.measurement_std_estimate_m();
    }
    return j;
  }

  idl::PoseEstimate to_message(std::uint32_t id, const Judged& judged, double age_s) const {
    idl::PoseEstimate m;
    m.robot_id(id);
    if (judged.initialized) {
      PoseEstimate e = judged.estimate;
      const auto last = last_odometry_.find(id);
      if (age_s > 0.0 && last != last_odometry_.end()) {
        e = extrapolate_estimate(e, last->second.v(), last->second.omega(), last->second.var_omega(), age_s);
      }
      m.x(e.mean.x());
      m.y(e.mean.y());
      m.theta(e.mean.z());
      for (int i = 0; i < 9; ++i) {
        m.cov()[static_cast<std::size_t>(i)] = e.covariance(i / 3, i % 3);
      }
      m.valid(judged.valid);
      m.restarts(static_cast<std::uint32_t>(judged.restarts));  // a consumer sees each redraw, even one it missed
      m.fix_noise_std_m(judged.fix_noise_std_m);
    }
    return m;
  }

  std::map<std::uint32_t, std::unique_ptr<ParticleFilter>> filters_;
  std::map<std::uint32_t, idl::PoseEstimate> published_;  // last estimate per robot
  std::map<std::uint32_t, Judged> estimates_;             // the filter's last estimate per robot
  std::map<std::uint32_t, idl::Odometry> last_odometry_;  // per robot
  bool extrapolate_ = true;
  std::map<std::uint32_t, ValidityTracker> validity_;  // per robot
  double input_timeout_s_ = 0.5;
  bool realtime_ = false;
  Input<idl::Odometry>* odometry_ = nullptr;
  Input<idl::PositionMeasurement>* fixes_ = nullptr;
  Output<idl::PoseEstimate>* out_ = nullptr;
  ComputeTimes* compute_times_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_pf_estimator_node() { return std::make_unique<PfEstimatorNode>(); }

}  // namespace robodds::pf_estimator

ROBODDS_REGISTER_COMPONENT(pf_estimator, "paper 1 particle filter, full pose: sensor/odometry + sensor/position -> estimate/pose",
                           robodds::pf_estimator::make_pf_estimator_node,
                           robodds::pf_estimator::pf_estimator_param_table);
