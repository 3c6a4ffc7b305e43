// Closed loop without DDS and without the observer: four unicycles around a fixed target, the law
// fed the TRUE range and range rate. Guards the law (radius) and its spacing term (gaps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "components/circumnavigation_controller/guidance_law.hpp"

namespace robodds::circumnavigation_controller {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kTargetX = 1000.0;
constexpr double kTargetY = 1000.0;
constexpr double kRadius = 200.0;
constexpr double kDt = 0.02;  // 50 Hz
constexpr double kRadiusTolerance = 5.0;
constexpr double kGapTolerance = 5.0 * kDeg;

/// Paper 2, Table 1: robots 1-4, headings in degrees counter-clockwise from +x.
std::vector<model::Pose2> table_one_poses() {
  return {{0.0, 1500.0, 20.0 * kDeg}, {-500.0, 500.0, 50.0 * kDeg}, {-500.0, -500.0, 100.0 * kDeg},
          {0.0, 0.0, 100.0 * kDeg}};
}

struct LoopResult {
  double settle_time_s = 0.0;         // from then on every radius within 5 m, every gap within 5 deg of 2 pi / n
  double final_max_radius_error_m = 0.0;
  double final_max_gap_error_deg = 0.0;
  double max_range_accel_mps2 = 0.0;  // |r''| over the run (truth, from the kinematics)
  double max_range_accel_time_s = 0.0;
  double fraction_over_b = 0.0;       // of robot-steps with |r''| > 2.2 m/s^2 (the observer's b)
};

LoopResult run_loop(const GuidanceParams& params, double duration_s, std::vector<model::Pose2> poses = table_one_poses()) {
  const std::size_t n = poses.size();
  std::vector<GuidanceLaw> laws(n, GuidanceLaw(params));
  std::vector<model::Twist> applied(n);  // the plant's twist: the previous step's command (rest at 0)
  const model::TwistLimits plant_limits{13.0, 0.15};
  LoopResult result;
  const long steps = std::lround(duration_s / kDt);
  for (long k = 0; k <= steps; ++k) {
    const double t = k * kDt;
    std::vector<TeamBearing> bearings;
    for (std::size_t i = 0; i < n; ++i) {
      bearings.push_back({static_cast<std::uint32_t>(i + 1),
                          bearing_from_target(poses[i].x, poses[i].y, kTargetX, kTargetY)});
    }
    bool in_band = true;
    double max_radius_error = 0.0;
    double max_gap_error = 0.0;
    std::vector<model::Twist> commands(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double ex = poses[i].x - kTargetX;
      const double ey = poses[i].y - kTargetY;
      const double range = std::hypot(ex, ey);
      const double hx = std::cos(poses[i].theta);
      const double hy = std::sin(poses[i].theta);
      const double v = applied[i].v;
      const double range_rate = v * (hx * ex + hy * ey) / range;
      const Gaps gaps = formation_gaps(bearings[i], bearings);
      max_radius_error = std::max(max_radius_error, std::abs(range - kRadius));
      max_gap_error = std::max(max_gap_error, std::abs(gaps.ahead_rad - 2.0 * kPi / static_cast<double>(n)));
      commands[i] = model::saturate(laws[i].step(range, range_rate, kRadius, gaps, kDt), plant_limits);
      // Range acceleration of a unicycle: (v^2 - rdot^2)/r + a_t (e.h) + v omega (e.n), n = h turned left.
      const double a_t = (commands[i].v - v) / kDt;
      const double accel = (v * v - range_rate * range_rate) / range + a_t * (hx * ex + hy * ey) / range +
                           commands[i].v * commands[i].omega * (-hy * ex + hx * ey) / range;
      if (std::abs(accel) > result.max_range_accel_mps2) {
        result.max_range_accel_mps2 = std::abs(accel);
        result.max_range_accel_time_s = t;
      }
      if (std::abs(accel) > 2.2) {
        result.fraction_over_b += 1.0;
      }
    }
    in_band = max_radius_error <= kRadiusTolerance && max_gap_error <= kGapTolerance;
    if (!in_band) {
      result.settle_time_s = t + kDt;
    }
    result.final_max_radius_error_m = max_radius_error;
    result.final_max_gap_error_deg = max_gap_error / kDeg;
    for (std::size_t i = 0; i < n; ++i) {
      poses[i] = model::integrate_exact(poses[i], commands[i], kDt);
      applied[i] = commands[i];
    }
  }
  result.fraction_over_b /= static_cast<double>(n * (steps + 1));
  return result;
}

TEST(CircumnavigationClosedLoop, TableOneStartSettlesOnTheOrbitWithEqualGapsWithin500s) {
  const LoopResult r = run_loop(GuidanceParams{}, 1000.0);
  std::printf("defaults: settle %.2f s, final max radius error %.4f m, max gap error %.4f deg, max |r''| %.3f m/s^2 at %.2f s, "
              "|r''| > 2.2 in %.5f of robot-steps\n",
              r.settle_time_s, r.final_max_radius_error_m, r.final_max_gap_error_deg, r.max_range_accel_mps2,
              r.max_range_accel_time_s, r.fraction_over_b);
  EXPECT_LE(r.settle_time_s, 500.0);
  EXPECT_LE(r.final_max_radius_error_m, kRadiusTolerance);
  EXPECT_LE(r.final_max_gap_error_deg, 5.0);
}

TEST(CircumnavigationClosedLoop, WithoutTheSpacingTermTheGapsStayUnequal) {
  GuidanceParams params;
  params.spacing_gain = 0.0;
  const LoopResult r = run_loop(params, 1000.0);
  std::printf("spacing_gain 0: settle %.2f s, final max radius error %.4f m, max gap error %.4f deg\n",
              r.settle_time_s, r.final_max_radius_error_m, r.final_max_gap_error_deg);
  EXPECT_LE(r.final_max_radius_error_m, kRadiusTolerance);  // the orbit still forms...
  EXPECT_GT(r.final_max_gap_error_deg, 5.0);                 // ...but the robots are not spread
}

// Beyond Table 1: a single robot from 4 ranges x 6 bearings x 8 headings, and seeded random
// four-robot starts, all reach the orbit (and the team its even spacing).
TEST(CircumnavigationClosedLoop, SingleRobotFromEveryStartReachesTheOrbit) {
  double worst_settle = 0.0;
  int count = 0;
  for (const double range : {20.0, 150.0, 600.0, 2000.0}) {
    for (int b = 0; b < 6; ++b) {
      for (int h = 0; h < 8; ++h) {
        const double bearing = b * kPi / 3.0;
        const model::Pose2 start{kTargetX + range * std::cos(bearing), kTargetY + range * std::sin(bearing), h * kPi / 4.0 - kPi};
        const LoopResult r = run_loop(GuidanceParams{}, 500.0, {start});
        worst_settle = std::max(worst_settle, r.settle_time_s);
        ++count;
        EXPECT_LE(r.settle_time_s, 400.0) << "range " << range << " bearing " << bearing << " heading " << start.theta;
      }
    }
  }
  std::printf("single robot, %d starts: worst settle %.2f s\n", count, worst_settle);
}

TEST(CircumnavigationClosedLoop, RandomFourRobotStartsSpreadEvenly) {
  std::uint64_t state = 12345;
  auto uniform = [&state] {  // a fixed LCG: the starts are the same on every machine
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  double worst_settle = 0.0;
  constexpr int kRuns = 16;
  for (int run = 0; run < kRuns; ++run) {
    std::vector<model::Pose2> poses;
    for (int i = 0; i < 4; ++i) {
      poses.push_back({-1000.0 + 4000.0 * uniform(), -1000.0 + 4000.0 * uniform(), -kPi + 2.0 * kPi * uniform()});
    }
    const LoopResult r = run_loop(GuidanceParams{}, 1000.0, poses);
    worst_settle = std::max(worst_settle, r.settle_time_s);
    EXPECT_LE(r.settle_time_s, 800.0) << "run " << run;
  }
  std::printf("four robots, %d random starts: worst settle %.2f s\n", kRuns, worst_settle);
}

}  // namespace
}  // namespace robodds::circumnavigation_controller
