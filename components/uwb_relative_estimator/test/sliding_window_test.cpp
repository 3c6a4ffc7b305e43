#include "components/uwb_relative_estimator/sliding_window.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/angle.hpp"
#include "common/random.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

/// Three robots on circles of different radius, speed and centre (world frame), one epoch per 0.1 s.
model::Pose2 truth_of(std::size_t robot, int epoch) {
  const double t = 0.1 * epoch;
  const double radius[3] = {2.0, 3.0, 1.5};
  const double omega[3] = {0.2, -0.15, 0.3};
  const double cx[3] = {0.0, 4.0, -2.0};
  const double cy[3] = {0.0, 1.0, 3.0};
  const double phase = omega[robot] * t;
  const double heading = phase + (omega[robot] > 0 ? kPi / 2.0 : -kPi / 2.0);
  return {cx[robot] + radius[robot] * std::cos(phase), cy[robot] + radius[robot] * std::sin(phase), wrap_angle(heading)};
}

struct Errors {
  double raw_m = 0.0;        // RMSE of the single-epoch UWB relative positions
  double window_m = 0.0;     // RMSE of the window's latest relative positions
  double raw_deg = 0.0;
  double window_deg = 0.0;
};

Errors run(double uwb_xy_noise_m, double uwb_theta_noise_rad, double odometry_noise_m, int epochs, std::size_t window) {
  SlidingWindowGraph graph(3, window, WindowWeights{});
  RandomEngine engine(derive_seed(11, "sliding_window"));
  double raw_sq = 0.0, win_sq = 0.0, raw_h = 0.0, win_h = 0.0;
  int counted = 0;
  for (int e = 0; e < epochs; ++e) {
    std::vector<model::Pose2> odometry(3);
    for (std::size_t i = 0; i < 3; ++i) {
      odometry[i] = e == 0 ? model::Pose2{} : model::between(truth_of(i, e - 1), truth_of(i, e));
      odometry[i].x += odometry_noise_m * standard_normal(engine);
      odometry[i].y += odometry_noise_m * standard_normal(engine);
    }
    std::vector<PairMeasurement> uwb;
    for (std::size_t own = 0; own < 3; ++own) {
      for (std::size_t other = own + 1; other < 3; ++other) {
        model::Pose2 m = model::between(truth_of(own, e), truth_of(other, e));
        m.x += uwb_xy_noise_m * standard_normal(engine);
        m.y += uwb_xy_noise_m * standard_normal(engine);
        m.theta = wrap_angle(m.theta + uwb_theta_noise_rad * standard_normal(engine));
        uwb.push_back({own, other, m});
      }
    }
    graph.add_epoch(odometry, uwb);
    graph.optimize();
    if (e >= static_cast<int>(window)) {
      for (const PairMeasurement& m : uwb) {
        const model::Pose2 truth = model::between(truth_of(m.own, e), truth_of(m.other, e));
        const model::Pose2 est = graph.latest_relative(m.own, m.other);
        raw_sq += std::pow(std::hypot(m.pose.x - truth.x, m.pose.y - truth.y), 2);
        win_sq += std::pow(std::hypot(est.x - truth.x, est.y - truth.y), 2);
        raw_h += std::pow(wrap_angle(m.pose.theta - truth.theta), 2);
        win_h += std::pow(wrap_angle(est.theta - truth.theta), 2);
        ++counted;
      }
    }
  }
  return {std::sqrt(raw_sq / counted), std::sqrt(win_sq / counted), std::sqrt(raw_h / counted) * 180.0 / kPi,
          std::sqrt(win_h / counted) * 180.0 / kPi};
}

TEST(SlidingWindowGraph, NoiseFreeMeasurementsGiveTheTruth) {
  const Errors e = run(0.0, 0.0, 0.0, 40, 10);
  EXPECT_LT(e.window_m, 1e-6);
  EXPECT_LT(e.window_deg, 1e-5);
}

