#include "components/range_rate_observer/node/range_rate_observer_node.hpp"

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <stdexcept>

#include "common/number_text.hpp"

#include "components/range_rate_observer/node/range_rate_observer_params.hpp"
#include "components/range_rate_observer/range_rate_observer.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::range_rate_observer {
namespace {

/// m/s: the start's rate std when the robot's body sets no top speed (uncertainty.initial_rate_std_mps
/// 0): nothing bounds the rate then; 5 m/s covers 15 m/s at 3 stds, beyond the papers' robots.
constexpr double kUnlimitedSpeedInitialRateStdMps = 5.0;

/// One robot's observers on its range stream: paper 2's two and the Kalman filter (issue 28).
struct RobotObservers {
  RobotObservers(const ObserverNodeParams& p, const RateUncertaintyParams& u, double period_s)
      : sta(p.sta, u, period_s), linear(p.linear, u, period_s), kalman(p.kalman, u, period_s) {}
  SuperTwistingObserver sta;
  LinearRangeRateObserver linear;
  KalmanRangeRateObserver kalman;
  std::uint32_t target_id = 0;
  bool ended = false;  // its range stream ended (the robot left): final estimates are out
};

class RangeRateObserverNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, observer_node_param_table());
    p.validate(params_);
    // The gain b must cover the range accelerations the mission allows (the scenario's shared
    // fact): below them the estimate is no longer exact (paper 2, b > 3/4 mu1).
    const system::RangeAccelBound bound = system::range_accel_bound(ctx.scenario());
    if (params_.sta.b < bound.mps2) {
      p.fail("sta.b: " + shortest_text(params_.sta.b) + " m/s^2 is below the range acceleration bound " +
             shortest_text(bound.mps2) + " m/s^2 of " + bound.key +
             ": the observer would not follow the accelerations the guidance allows (raise sta.b or declare the bound)");
    }
    // A restart's rate is a window line's slope, the rate at the window's centre: off by up to
    // the largest range acceleration times half the window (the reported std says so).
    params_.uncertainty.range_accel_mps2 = bound.mps2;
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    // rate_hz is the range sensor's rate: a slower sensor would leave steps without a range, whose
    // estimate is the last one published again as if new (issue 27: 10 Hz ranges into a 50 Hz
    // observer were accepted silently). Checked against the scenario's range sensor before the run.
    ctx.expects_rate_of("sensor/range", "rate_hz", InputRateAssumption::Kind::kSameRate);
    // A restart window's least-squares slope needs several ranges: one shorter than two sample
    // periods closes at its second sample, and the rate restarts from one difference of two noisy
    // ranges (the old rule: up to 90 m/s off at 0.5 m of noise, README.md "Restart window").
    const double period_s = static_cast<double>(ctx.period_steps()) * ctx.step_s();
    for (const auto& [key, window_s] : {std::pair<std::string, double>{"sta.restart_window_s", params_.sta.restart_window_s},
                                        {"linear.restart_window_s", params_.linear.restart_window_s},
                                        {"kalman.restart_window_s", params_.kalman.restart_window_s}}) {
      if (window_s < 2.0 * period_s - 1e-9) {
        p.fail(key + ": " + shortest_text(window_s) + " s spans fewer than two periods of the range samples (" +
               shortest_text(period_s) + " s at rate_hz " + shortest_text(params_.rate_hz) +
               "): the restarted rate would rest on one difference of two noisy ranges; make it at least " +
               shortest_text(2.0 * period_s) + " s");
      }
    }
    name_ = ctx.name();
    for (const RobotSpec& robot : ctx.robots()) {
      // The sensor's period: a longer step between two ranges spans lost ones (dropouts), which
      // the observers integrate across period by period (range_rate_observer.hpp, issue 27
      // finding 6).
      robots_.emplace(robot.id, RobotObservers(params_, uncertainty_of(ctx, robot.id), period_s));
    }
    ranges_ = &ctx.subscribe<idl::RangeMeasurement>("sensor/range", Subscription::robot_streams(ctx.robot_keys()));
    sta_out_ = &ctx.advertise<idl::RangeRateEstimate>("observer/range_rate");
    linear_out_ = &ctx.advertise<idl::RangeRateEstimate>("observer/range_rate_linear");
    kalman_out_ = &ctx.advertise<idl::RangeRateEstimate>("observer/range_rate_kf");
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, robot] : robots_) {
      if (robot.ended) {
        continue;
      }
      const std::size_t sta_restarts = robot.sta.restarts();
      const std::size_t linear_restarts = robot.linear.restarts();
      const std::size_t kalman_restarts = robot.kalman.restarts();
      bool final_sample = false;
      bool fresh = false;  // a range came this step
      for (const idl::RangeMeasurement& m : ranges_->take_new_of_robot(id)) {
        if (robot.sta.started() && m.target_id() != robot.target_id) {
          robot.sta.restart();  // a new target: its range has nothing to do with the old one's
          robot.linear.restart();
          robot.kalman.restart();
        }
        robot.target_id = m.target_id();
        feed(id, robot, static_cast<double>(m.header().stamp_ns()) * 1e-9, m.range());
        final_sample |= m.header().next_step() == kNeverAgain;
        fresh = true;
      }
      if (!robot.sta.started()) {
        continue;  // real time before the first range
      }
      // Without a new sample (a lost one) every due step still carries an estimate, as its
      // next_step promised: each observer's own prediction to this step, its std widened for the
      // hold (RangeRateObserver::predict; issue 27, finding 6), not the last one again.
      const double now_s = static_cast<double>(info.stamp_ns) * 1e-9;
      publish(*sta_out_, id, robot, robot.sta, fresh, now_s, robot.sta.restarts() != sta_restarts, final_sample);
      publish(*linear_out_, id, robot, robot.linear, fresh, now_s, robot.linear.restarts() != linear_restarts,
              final_sample);
      publish(*kalman_out_, id, robot, robot.kalman, fresh, now_s, robot.kalman.restarts() != kalman_restarts,
              final_sample);
      robot.ended = final_sample;
    }
  }

 private:
  /// Every observer takes the sample, or none: the library refuses a time that does not
  /// advance (e.g. a duplicated sample) and leaves its state unchanged; the sample is dropped.
  void feed(std::uint32_t id, RobotObservers& robot, double time_s, double range_m) {
    try {
      robot.sta.update(time_s, range_m);
      robot.linear.update(time_s, range_m);
      robot.kalman.update(time_s, range_m);
    } catch (const std::invalid_argument& e) {
      if (!warned_) {
        log::warn(name_, "robot " + std::to_string(id) + ": range sample dropped: " + e.what() + " (logged once)");
        warned_ = true;
      }
    }
  }

  /// fresh: a range came this step (the observer's estimate at it); else its prediction to now_s.
  template <class Observer>
  void publish(Output<idl::RangeRateEstimate>& out, std::uint32_t id, const RobotObservers& robot, const Observer& observer,
               bool fresh, double now_s, bool restarted, bool final_sample) {
    const RangeRateEstimate estimate = fresh ? observer.estimate() : observer.predict(now_s);
    idl::RangeRateEstimate e;
    e.robot_id(id);
    e.target_id(robot.target_id);
    e.range(estimate.range_m);
    e.range_rate(estimate.rate_mps);
    e.valid(estimate.valid);
    e.restarted(restarted);
    e.range_noise_std_m(observer.noise_sigma_m());
    e.range_rate_std_mps(estimate.rate_std_mps);
    if (final_sample) {
      out.publish_final(e);
    } else {
      out.publish(e);
    }
  }

  /// The noise each robot's observers estimated (issue 27: estimated, not assumed): one line per
  /// robot at the end of the run, beside the restarts the evaluator counts.
  void on_finish(const StepInfo&) override {
    for (const auto& [id, robot] : robots_) {
      if (!robot.sta.started()) {
        continue;
      }
      const double sigma_m = std::round(robot.sta.noise_sigma_m() * 1e3) / 1e3;
      const double threshold_m = std::round(robot.sta.restart_threshold_m() * 1e2) / 1e2;
      log::info(name_, "robot " + std::to_string(id) + ": range noise estimated sigma " + shortest_text(sigma_m) +
                           " m (floor " + shortest_text(params_.sta.noise_floor_m) + " m), restart threshold " +
                           shortest_text(threshold_m) + " m, " + std::to_string(robot.sta.restarts()) +
                           " restarts (super-twisting)");
    }
  }

  /// The robot's uncertainty parameters: initial_rate_std_mps 0 becomes its top speed / 3, or
  /// kUnlimitedSpeedInitialRateStdMps for a body without a top speed.
  RateUncertaintyParams uncertainty_of(const ComponentContext& ctx, std::uint32_t robot) const {
    RateUncertaintyParams u = params_.uncertainty;
    if (u.initial_rate_std_mps == 0.0) {
      const double top_mps = system::robot_body(ctx.scenario(), robot).limits.max_speed_mps;
      u.initial_rate_std_mps = top_mps > 0.0 ? top_mps / 3.0 : kUnlimitedSpeedInitialRateStdMps;
    }
    return u;
  }

  ObserverNodeParams params_;
  std::string name_;
  bool warned_ = false;
  std::map<std::uint32_t, RobotObservers> robots_;
  Input<idl::RangeMeasurement>* ranges_ = nullptr;
  Output<idl::RangeRateEstimate>* sta_out_ = nullptr;
  Output<idl::RangeRateEstimate>* linear_out_ = nullptr;
  Output<idl::RangeRateEstimate>* kalman_out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_range_rate_observer_node() { return std::make_unique<RangeRateObserverNode>(); }

}  // namespace robodds::range_rate_observer

ROBODDS_REGISTER_COMPONENT(range_rate_observer,
                           "range-rate observers (super-twisting, linear, Kalman): sensor/range -> observer/range_rate(_linear, _kf)",
                           robodds::range_rate_observer::make_range_rate_observer_node,
                           robodds::range_rate_observer::observer_node_param_table);
