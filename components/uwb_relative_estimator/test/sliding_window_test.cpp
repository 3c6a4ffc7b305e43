#include "components/uwb_relative_estimator/sliding_window.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <deque>

#include <ceres/ceres.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/angle.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/window_edge.hpp"

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

TEST(SlidingWindowGraph, ItsBlockEliminationTakesTheStepsCeresTakes) {
  // optimize() solves eq. (2) by its own Levenberg-Marquardt with a block-tridiagonal elimination
  // (issue 29; before, a ceres::Problem). The oracle: the graph as it was, i.e. the same warm start
  // (the previous solution, the new epoch by dead reckoning) and the same edges solved by Ceres with
  // the options optimize() had (sparse normal Cholesky, initial trust region 1e6, default
  // tolerances), and, to check where both stop, the same solved to tight tolerances. Five robots,
  // every pair measured with noise, robot 4 only from epoch 8 (its poses a guess until then: the
  // system is singular in them but for the damping), window 12.
  constexpr std::size_t kRobots = 5;
  constexpr std::size_t kWindow = 12;
  const auto truth = [](std::size_t i, int e) {
    const double radius = 2.0 + static_cast<double>(i);
    const double omega = (i % 2 == 0 ? 0.2 : -0.15) / (1.0 + 0.3 * static_cast<double>(i));
    const double phase = omega * 0.1 * e + static_cast<double>(i);
    return model::Pose2{radius * std::cos(phase), radius * std::sin(phase),
                        wrap_angle(phase + (omega > 0 ? kPi / 2.0 : -kPi / 2.0))};
  };
  const WindowWeights weights;
  SlidingWindowGraph graph(kRobots, kWindow, weights);
  RandomEngine engine(derive_seed(12, "sliding_window_oracle"));
  std::deque<std::vector<model::Pose2>> odometry_of;
  std::deque<std::vector<PairMeasurement>> uwb_of;
  std::deque<std::array<double, 3 * kRobots>> oracle;  // the oracle's poses per epoch
  double largest_m = 0.0;
  double largest_rad = 0.0;
  double largest_tight_m = 0.0;
  for (int e = 0; e < 40; ++e) {
    std::vector<model::Pose2> odometry(kRobots);
    for (std::size_t i = 0; i < kRobots; ++i) {
      odometry[i] = e == 0 ? model::Pose2{} : model::between(truth(i, e - 1), truth(i, e));
      odometry[i].x += 0.02 * standard_normal(engine);
      odometry[i].y += 0.02 * standard_normal(engine);
      odometry[i].theta += 0.01 * standard_normal(engine);
    }
    std::vector<PairMeasurement> uwb;
    for (std::size_t a = 0; a < kRobots; ++a) {
      for (std::size_t b = a + 1; b < kRobots; ++b) {
        if (b == kRobots - 1 && e < 8) {
          continue;
        }
        model::Pose2 m = model::between(truth(a, e), truth(b, e));
        m.x += 0.3 * standard_normal(engine);
        m.y += 0.3 * standard_normal(engine);
        m.theta = wrap_angle(m.theta + 0.1 * standard_normal(engine));
        uwb.push_back({a, b, m});
      }
    }
    graph.add_epoch(odometry, uwb);
    ASSERT_TRUE(graph.optimize()) << "epoch " << e;
    // The oracle's warm start, as add_epoch makes it.
    std::array<double, 3 * kRobots> next{};
    for (std::size_t i = 0; i < kRobots; ++i) {
      model::Pose2 p{static_cast<double>(i), 0.0, 0.0};
      if (i == 0) {
        p = model::Pose2{};
      }
      if (oracle.empty()) {
        for (const PairMeasurement& m : uwb) {
          if (m.own == 0 && m.other == i) {
            p = m.pose;
          }
        }
      } else {
        const std::array<double, 3 * kRobots>& last = oracle.back();
        p = model::compose({last[3 * i], last[3 * i + 1], last[3 * i + 2]}, odometry[i]);
      }
      next[3 * i] = p.x;
      next[3 * i + 1] = p.y;
      next[3 * i + 2] = p.theta;
    }
    oracle.push_back(next);
    odometry_of.push_back(odometry);
    uwb_of.push_back(uwb);
    if (oracle.size() > kWindow) {
      oracle.pop_front();
      odometry_of.pop_front();
      uwb_of.pop_front();
    }
    const auto solve = [&](std::deque<std::array<double, 3 * kRobots>>& x, bool tight) {
      ceres::Problem problem;
      for (std::size_t t = 0; t < x.size(); ++t) {
        for (std::size_t i = 0; i < kRobots && t > 0; ++i) {
          problem.AddResidualBlock(new WindowEdgeResidual(odometry_of[t][i], weights.odometry_xy_std_m,
                                                          weights.odometry_theta_std_rad),
                                   nullptr, &x[t - 1][3 * i], &x[t][3 * i]);
        }
        for (const PairMeasurement& m : uwb_of[t]) {
          problem.AddResidualBlock(new WindowEdgeResidual(m.pose, weights.uwb_xy_std_m, weights.uwb_theta_std_rad),
                                   nullptr, &x[t][3 * m.own], &x[t][3 * m.other]);
        }
      }
      for (std::size_t t = 0; t < x.size(); ++t) {
        for (std::size_t i = 0; i < kRobots; ++i) {
          problem.AddParameterBlock(&x[t][3 * i], 3);
        }
      }
      problem.SetParameterBlockConstant(&x[0][0]);
      ceres::Solver::Options options;
      options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      options.initial_trust_region_radius = 1e6;
      options.max_num_iterations = 50;
      if (tight) {
        options.function_tolerance = 1e-15;
        options.parameter_tolerance = 1e-15;
        options.max_num_iterations = 200;
      }
      ceres::Solver::Summary summary;
      ceres::Solve(options, &problem, &summary);
      for (auto& poses : x) {
        for (std::size_t i = 0; i < kRobots; ++i) {
          poses[3 * i + 2] = wrap_angle(poses[3 * i + 2]);
        }
      }
      return summary.termination_type == ceres::CONVERGENCE;
    };
    ASSERT_TRUE(solve(oracle, false)) << "epoch " << e;
    std::deque<std::array<double, 3 * kRobots>> tight = oracle;
    solve(tight, true);
    const auto relative = [&](const std::array<double, 3 * kRobots>& x, std::size_t k) {
      return model::between({x[0], x[1], x[2]}, {x[3 * k], x[3 * k + 1], x[3 * k + 2]});
    };
    for (std::size_t k = 1; k < kRobots; ++k) {
      const model::Pose2 got = graph.latest_relative(0, k);
      const model::Pose2 expected = relative(oracle.back(), k);
      largest_m = std::max(largest_m, std::hypot(got.x - expected.x, got.y - expected.y));
      largest_rad = std::max(largest_rad, std::abs(wrap_angle(got.theta - expected.theta)));
      if (e >= 8) {  // robot 4 measured: a unique minimum
        const model::Pose2 minimum = relative(tight.back(), k);
        largest_tight_m = std::max(largest_tight_m, std::hypot(got.x - minimum.x, got.y - minimum.y));
      }
    }
  }
  std::printf("block elimination against Ceres' steps: largest difference %.2e m, %.2e rad; against the minimum "
              "(tight tolerances) %.2e m\n",
              largest_m, largest_rad, largest_tight_m);
  EXPECT_LT(largest_m, 1e-9);  // the same steps, rounded otherwise (3e-15 m when written)
  EXPECT_LT(largest_rad, 1e-10);
  EXPECT_LT(largest_tight_m, 2e-3);  // where Ceres' default function tolerance (1e-6) stops both
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
