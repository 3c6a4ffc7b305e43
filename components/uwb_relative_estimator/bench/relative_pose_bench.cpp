// Per-epoch costs of paper 3's first two stages (issue 11, Performance): one eq. (1) solve warm-started
// from the previous epoch, one cold start (32 starts), the RelativePoseTracker in steady state (warm
// starts, a periodic cold start every 10 s, cost checks) against the plain warm start, and one
// sliding-window optimisation (eq. 2) of 3 robots with w = 30 and w = 160, window full.

#include <benchmark/benchmark.h>

#include <cmath>
#include <optional>
#include <vector>

#include "common/angle.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "components/uwb_relative_estimator/relative_pose_tracker.hpp"
#include "components/uwb_relative_estimator/sliding_window.hpp"

namespace {

using namespace robodds;
using namespace robodds::uwb_relative_estimator;

constexpr double kEpochS = 0.1;

/// 1000 epochs (100 s at 10 Hz) of 16 ranges between two side-0.5 m arrays, the peer circling
/// robot i at 5 m while turning, white noise 0.04 m.
struct RangeSequence {
  UwbArray array = square_array(0.5);
  std::vector<Eigen::MatrixXd> ranges;

  RangeSequence() {
    RandomEngine engine(derive_seed(1, "relative_pose_bench"));
    for (int e = 0; e < 1000; ++e) {
      const double t = kEpochS * e;
      const model::Pose2 pose{5.0 * std::cos(0.05 * t), 5.0 * std::sin(0.05 * t), wrap_angle(0.3 * t)};
      Eigen::MatrixXd r(4, 4);
      for (Eigen::Index k = 0; k < 4; ++k) {
        for (Eigen::Index l = 0; l < 4; ++l) {
          const double noise = 0.04 * standard_normal(engine);
          r(k, l) = predicted_range(pose, array.nodes_m[static_cast<std::size_t>(k)], array.nodes_m[static_cast<std::size_t>(l)]) + noise;
        }
      }
      ranges.push_back(r);
    }
  }
};

const RangeSequence& sequence() {
  static const RangeSequence s;
  return s;
}

SolverOptions paper_solver() {
  SolverOptions options;
  options.loss = RobustLoss::kNone;  // issue 11's `uwb` stage default, as the paper
  return options;
}

void BM_WarmSolve(benchmark::State& state) {
  const RangeSequence& s = sequence();
  const SolverOptions options = paper_solver();
  std::optional<model::Pose2> previous = solve_relative_pose(s.array, s.array, s.ranges[0], std::nullopt, options).pose;
  std::size_t e = 0;
  for (auto _ : state) {
    e = (e + 1) % s.ranges.size();
    previous = solve_relative_pose(s.array, s.array, s.ranges[e], previous, options).pose;
    benchmark::DoNotOptimize(previous);
  }
}
BENCHMARK(BM_WarmSolve)->Unit(benchmark::kMicrosecond);

void BM_ColdSolve(benchmark::State& state) {
  const RangeSequence& s = sequence();
  const SolverOptions options = paper_solver();
  std::size_t e = 0;
  for (auto _ : state) {
    e = (e + 1) % s.ranges.size();
    benchmark::DoNotOptimize(solve_relative_pose(s.array, s.array, s.ranges[e], std::nullopt, options));
  }
}
BENCHMARK(BM_ColdSolve)->Unit(benchmark::kMicrosecond);

/// Steady state of the tracker over the 100 s sequence (times keep growing across its wraps, so
/// the periodic cold start every 10 s is included: 1 epoch in 100).
void BM_TrackerUpdate(benchmark::State& state) {
  const RangeSequence& s = sequence();
  RelativePoseTracker tracker(s.array, s.array, paper_solver(), TrackerParams{});
  std::size_t e = 0;
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tracker.update(s.ranges[e], t));
    e = (e + 1) % s.ranges.size();
    t += kEpochS;
  }
  state.counters["cold_starts_per_epoch"] =
      static_cast<double>(tracker.counts().cold_starts) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_TrackerUpdate)->Unit(benchmark::kMicrosecond);

/// Robot r of 3 on circles (world frame) at epoch e, as sliding_window_test.cpp.
model::Pose2 circle_pose(std::size_t robot, long long epoch) {
  const double t = kEpochS * static_cast<double>(epoch);
  const double radius[3] = {2.0, 3.0, 1.5};
  const double omega[3] = {0.2, -0.15, 0.3};
  const double cx[3] = {0.0, 4.0, -2.0};
  const double cy[3] = {0.0, 1.0, 3.0};
  const double phase = omega[robot] * t;
  const double heading = phase + (omega[robot] > 0 ? kPi / 2.0 : -kPi / 2.0);
  return {cx[robot] + radius[robot] * std::cos(phase), cy[robot] + radius[robot] * std::sin(phase), wrap_angle(heading)};
}

/// Adds epoch `e` of 3 robots: odometry with 1 mm / 1 mrad noise, the 3 pairs' UWB relative poses
/// with 0.3 m / 0.1 rad noise.
void add_epoch(SlidingWindowGraph& graph, long long e, RandomEngine& engine) {
  std::vector<model::Pose2> odometry(3);
  for (std::size_t i = 0; i < 3; ++i) {
    odometry[i] = e == 0 ? model::Pose2{} : model::between(circle_pose(i, e - 1), circle_pose(i, e));
    odometry[i].x += 0.001 * standard_normal(engine);
    odometry[i].y += 0.001 * standard_normal(engine);
    odometry[i].theta += 0.001 * standard_normal(engine);
  }
  std::vector<PairMeasurement> uwb;
  for (std::size_t own = 0; own < 3; ++own) {
    for (std::size_t other = own + 1; other < 3; ++other) {
      model::Pose2 m = model::between(circle_pose(own, e), circle_pose(other, e));
      m.x += 0.3 * standard_normal(engine);
      m.y += 0.3 * standard_normal(engine);
      m.theta = wrap_angle(m.theta + 0.1 * standard_normal(engine));
      uwb.push_back({own, other, m});
    }
  }
  graph.add_epoch(odometry, uwb);
}

/// One epoch of the window in steady state: add the newest epoch (the oldest drops out), optimise.
/// Issue 11's weights (odometry 0.005 m / 0.005 rad, UWB 0.3 m / 0.1 rad).
void BM_WindowEpoch(benchmark::State& state) {
  const auto window = static_cast<std::size_t>(state.range(0));
  WindowWeights weights;
  weights.odometry_xy_std_m = 0.005;
  weights.odometry_theta_std_rad = 0.005;
  SlidingWindowGraph graph(3, window, weights);
  RandomEngine engine(derive_seed(2, "relative_pose_bench"));
  long long e = 0;
  for (; e < static_cast<long long>(window); ++e) {
    add_epoch(graph, e, engine);
    graph.optimize();
  }
  for (auto _ : state) {
    add_epoch(graph, e++, engine);
    benchmark::DoNotOptimize(graph.optimize());
  }
}
BENCHMARK(BM_WindowEpoch)->Arg(30)->Arg(160)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
