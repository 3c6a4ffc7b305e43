#include "sim/evaluator/metrics/circumnavigation/circumnavigation_metrics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace robodds::evaluator {
namespace {

constexpr double kStep = 0.5;  // s: coarse, so that runs of several hundred seconds stay short
constexpr double kPiT = 3.14159265358979323846;
constexpr double kDeg = kPiT / 180.0;

std::uint64_t step_at(double t) { return static_cast<std::uint64_t>(std::llround(t / kStep)); }

TargetAssignmentInfo target(std::uint32_t id, double x, double y, double radius) { return {true, id, x, y, radius}; }
const TargetAssignmentInfo kTarget1 = target(1, 1000.0, 1000.0, 200.0);
const TargetAssignmentInfo kTarget2 = target(2, 2000.0, 2000.0, 100.0);

/// A robot on a counter-clockwise orbit `off` m outside the circle of `a`, at angle `angle0 +
/// V t / R`, moving along it (rdot = 0, r'' = 0 on the circle).
PlantSample orbit(std::uint64_t step, const TargetAssignmentInfo& a, double angle0, double off = 0.0, double v = 10.0) {
  const double t = static_cast<double>(step) * kStep;
  const double w = v / a.desired_radius;
  const double angle = angle0 + w * t;
  const double r = a.desired_radius + off;
  return {step, a.target_x + r * std::cos(angle), a.target_y + r * std::sin(angle), angle + kPiT / 2.0, v, w};
}

/// What one step of a run delivers.
struct StepData {
  std::map<std::uint32_t, TargetAssignmentInfo> assignments;  // published at this step
  std::map<std::uint32_t, PlantSample> truth;
  std::map<std::uint32_t, RateEstimateSample> sta;
  std::map<std::uint32_t, RateEstimateSample> linear;
};
using RunFn = std::function<StepData(std::uint64_t step)>;

/// Feeds steps 0..last as the evaluator would in lockstep (each step's samples together, in
/// robot order; the estimates `lag` steps after their truth), update() after each step;
/// `reversed`: truth in reverse robot order, update() after each sample.
CircumnavigationSummary run(const RunFn& fn, std::uint64_t last, double b = 2.2, std::uint64_t lag = 0,
                            bool reversed = false, std::size_t* kept = nullptr) {
  CircumnavigationMetrics m(kStep, b);
  m.expect_observer(ObserverKind::kSta);
  m.expect_observer(ObserverKind::kLinear);
  std::map<std::uint64_t, StepData> later;  // estimates still on their way
  for (std::uint64_t k = 0; k <= last + lag; ++k) {
    if (k <= last) {
      StepData d = fn(k);
      for (const auto& [id, a] : d.assignments) {
        m.add_assignment(id, k, a);
      }
      if (reversed) {
        for (auto it = d.truth.rbegin(); it != d.truth.rend(); ++it) {
          m.add_truth(it->first, it->second);
          m.update();
        }
      } else {
        for (const auto& [id, s] : d.truth) {
          m.add_truth(id, s);
        }
      }
      later[k + lag] = d;
    }
    const StepData& due = later[k];
    for (const auto& [id, e] : due.sta) {
      m.add_estimate(ObserverKind::kSta, id, e);
    }
    for (const auto& [id, e] : due.linear) {
      m.add_estimate(ObserverKind::kLinear, id, e);
    }
    later.erase(k);
    m.update();
    if (kept != nullptr) {
      *kept = std::max(*kept, m.kept_truth());
    }
  }
  m.finish();
  return m.summary();
}

/// Four robots evenly around target 1 from step 0; `off(robot, t)` m outside the circle and
/// `shift(robot, t)` rad ahead of the even place.
RunFn formation(std::function<double(std::uint32_t, double)> off, std::function<double(std::uint32_t, double)> shift) {
  return [off, shift](std::uint64_t k) {
    StepData d;
    const double t = static_cast<double>(k) * kStep;
    for (std::uint32_t id = 1; id <= 4; ++id) {
      if (k == 0) {
        d.assignments[id] = kTarget1;
      }
      d.truth[id] = orbit(k, kTarget1, (id - 1) * kPiT / 2.0 + shift(id, t), off(id, t));
    }
    return d;
  };
}
double none(std::uint32_t, double) { return 0.0; }

TEST(RangeDerivatives, FromThePlantState) {
  // On the circle, moving along it with omega = V / R: the range neither changes nor bends.
  const RangeDerivatives on = range_derivatives(200.0, 0.0, kPiT / 2.0, 10.0, 10.0 / 200.0, 0.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(on.r, 200.0);
  EXPECT_NEAR(on.rdot, 0.0, 1e-12);
  EXPECT_NEAR(on.rddot, 0.0, 1e-12);
  // Straight on along the tangent: r'' = V^2 / R.
  EXPECT_NEAR(range_derivatives(200.0, 0.0, kPiT / 2.0, 10.0, 0.0, 0.0, 0.0, 0.0).rddot, 0.5, 1e-12);
  // Heading 60 deg off the line of sight outward: rdot = V cos 60 deg; speeding up along it adds v_dot cos 60 deg.
  const RangeDerivatives d = range_derivatives(100.0, 0.0, 60.0 * kDeg, 4.0, 0.0, 2.0, 0.0, 0.0);
  EXPECT_NEAR(d.rdot, 2.0, 1e-12);
  EXPECT_NEAR(d.rddot, (16.0 - 4.0) / 100.0 + 1.0, 1e-12);
}

TEST(CircumnavigationMetrics, APerfectOrbitSettlesAtOnceWithNoError) {
  const CircumnavigationSummary s = run(formation(none, none), step_at(600.0));
  ASSERT_EQ(s.phases.size(), 1u);
  EXPECT_EQ(s.phases[0].start_s, 0.0);
  EXPECT_EQ(s.phases[0].settle_time_s, 0.0);
  ASSERT_TRUE(s.phases[0].radius_rmse_m.has_value());
  ASSERT_TRUE(s.phases[0].spacing_rmse_deg.has_value());
  EXPECT_NEAR(*s.phases[0].radius_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(*s.phases[0].spacing_rmse_deg, 0.0, 1e-9);
  EXPECT_EQ(*s.range_accel_over_b_fraction, 0.0);
  EXPECT_EQ(s.range_accel_samples, 4 * step_at(600.0)) << "every sample but each robot's first";
  EXPECT_FALSE(s.observers[0].transient_rmse_mps.has_value()) << "no estimates";
}

TEST(CircumnavigationMetrics, ARobotOffTheCircleUntil300sSettlesThen) {
  const auto off_until_300 = [](double metres) {
    return [metres](std::uint32_t id, double t) { return id == 2 && t < 300.0 ? metres : 0.0; };
  };
  const double settle = run(formation(off_until_300(10.0), none), step_at(600.0)).phases[0].settle_time_s;
  EXPECT_NEAR(settle, 300.0, kStep);
  // The radius tolerance is 5 m: 5.1 m off is out, 4.9 m in.
  EXPECT_NEAR(run(formation(off_until_300(5.1), none), step_at(600.0)).phases[0].settle_time_s, 300.0, kStep);
  EXPECT_EQ(run(formation(off_until_300(4.9), none), step_at(600.0)).phases[0].settle_time_s, 0.0);
  // Off at the end: never settled.
  const auto off_from_500 = [](std::uint32_t id, double t) { return id == 2 && t >= 500.0 ? 10.0 : 0.0; };
  EXPECT_EQ(run(formation(off_from_500, none), step_at(600.0)).phases[0].settle_time_s, -1.0);
}

TEST(CircumnavigationMetrics, RadiusRmseIsOverTheLast200sOfThePhase) {
  // Robot 1 is 3 m out up to 400 s, 1 m out after: the last 200 s (400, 600] see 1 m for one robot of four.
  const auto off = [](std::uint32_t id, double t) { return id == 1 ? (t <= 400.0 ? 3.0 : 1.0) : 0.0; };
  const CircumnavigationSummary s = run(formation(off, none), step_at(600.0));
  EXPECT_NEAR(*s.phases[0].radius_rmse_m, 0.5, 1e-9);
  EXPECT_EQ(s.phases[0].settle_time_s, 0.0) << "3 m is within the tolerance";
}

TEST(CircumnavigationMetrics, AGapErrorCountsInSpacingAndSettling) {
  // Robot 2 6 deg ahead: its gaps are 96 and 84 deg instead of 90 (+6, -6; two gaps of four exact).
  const auto ahead = [](double deg) { return [deg](std::uint32_t id, double) { return id == 2 ? deg * kDeg : 0.0; }; };
  const CircumnavigationSummary six = run(formation(none, ahead(6.0)), step_at(600.0));
  EXPECT_EQ(six.phases[0].settle_time_s, -1.0) << "6 deg is out of the 5 deg tolerance";
  EXPECT_FALSE(six.phases[0].spacing_rmse_deg.has_value()) << "not settled: no tail figure (issue 27)";
  EXPECT_EQ(six.phases[0].not_settled.rfind("never settled", 0), 0u) << six.phases[0].not_settled;
  const CircumnavigationSummary four = run(formation(none, ahead(4.0)), step_at(600.0));
  EXPECT_TRUE(four.phases[0].not_settled.empty()) << four.phases[0].not_settled;
  EXPECT_NEAR(*four.phases[0].spacing_rmse_deg, std::sqrt(8.0), 1e-9);
  EXPECT_EQ(four.phases[0].settle_time_s, 0.0);
  EXPECT_NEAR(*four.phases[0].radius_rmse_m, 0.0, 1e-9);
  const auto ahead_until_100 = [](std::uint32_t id, double t) { return id == 2 && t < 100.0 ? 6.0 * kDeg : 0.0; };
  EXPECT_NEAR(run(formation(none, ahead_until_100), step_at(600.0)).phases[0].settle_time_s, 100.0, kStep);
}

TEST(CircumnavigationMetrics, APhaseThatNeverSettledHasNoTailFiguresButSaysWhy) {
  // Issue 27: a phase cut short (the switch at 600 s) while robot 2 is still 10 m out: its last
  // 200 s are the approach. Was: radius RMSE 5 m reported as if it were the settled error.
  const auto off_until_700 = [](std::uint32_t id, double t) { return id == 2 && t < 700.0 ? 10.0 : 0.0; };
  const PhaseMetrics p = run(formation(off_until_700, none), step_at(600.0)).phases[0];
  EXPECT_TRUE(p.evaluated);
  EXPECT_EQ(p.settle_time_s, -1.0);
  EXPECT_FALSE(p.radius_rmse_m.has_value());
  EXPECT_FALSE(p.spacing_rmse_deg.has_value());
  EXPECT_EQ(p.not_settled, "never settled (radius within 5 m and every gap within 5 deg did not hold to the phase's end)");
}

TEST(CircumnavigationMetrics, APhaseSettledLessThanTheTailWindowBeforeItsEndHasNoTailFigures) {
  // Settled at 450 s, the phase ends at 600 s: the last 200 s (400, 600] include 50 s of approach.
  const auto off_until = [](double until) {
    return [until](std::uint32_t id, double t) { return id == 2 && t < until ? 10.0 : 0.0; };
  };
  const PhaseMetrics late = run(formation(off_until(450.0), none), step_at(600.0)).phases[0];
  EXPECT_NEAR(late.settle_time_s, 450.0, kStep) << "it did settle";
  EXPECT_FALSE(late.radius_rmse_m.has_value());
  EXPECT_EQ(late.not_settled, "settled only 150.5 s before the phase's end: its last 200 s include the approach");
  // Settled at 400 s: the window (400, 600] is all settled: the tail figures are given.
  const PhaseMetrics in_time = run(formation(off_until(400.5), none), step_at(600.0)).phases[0];
  EXPECT_TRUE(in_time.not_settled.empty()) << in_time.not_settled;
  ASSERT_TRUE(in_time.radius_rmse_m.has_value());
  EXPECT_NEAR(*in_time.radius_rmse_m, 0.0, 1e-9);
  // A phase shorter than the window that settled at its start: the whole phase is its tail.
  const PhaseMetrics short_phase = run(formation(none, none), step_at(150.0)).phases[0];
  EXPECT_TRUE(short_phase.not_settled.empty()) << short_phase.not_settled;
  EXPECT_TRUE(short_phase.radius_rmse_m.has_value());
}

TEST(CircumnavigationMetrics, PhasesFollowAssignmentChangesAndOnlyActiveRobotsCount) {
  // 0-300 s: four robots on target 1. From 300 s robots 1-3 on target 2 (120 deg apart, 10 m out until
  // 350 s), robot 4 leaves and wanders far off. At 100 s the mission republishes unchanged assignments.
  const RunFn fn = [](std::uint64_t k) {
    StepData d;
    const double t = static_cast<double>(k) * kStep;
    for (std::uint32_t id = 1; id <= 4; ++id) {
      if (k == 0 || k == step_at(100.0)) {
        d.assignments[id] = kTarget1;
      }
      if (k == step_at(300.0)) {
        d.assignments[id] = id <= 3 ? kTarget2 : TargetAssignmentInfo{};
      }
      if (t < 300.0) {
        d.truth[id] = orbit(k, kTarget1, (id - 1) * kPiT / 2.0);
      } else if (id <= 3) {
        d.truth[id] = orbit(k, kTarget2, (id - 1) * 2.0 * kPiT / 3.0, t < 350.0 ? 10.0 : 0.0);
      } else {
        d.truth[id] = {k, 5000.0 + t, -3000.0, 0.0, 1.0, 0.0};
      }
    }
    return d;
  };
  const CircumnavigationSummary s = run(fn, step_at(600.0));
  ASSERT_EQ(s.phases.size(), 2u) << "the republished assignments at 100 s change nothing";
  EXPECT_EQ(s.phases[0].settle_time_s, 0.0);
  EXPECT_EQ(s.phases[1].start_s, 300.0);
  EXPECT_NEAR(s.phases[1].settle_time_s, 50.0, kStep) << "counted from the phase's start";
  EXPECT_NEAR(*s.phases[0].radius_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(*s.phases[1].radius_rmse_m, 0.0, 1e-9) << "robot 4 left: it counts nowhere";
  EXPECT_NEAR(*s.phases[1].spacing_rmse_deg, 0.0, 1e-9) << "three gaps of 120 deg";
  EXPECT_EQ(*s.range_accel_over_b_fraction, 0.0) << "the jump to target 2 is a new target, not an acceleration";
}

/// One robot on a straight line past target 1 (so that the truth range rate changes), its estimates
/// `err(t)` m/s off the truth rate; valid unless `invalid(t)`, restarted when `restart(t)`.
struct Line {
  std::function<double(double)> err;
  std::function<bool(double)> invalid = [](double) { return false; };
  std::function<bool(double)> restart = [](double t) { return t == 0.0; };  // a first sample's flag is no restart
  std::function<double(double)> std_mps = [](double) { return 0.0; };        // the reported rate std
};
double true_rate(const PlantSample& s) {
  const double dx = s.x - kTarget1.target_x;
  const double dy = s.y - kTarget1.target_y;
  return s.v * (dx * std::cos(s.theta) + dy * std::sin(s.theta)) / std::hypot(dx, dy);
}
RunFn line(const Line& sta, const Line& linear) {
  return [sta, linear](std::uint64_t k) {
    StepData d;
    const double t = static_cast<double>(k) * kStep;
    if (k == 0) {
      d.assignments[1] = kTarget1;
    }
    const PlantSample s{k, 300.0 + 8.0 * t * std::cos(0.3), 600.0 + 8.0 * t * std::sin(0.3), 0.3, 8.0, 0.0};
    d.truth[1] = s;
    d.sta[1] = {k, 1, true_rate(s) + sta.err(t), !sta.invalid(t), sta.restart(t), sta.std_mps(t)};
    d.linear[1] = {k, 1, true_rate(s) + linear.err(t), !linear.invalid(t), linear.restart(t), linear.std_mps(t)};
    return d;
  };
}

TEST(CircumnavigationMetrics, ObserverErrorsAgainstTheTruthRate) {
  // 1 m/s off before 5 s (outside the transient window), 0.5 from 5 to 200 s (inside), 0.15 after.
  Line sta{[](double t) { return t < 5.0 ? 1.0 : (t <= 200.0 ? 0.5 : 0.15); }};
  Line linear{[](double t) { return t < 300.0 ? 2.0 : -0.75; }};
  const CircumnavigationSummary s = run(line(sta, linear), step_at(600.0), 2.2, 2);
  const ObserverMetrics& o = s.observers[static_cast<std::size_t>(ObserverKind::kSta)];
  EXPECT_NEAR(*o.transient_rmse_mps, 0.5, 1e-9);
  EXPECT_NEAR(*o.steady_rmse_mps, 0.15, 1e-9) << "the last 200 s: (400, 600]";
  EXPECT_NEAR(o.convergence_s, 200.0 + kStep, 1e-9) << "within 0.2 m/s from 200.5 s on, for more than 200 s";
  EXPECT_EQ(o.restarts, 0u);
  EXPECT_FALSE(o.max_error_after_restart_mps.has_value());
  EXPECT_EQ(o.matched, step_at(600.0) + 1);
  const ObserverMetrics& l = s.observers[static_cast<std::size_t>(ObserverKind::kLinear)];
  EXPECT_NEAR(*l.transient_rmse_mps, 2.0, 1e-9);
  EXPECT_NEAR(*l.steady_rmse_mps, 0.75, 1e-9);
  EXPECT_EQ(l.convergence_s, -1.0) << "never within 0.2 m/s";
  // Convergence needs 200 s: a run of 600 s that gets within 0.2 m/s at 450 s has not converged.
  Line late{[](double t) { return t < 450.0 ? 1.0 : 0.0; }};
  EXPECT_EQ(run(line(late, late), step_at(600.0)).observers[0].convergence_s, -1.0);
}

TEST(CircumnavigationMetrics, ConvergenceExcusesExcursionsOnlyWhereTheTruthBrokeTheBound) {
  // Issue 27, finding 6: from unseen start formations the convergence (0.2 m/s held for 200 s)
  // read 96 s where the observer had converged in 2.5 s: the robot later turned at its top rate
  // 390 m from the target (|r''| 2.38 m/s^2 > b 2.2), outside the paper's assumption, and the
  // error left the band for 4 s. The line's truth has |r''| <= 64 / r m/s^2 (> 0): b = 1e-6 puts
  // every step beyond the bound, b = 2.2 none. 2 m/s off for 3 s (the start's transient), exact,
  // then 0.5 m/s off at 100-102 s.
  Line sta{[](double t) { return t < 3.0 ? 2.0 : (t >= 100.0 && t < 102.0 ? 0.5 : 0.0); }};
  const ObserverMetrics within_b = run(line(sta, sta), step_at(600.0), 2.2).observers[0];
  EXPECT_NEAR(within_b.convergence_s, 102.0, 1e-9) << "the excursion breaks the hold where the bound held";
  EXPECT_EQ(within_b.convergence_excused, 0u);
  const ObserverMetrics beyond_b = run(line(sta, sta), step_at(600.0), 1e-6).observers[0];
  EXPECT_NEAR(beyond_b.convergence_s, 3.0, 1e-9) << "excused; the start's transient is not";
  EXPECT_EQ(beyond_b.convergence_excused, step_at(2.0));
  // An excursion 4 s after the error got within the band (before kConvergenceConfirmS) is not
  // excused: the observer had not shown it converged.
  Line early{[](double t) { return t < 3.0 ? 2.0 : (t >= 7.0 && t < 8.0 ? 0.5 : 0.0); }};
  EXPECT_NEAR(run(line(early, early), step_at(600.0), 1e-6).observers[0].convergence_s, 8.0, 1e-9);
}

TEST(CircumnavigationMetrics, ObserverConsistencyJudgesTheErrorAgainstTheReportedStd) {
  // 0.3 m/s off throughout, reported at 0.2 m/s (inside 3 stds) but at 0.05 m/s from 100 s to 110 s
  // (outside: over-confident for 10 s), invalid from 200 s to 205 s (not judged).
  Line sta{[](double) { return 0.3; }, [](double t) { return t >= 200.0 && t < 205.0; }, [](double t) { return t == 0.0; },
           [](double t) { return t >= 100.0 && t < 110.0 ? 0.05 : 0.2; }};
  // 1 m/s off for 50 s, then exact, reported at 0.01 m/s: over-confident while off.
  Line linear{[](double t) { return t < 50.0 ? 1.0 : 0.0; }, [](double) { return false; }, [](double t) { return t == 0.0; },
              [](double) { return 0.01; }};
  const CircumnavigationSummary s = run(line(sta, linear), step_at(300.0), 2.2, 2);
  const ConsistencyStats& c = s.observers[static_cast<std::size_t>(ObserverKind::kSta)].consistency;
  EXPECT_EQ(c.samples, step_at(300.0) + 1);
  EXPECT_EQ(c.valid_samples, c.samples - step_at(5.0));
  EXPECT_EQ(c.overconfident, step_at(10.0));
  EXPECT_NEAR(c.overconfident_fraction, static_cast<double>(step_at(10.0)) / static_cast<double>(c.valid_samples), 1e-12);
  EXPECT_NEAR(c.longest_overconfident_s, 10.0, 1e-9);
  EXPECT_NEAR(c.worst_position_error_valid_m, 0.3, 1e-9) << "the worst |rate error| while valid (m/s)";
  const ConsistencyStats& l = s.observers[static_cast<std::size_t>(ObserverKind::kLinear)].consistency;
  EXPECT_EQ(l.overconfident, step_at(50.0));
}

TEST(CircumnavigationMetrics, ARestartOpensItsWindows) {
  // A restart at 300 s: two invalid samples 50 m/s off (not counted), then from 301 s 2 m/s off for 5 s,
  // 1.5 at 310.5 s (within 10 s of the first valid sample) and 3 at 312 s (after).
  Line sta{[](double t) {
             if (t >= 300.0 && t < 301.0) return 50.0;
             if (t >= 301.0 && t < 306.0) return 2.0;
             if (t == 310.5) return 1.5;
             if (t == 312.0) return 3.0;
             return 0.0;
           },
           [](double t) { return t >= 300.0 && t < 301.0; }, [](double t) { return t == 0.0 || t == 300.0; }};
  const CircumnavigationSummary s = run(line(sta, sta), step_at(600.0), 2.2, 3);
  const ObserverMetrics& o = s.observers[0];
  EXPECT_EQ(o.restarts, 1u) << "the first sample's flag is no restart";
  ASSERT_TRUE(o.max_error_after_restart_mps.has_value());
  EXPECT_DOUBLE_EQ(*o.max_error_after_restart_mps, 2.0);
  // Transient: 5-200 s after the start at 0 (all exact) and after the restart at 300 s: from 305 s,
  // 2 m/s at 305, 305.5; 1.5 at 310.5; 3 at 312; zeros up to 500 s.
  const double n = static_cast<double>(step_at(200.0) - step_at(5.0) + 1) * 2.0;
  EXPECT_NEAR(*o.transient_rmse_mps, std::sqrt((2 * 4.0 + 2.25 + 9.0) / n), 1e-9);
  EXPECT_EQ(o.convergence_s, 0.0);
}

TEST(CircumnavigationMetrics, ATargetChangeIsAStartForTheTransient) {
  // The estimates switch to target 2's stream at 300 s: 1 m/s off 5-200 s after the first sample,
  // 2 m/s off 5-200 s after the switch, exact otherwise.
  const RunFn fn = [](std::uint64_t k) {
    StepData d;
    const double t = static_cast<double>(k) * kStep;
    if (k == 0) {
      d.assignments[1] = kTarget1;
    } else if (k == step_at(300.0)) {
      d.assignments[1] = kTarget2;
    }
    const TargetAssignmentInfo& a = t < 300.0 ? kTarget1 : kTarget2;
    d.truth[1] = orbit(k, a, 0.0, 20.0);  // rdot = 0, off the circle (no matter here)
    const double since = t < 300.0 ? t : t - 300.0;
    d.sta[1] = {k, a.target_id, since >= 5.0 && since <= 200.0 ? (t < 300.0 ? 1.0 : 2.0) : 0.0, true, false};
    return d;
  };
  const ObserverMetrics o = run(fn, step_at(600.0)).observers[0];
  EXPECT_NEAR(*o.transient_rmse_mps, std::sqrt(2.5), 1e-9) << "equal numbers of samples after each start";
  EXPECT_EQ(o.restarts, 0u) << "a target change is a start, not a restart sample";
}

TEST(CircumnavigationMetrics, RangeAccelerationOverB) {
  // Heading straight out from target 1, speeding up by 2 m/s over one 0.5 s step at 100 s: r'' = 4 m/s^2 once.
  const RunFn fn = [](std::uint64_t k) {
    StepData d;
    const double t = static_cast<double>(k) * kStep;
    if (k == 0) {
      d.assignments[1] = kTarget1;
    }
    d.truth[1] = {k, 1100.0 + t, 1000.0, 0.0, t < 100.0 ? 1.0 : 3.0, 0.0};
    return d;
  };
  const CircumnavigationSummary s = run(fn, step_at(200.0), 2.2);
  EXPECT_NEAR(*s.range_accel_over_b_fraction, 1.0 / static_cast<double>(step_at(200.0)), 1e-12);
  EXPECT_EQ(*run(fn, step_at(200.0), 4.5).range_accel_over_b_fraction, 0.0) << "b above 4 m/s^2";
}

TEST(CircumnavigationMetrics, ArrivalOrderAcrossTopicsDoesNotMatter) {
  Line sta{[](double t) { return std::sin(t); }, [](double t) { return std::fmod(t, 7.0) == 0.0; },
           [](double t) { return t == 250.0; }};
  Line linear{[](double t) { return 0.3 + 0.01 * t; }};
  const RunFn one = line(sta, linear);
  const RunFn fn = [one](std::uint64_t k) {  // plus a formation of three others
    StepData d = one(k);
    for (std::uint32_t id = 2; id <= 4; ++id) {
      if (k == 0) {
        d.assignments[id] = kTarget1;
      }
      d.truth[id] = orbit(k, kTarget1, id * 1.3, id == 3 ? 2.0 : 0.0);
    }
    return d;
  };
  const CircumnavigationSummary a = run(fn, step_at(500.0));
  const CircumnavigationSummary b = run(fn, step_at(500.0), 2.2, 7, true);
  ASSERT_EQ(a.phases.size(), b.phases.size());
  EXPECT_EQ(a.phases[0].settle_time_s, b.phases[0].settle_time_s);
  // Robot 1 on its line never settles: no tail figures, the same reason (issue 27).
  EXPECT_FALSE(a.phases[0].radius_rmse_m.has_value());
  EXPECT_TRUE(a.phases[0].radius_rmse_m == b.phases[0].radius_rmse_m);
  EXPECT_TRUE(a.phases[0].spacing_rmse_deg == b.phases[0].spacing_rmse_deg);
  EXPECT_EQ(a.phases[0].not_settled, b.phases[0].not_settled);
  for (std::size_t k = 0; k < 2; ++k) {  // the two observers line() feeds (sta, linear)
    EXPECT_EQ(a.observers[k].matched, step_at(500.0) + 1 - (k == 0 ? 72u : 0u)) << "invalid every 7 s";
    EXPECT_EQ(a.observers[k].matched, b.observers[k].matched);
    EXPECT_EQ(*a.observers[k].transient_rmse_mps, *b.observers[k].transient_rmse_mps);
    EXPECT_EQ(*a.observers[k].steady_rmse_mps, *b.observers[k].steady_rmse_mps);
    EXPECT_EQ(a.observers[k].convergence_s, b.observers[k].convergence_s);
    EXPECT_EQ(a.observers[k].restarts, b.observers[k].restarts);
  }
}

TEST(CircumnavigationMetrics, KeepsOnlyTheTruthThatLateEstimatesNeed) {
  Line zero{[](double) { return 0.0; }};
  std::size_t kept = 0;
  run(line(zero, zero), step_at(3000.0), 2.2, 5, false, &kept);
  EXPECT_LE(kept, 6u) << "the estimates lag 5 steps: truth of steps k-5..k at most";
  EXPECT_GE(kept, 6u);
  CircumnavigationMetrics m(kStep, 2.2);  // no observer expected: nothing kept once evaluated
  m.add_assignment(1, 0, kTarget1);
  for (std::uint64_t k = 0; k < 100; ++k) {
    m.add_truth(1, orbit(k, kTarget1, 0.0));
    m.update();
  }
  EXPECT_LE(m.kept_truth(), 1u) << "the newest waits for the next step";
}

TEST(TailSum, KeepsTheWindowOfTheNewestStep) {
  TailSum tail(10);
  for (std::uint64_t k = 0; k < 100; ++k) {
    if (k != 95) {
      tail.add(k, k < 90 ? 5.0 : 1.0);
    }
  }
  EXPECT_EQ(tail.size(), 9u);
  const SquareSum s = tail.over_window_ending(99);
  EXPECT_EQ(s.count, 9u);
  EXPECT_DOUBLE_EQ(*s.rms(), 1.0);
  tail.add(50, 100.0);  // older than the window: dropped
  EXPECT_EQ(tail.over_window_ending(99).count, 9u);
  tail.add(95, 3.0);  // late but within the window: counts, at its step
  tail.add(95, 3.0);
  EXPECT_EQ(tail.over_window_ending(99).count, 11u);
  EXPECT_DOUBLE_EQ(tail.over_window_ending(99).sum_squares, 9.0 + 18.0);
  EXPECT_EQ(tail.over_window_ending(94).count, 5u) << "steps 90..94 and nothing of 95";
  EXPECT_EQ(tail.over_window_ending(95).count, 7u) << "steps 90..94 and both of 95 (not of 96)";
}

}  // namespace
}  // namespace robodds::evaluator