TEST(SlidingWindowGraph, AFarOffGuessConvergesToTheTruth) {
  // Robot 2 is not measured for its first 5 epochs: its poses are the placeholder (2, 0, 0) moved by
  // dead reckoning, metres and radians off. The solver's first step is nearly Gauss-Newton's
  // (initial trust region 1e6, issue 29): from so far off it must still find the truth, with noise-free
  // measurements exactly, and say it converged.
  SlidingWindowGraph graph(3, 10, WindowWeights{});
  for (int e = 0; e < 20; ++e) {
    std::vector<model::Pose2> odometry(3);
    for (std::size_t i = 0; i < 3; ++i) {
      odometry[i] = e == 0 ? model::Pose2{} : model::between(truth_of(i, e - 1), truth_of(i, e));
    }
    std::vector<PairMeasurement> uwb{{0, 1, model::between(truth_of(0, e), truth_of(1, e))}};
    if (e >= 5) {
      uwb.push_back({0, 2, model::between(truth_of(0, e), truth_of(2, e))});
      uwb.push_back({1, 2, model::between(truth_of(1, e), truth_of(2, e))});
    }
    graph.add_epoch(odometry, uwb);
    const bool converged = graph.optimize();
    if (e >= 5) {
      EXPECT_TRUE(converged) << "epoch " << e;
      const model::Pose2 truth = model::between(truth_of(0, e), truth_of(2, e));
      const model::Pose2 est = graph.latest_relative(0, 2);
      EXPECT_LT(std::hypot(est.x - truth.x, est.y - truth.y), 1e-6) << "epoch " << e;
      EXPECT_LT(std::abs(wrap_angle(est.theta - truth.theta)), 1e-6) << "epoch " << e;
    }
  }
}

TEST(SlidingWindowGraph, OdometryConstraintsSmoothTheUwbRelativePoses) {
  // Paper 3 section 2.2: the window (w = 30) with odometry edges beats the single epochs.
  const Errors e = run(0.3, 0.1, 0.005, 120, 30);
  std::printf("UWB 0.3 m / 5.7 deg per epoch, odometry 5 mm per epoch, window 30: raw %.3f m / %.2f deg, window %.3f m / %.2f deg\n",
              e.raw_m, e.raw_deg, e.window_m, e.window_deg);
  EXPECT_LT(e.window_m, 0.5 * e.raw_m);
  EXPECT_LT(e.window_deg, 0.5 * e.raw_deg);
}

TEST(SlidingWindowGraph, BadInputIsRejectedAndChangesNothing) {
  EXPECT_THROW(SlidingWindowGraph(1, 30, WindowWeights{}), std::invalid_argument);
  try {
    SlidingWindowGraph(3, 1, WindowWeights{});
    FAIL() << "accepted a window of 1 epoch";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "window: must be >= 2 epochs (got 1)");
  }
  WindowWeights bad;
  bad.uwb_xy_std_m = 0.0;
  EXPECT_THROW(SlidingWindowGraph(3, 30, bad), std::invalid_argument);

  SlidingWindowGraph graph(3, 5, WindowWeights{});
  const std::vector<model::Pose2> still(3);
  graph.add_epoch(still, {{0, 1, model::Pose2{2.0, 0.0, 0.0}}});
  EXPECT_THROW(graph.add_epoch(std::vector<model::Pose2>(2), {}), std::invalid_argument);
  EXPECT_THROW(graph.add_epoch(still, {{1, 1, model::Pose2{}}}), std::invalid_argument);
  EXPECT_THROW(graph.add_epoch(still, {{0, 3, model::Pose2{}}}), std::invalid_argument);
  EXPECT_THROW(graph.add_epoch(still, {{0, 1, model::Pose2{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}}}),
               std::invalid_argument);
  try {
    graph.add_epoch({model::Pose2{}, model::Pose2{0.0, std::numeric_limits<double>::quiet_NaN(), 0.0}, model::Pose2{}}, {});
    FAIL() << "accepted NaN odometry";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "add_epoch: odometry of robot 1 is not finite (got x=0, y=nan, theta=0)");
  }
  EXPECT_EQ(graph.epochs(), 1u);
  EXPECT_THROW(graph.latest_relative(0, 3), std::invalid_argument);
  EXPECT_THROW(SlidingWindowGraph(3, 5, WindowWeights{}).latest_relative(0, 1), std::invalid_argument);
  const model::Pose2 r = graph.latest_relative(0, 1);
  EXPECT_DOUBLE_EQ(r.x, 2.0);
  for (int e = 0; e < 10; ++e) {
    graph.add_epoch(still, {});
  }
  EXPECT_EQ(graph.epochs(), 5u);  // the window keeps the newest 5
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
