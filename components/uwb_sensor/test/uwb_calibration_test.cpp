// Calibration of the UWB error model against paper 3's UWB-only row (Table 1): the estimator's
// single-epoch solver (eq. 1, plain least squares as the paper) on experiment 1-a's geometry with
// ranges from this model. Robot 2 stands at (0, 0) facing +y; robot 1 drives the rectangle with
// corners (+-3.5, +-3) counter-clockwise from (-3.5, -3) at 0.2 m/s, turning in place at 0.5 rad/s;
// 10 Hz epochs over 430 s (3 laps); errors of robot 1's pose in robot 2's frame from t >= 20 s.
// Paper (side 0.3 / 0.5 / 0.7 m): 0.48 / 0.39 / 0.37 m, 7.57 / 5.27 / 5.05 deg.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"
#include "common/model/uwb_array.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"

namespace robodds::uwb_sensor {
namespace {

constexpr double kSpeed = 0.2;      // m/s
constexpr double kTurnRate = 0.5;   // rad/s
constexpr double kHalfX = 3.5;      // m
constexpr double kHalfY = 3.0;      // m

/// Robot 1's true pose at time t (world frame): the rectangle, counter-clockwise from (-3.5, -3)
/// facing +x; each leg then a quarter turn in place.
model::Pose2 robot1_at(double t) {
  const double legs[4] = {2.0 * kHalfX, 2.0 * kHalfY, 2.0 * kHalfX, 2.0 * kHalfY};
  const double turn_s = (kPi / 2.0) / kTurnRate;
  double lap_s = 4.0 * turn_s;
  for (double leg : legs) {
    lap_s += leg / kSpeed;
  }
  double s = std::fmod(t, lap_s);
  model::Pose2 pose{-kHalfX, -kHalfY, 0.0};
  for (double leg : legs) {
    const double drive_s = leg / kSpeed;
    const double d = std::min(s, drive_s) * kSpeed;
    pose.x += d * std::cos(pose.theta);
    pose.y += d * std::sin(pose.theta);
    s -= std::min(s, drive_s);
    const double turn = std::min(s, turn_s);
    pose.theta = wrap_angle(pose.theta + turn * kTurnRate);
    s -= turn;
    if (s <= 0.0) {
      break;
    }
  }
  return pose;
}

struct Errors {
  double position_m = 0.0;   // mean
  double heading_deg = 0.0;  // mean
  double position_std_m = 0.0;
  double heading_std_deg = 0.0;
};

/// One 430 s run of experiment 1-a: robot 2 measures robot 1 at 10 Hz, solves eq. (1) with plain
/// least squares, warm-started from its previous epoch (cold start, 32 starts, at the first epoch
/// and every 10 s, the lower cost wins).
Errors run_experiment_1a(double side_m, std::uint64_t seed, const UwbErrorParams& params = UwbErrorParams{}) {
  const model::UwbArray array = model::square_array(side_m);
  const model::Pose2 robot2{0.0, 0.0, kPi / 2.0};
  // Robot 1 is a, robot 2 is b of the pair; robot 2 measures: from b.
  PairErrors shared(4, 4, 0.0, params, RandomEngine(seed * 1000 + 1), RandomEngine(seed * 1000 + 2));
  RandomEngine white(seed * 1000 + 3);
  RandomEngine nlos(seed * 1000 + 4);
  uwb_relative_estimator::SolverOptions options;
  options.loss = uwb_relative_estimator::RobustLoss::kNone;
  std::optional<model::Pose2> previous;
  std::vector<double> pos;
  std::vector<double> head;
  for (int epoch = 0; epoch <= 4300; ++epoch) {
    const double t = 0.1 * epoch;
    const model::Pose2 robot1 = robot1_at(t);
    shared.advance_to(t);
    const Eigen::MatrixXd ranges = measure_ranges(model::array_ranges(array, robot2, array, robot1), shared.link_bias_m(false),
                                                  shared.common_m(), params, white, nlos);
    uwb_relative_estimator::SolverResult best = uwb_relative_estimator::solve_relative_pose(array, array, ranges, previous, options);
    if (previous && epoch % 100 == 0) {
      const uwb_relative_estimator::SolverResult cold = uwb_relative_estimator::solve_relative_pose(array, array, ranges, std::nullopt, options);
      if (cold.final_cost < best.final_cost) {
        best = cold;
      }
    }
    previous = best.pose;
    if (t >= 20.0) {
      const model::Pose2 truth = model::between(robot2, robot1);
      pos.push_back(std::hypot(best.pose.x - truth.x, best.pose.y - truth.y));
      head.push_back(std::abs(wrap_angle(best.pose.theta - truth.theta)) * 180.0 / kPi);
    }
  }
  auto mean_std = [](const std::vector<double>& x, double& mean, double& std) {
    double s = 0.0;
    for (double v : x) {
      s += v;
    }
    mean = s / static_cast<double>(x.size());
    double q = 0.0;
    for (double v : x) {
      q += (v - mean) * (v - mean);
    }
    std = std::sqrt(q / static_cast<double>(x.size() - 1));
  };
  Errors e;
  mean_std(pos, e.position_m, e.position_std_m);
  mean_std(head, e.heading_deg, e.heading_std_deg);
  return e;
}

/// The mean over seeds 1..4, printed.
Errors mean_over_seeds(double side_m, const UwbErrorParams& params = UwbErrorParams{}) {
  constexpr int kSeeds = 4;
  Errors m;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Errors e = run_experiment_1a(side_m, static_cast<std::uint64_t>(seed), params);
    std::printf("side %.1f m seed %d: position %.3f +- %.3f m, heading %.2f +- %.2f deg\n", side_m, seed, e.position_m,
                e.position_std_m, e.heading_deg, e.heading_std_deg);
    m.position_m += e.position_m / kSeeds;
    m.heading_deg += e.heading_deg / kSeeds;
    m.position_std_m += e.position_std_m / kSeeds;
    m.heading_std_deg += e.heading_std_deg / kSeeds;
  }
  std::printf("side %.1f m, mean of %d seeds: position %.3f +- %.3f m, heading %.2f +- %.2f deg\n", side_m, kSeeds,
              m.position_m, m.position_std_m, m.heading_deg, m.heading_std_deg);
  return m;
}

TEST(Experiment1aTrajectory, IsTheRectangleAtItsSpeeds) {
  EXPECT_NEAR(robot1_at(0.0).x, -3.5, 1e-12);
  EXPECT_NEAR(robot1_at(35.0).x, 3.5, 1e-12) << "7 m at 0.2 m/s";
  EXPECT_NEAR(robot1_at(35.0 + kPi).theta, kPi / 2.0, 1e-12) << "a quarter turn at 0.5 rad/s";
  EXPECT_NEAR(robot1_at(35.0 + kPi + 30.0).y, 3.0, 1e-12);
  const double lap = 130.0 + 4.0 * kPi;
  EXPECT_NEAR(robot1_at(lap + 1.0).x, robot1_at(1.0).x, 1e-9);
  EXPECT_GT(430.0 / lap, 3.0) << "430 s: 3 laps";
}

// The defaults reproduce the paper's UWB-only row at side 0.5 m within 15 %: 0.39 m / 5.27 deg.
TEST(UwbCalibration, DefaultsReproduceThePapersUwbOnlyRowAtSide05) {
  const Errors e = mean_over_seeds(0.5);
  EXPECT_NEAR(e.position_m, 0.39, 0.39 * 0.15);
  EXPECT_NEAR(e.heading_deg, 5.27, 5.27 * 0.15);
}

// The error falls with the array side (paper 0.48 / 0.39 / 0.37 m; issue's prototype 0.53 / 0.39 / 0.34).
TEST(UwbCalibration, ErrorFallsWithTheArraySide) {
  const Errors small = mean_over_seeds(0.3);
  const Errors large = mean_over_seeds(0.7);
  const Errors middle = mean_over_seeds(0.5);
  EXPECT_GT(small.position_m, middle.position_m);
  EXPECT_GT(middle.position_m, large.position_m);
  EXPECT_GT(small.heading_deg, middle.heading_deg);
  EXPECT_GT(middle.heading_deg, large.heading_deg);
}

}  // namespace
}  // namespace robodds::uwb_sensor
