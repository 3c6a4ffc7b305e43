// A full epoch of one robot's relative estimator in issue 11's experiment-2 shape (Performance): 2
// peers and the link between them, i.e. 3 eq. (1) solves (RelativePoseTracker, periodic cold
// starts included), one sliding window of 3 robots (w = 30, and 160), the particle filter and the
// baseline of 500 particles for each peer, odometry dead reckoning. The peers circle this robot at
// 4-6 m; ranges carry issue 11's structured errors (components/uwb_sensor's model, seeded).
// Issue 29: the same with 3 and 7 peers (4 and 8 robots tracked by one estimator; every pair of
// peers is a link, as in RelativeEstimator: 6 and 28 eq. (1) solves per epoch), peers k >= 2 on
// circles of 3-9 m at their own speeds.
// BM_WindowEpoch: the sliding window alone (SlidingWindowGraph::add_epoch + optimize, the window
// stage's work) for 3, 4 and 8 robots, every pair an edge each epoch, so that its CPU time is
// measured apart from the other stages (issue 29).
// A third argument: the estimator's threads (params threads; its worker pool runs the per-peer
// stages and the window side by side), timed in real time (UseRealTime: the CPU time of the
// calling thread alone would leave the workers' out; the CPU column is the whole process's).
// Counters: cpu_median_ms, the median of the per-epoch CPU time of the process (every thread;
// what the load of a shared machine does not inflate), the median and p99 (nearest rank) of the
// per-epoch wall times (EpochResult::cycle_ms,
// the whole step()), in ms, and the mean of each stage (the sum of its pieces' wall times, which
// overlap with threads > 1).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <vector>

#include "common/model/diff_drive_kinematics.hpp"
#include "components/uwb_relative_estimator/relative_estimator.hpp"
#include "components/uwb_relative_estimator/sliding_window.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"

namespace {

using namespace robodds;
using namespace robodds::uwb_relative_estimator;

constexpr double kEpochS = 0.1;
constexpr int kEpochs = 6000;  // 600 s, the length of experiment 2

struct Epoch {
  std::vector<PeerEpoch> peers;
  std::vector<std::optional<Eigen::MatrixXd>> links;
};

/// kEpochs epochs of `num_peers` peers circling this (static) robot, 16 ranges per direction, and
/// the ranges of every pair of peers (RelativeEstimator's links, in its order). With 2 peers the
/// sequence is the one this benchmark always had.
std::vector<Epoch> make_epochs(std::size_t num_peers) {
  const model::UwbArray array = square_array(0.5);
  const uwb_sensor::UwbErrorParams noise;
  std::vector<model::Pose2> pose{{4.0, 0.0, M_PI / 2}, {-6.0, 0.0, -M_PI / 2}};
  std::vector<model::Twist> twist{{0.2, 0.05}, {0.2, 1.0 / 30.0}};
  for (std::size_t k = 2; k < num_peers; ++k) {
    const double radius = 3.0 + static_cast<double>(k - 2);  // 3 .. 7 m
    const double bearing = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(num_peers);
    pose.push_back({radius * std::cos(bearing), radius * std::sin(bearing), bearing + M_PI / 2});
    twist.push_back({0.2, 0.2 / radius});
  }
  RandomEngine white(derive_seed(1, "bench/white"));
  RandomEngine nlos(derive_seed(1, "bench/nlos"));
  // Error streams: one per peer (its direct pair), then one per link; with 2 peers: 0, 1, then 2.
  std::vector<uwb_sensor::PairErrors> errors;
  const std::size_t num_links = num_peers * (num_peers - 1) / 2;
  for (std::size_t k = 0; k < num_peers + num_links; ++k) {
    errors.emplace_back(4, 4, 0.0, noise, RandomEngine(derive_seed(1, "bench/bias" + std::to_string(k))),
                        RandomEngine(derive_seed(1, "bench/common" + std::to_string(k))));
  }
  std::vector<Epoch> out;
  for (int e = 1; e <= kEpochs; ++e) {
    Epoch epoch;
    for (std::size_t k = 0; k < num_peers; ++k) {
      pose[k] = model::integrate_exact(pose[k], twist[k], kEpochS);
    }
    for (auto& stream : errors) {
      stream.advance_to(e * kEpochS);
    }
    for (std::size_t k = 0; k < num_peers; ++k) {
      const Eigen::MatrixXd d = model::array_ranges(array, model::Pose2{}, array, pose[k]);
      epoch.peers.push_back(PeerEpoch{model::integrate_exact(model::Pose2{}, twist[k], kEpochS),
                                      uwb_sensor::measure_ranges(d, errors[k].link_bias_m(true), errors[k].common_m(), noise,
                                                                 white, nlos)});
    }
    std::size_t stream = num_peers;
    for (std::size_t a = 0; a < num_peers; ++a) {
      for (std::size_t b = a + 1; b < num_peers; ++b, ++stream) {
        const Eigen::MatrixXd link = model::array_ranges(array, pose[a], array, pose[b]);
        epoch.links.push_back(
            uwb_sensor::measure_ranges(link, errors[stream].link_bias_m(true), errors[stream].common_m(), noise, white, nlos));
      }
    }
    out.push_back(std::move(epoch));
  }
  return out;
}

const std::vector<Epoch>& epochs(std::size_t num_peers) {
  static std::map<std::size_t, std::vector<Epoch>> made;
  auto it = made.find(num_peers);
  if (it == made.end()) {
    it = made.emplace(num_peers, make_epochs(num_peers)).first;
  }
  return it->second;
}

/// CPU time of the whole process (every thread), ms.
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double nearest_rank(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::max<std::size_t>(rank, 1) - 1];
}

/// One iteration = one epoch; the estimator runs through the 600 s sequence and starts over.
/// Arguments: the window (epochs), the number of peers, the estimator's threads and whether tc's
/// issue-27 terms are on (1; 0: tc.node_bias_term, bearing_curvature_term, innovation_check off,
/// jump_check_epochs 0, what they cost).
void BM_Exp2Cycle(benchmark::State& state) {
  const auto num_peers = static_cast<std::size_t>(state.range(1));
  const std::vector<Epoch>& sequence = epochs(num_peers);
  const model::UwbArray array = square_array(0.5);
  RelativeEstimatorParams params;
  params.window_epochs = static_cast<int>(state.range(0));
  params.threads = static_cast<int>(state.range(2));
  if (state.range(3) == 0) {
    params.tc.node_bias_term = false;
    params.tc.bearing_curvature_term = false;
    params.tc.innovation_check = false;
    params.tc.jump_check_epochs = 0;
  }
  std::optional<RelativeEstimator> estimator;
  std::vector<double> cycle_ms;
  std::vector<double> cycle_cpu_ms;
  std::array<double, kStageCount> stage_total{};
  std::size_t e = sequence.size();
  double time_s = 0.0;
  for (auto _ : state) {
    if (e == sequence.size()) {
      state.PauseTiming();
      std::vector<PeerSetup> peers;
      for (std::size_t k = 0; k < num_peers; ++k) {
        peers.push_back(PeerSetup{static_cast<std::uint32_t>(k + 2), array, std::nullopt});
      }
      estimator.emplace(array, peers, params, 1);
      e = 0;
      time_s = 0.0;
      state.ResumeTiming();
    }
    time_s += kEpochS;
    const double cpu_start = process_cpu_ms();
    const EpochResult r = estimator->step(time_s, model::Pose2{}, sequence[e].peers, sequence[e].links);
    cycle_cpu_ms.push_back(process_cpu_ms() - cpu_start);
    for (std::size_t s = 0; s < kStageCount; ++s) {
      stage_total[s] += r.stage_ms[s];
    }
    cycle_ms.push_back(r.cycle_ms);
    benchmark::DoNotOptimize(r.peers.data());
    ++e;
  }
  state.counters["median_ms"] = nearest_rank(cycle_ms, 0.5);
  state.counters["p99_ms"] = nearest_rank(cycle_ms, 0.99);
  state.counters["cpu_median_ms"] = nearest_rank(cycle_cpu_ms, 0.5);
  for (std::size_t s = 0; s < kStageCount; ++s) {
    state.counters[std::string(stage_name(static_cast<Stage>(s))) + "_ms"] = stage_total[s] / static_cast<double>(cycle_ms.size());
  }
}
BENCHMARK(BM_Exp2Cycle)
    ->Args({30, 2, 1, 1})
    ->Args({30, 2, 1, 0})
    ->Args({160, 2, 1, 1})
    ->Args({30, 3, 1, 1})
    ->Args({30, 7, 1, 1})
    ->Args({30, 2, 2, 1})
    ->Args({30, 3, 2, 1})
    ->Args({30, 7, 2, 1})
    ->Iterations(3000)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// One iteration = one epoch of the tc stage of one peer (TightlyCoupledWindow::step: the solve, the
/// marginalisation, the covariance) through the 600 s sequence of BM_Exp2Cycle's first peer, with
/// the eq. (1) fixes (RelativePoseTracker, ok only) computed beforehand; started over at its end.
void BM_TcEpoch(benchmark::State& state) {
  const std::vector<Epoch>& sequence = epochs(2);
  const model::UwbArray array = square_array(0.5);
  const RelativeEstimatorParams params;
  std::vector<std::optional<model::Pose2>> fixes;
  RelativePoseTracker tracker(array, array, params.solver, params.tracker);
  for (std::size_t e = 0; e < sequence.size(); ++e) {
    const TrackerOutput solved = tracker.update(*sequence[e].peers[0].ranges_m, kEpochS * static_cast<double>(e + 1));
    fixes.push_back(solved.status == TrackStatus::kOk ? std::optional<model::Pose2>(solved.pose) : std::nullopt);
  }
  std::optional<TightlyCoupledWindow> tc;
  std::size_t e = sequence.size();
  std::size_t valid = 0;
  for (auto _ : state) {
    if (e == sequence.size()) {
      state.PauseTiming();
      tc.emplace(array, array, params.tc);
      e = 0;
      state.ResumeTiming();
    }
    valid += tc->step(kEpochS * static_cast<double>(e + 1), model::Pose2{}, sequence[e].peers[0].odometry_increment,
                      sequence[e].peers[0].ranges_m, fixes[e])
                 ? 1
                 : 0;
    ++e;
  }
  state.counters["valid"] = static_cast<double>(valid);
}
BENCHMARK(BM_TcEpoch)->Iterations(6000)->Unit(benchmark::kMillisecond);

struct WindowEpoch {
  std::vector<model::Pose2> odometry;
  std::vector<PairMeasurement> uwb;
};

/// kEpochs epochs of `num_robots` robots on circles of 3-9 m: odometry increments and every pair's
/// relative pose (eq. 1's output), each with Gaussian noise of the window's default stds.
std::vector<WindowEpoch> make_window_epochs(std::size_t num_robots) {
  RandomEngine random(derive_seed(1, "bench/window"));
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<model::Pose2> pose;
  std::vector<model::Twist> twist;
  for (std::size_t i = 0; i < num_robots; ++i) {
    const double radius = 3.0 + static_cast<double>(i);
    const double bearing = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(num_robots);
    pose.push_back({radius * std::cos(bearing), radius * std::sin(bearing), bearing + M_PI / 2});
    twist.push_back({0.2, 0.2 / radius});
  }
  const WindowWeights w;
  std::vector<WindowEpoch> out;
  for (int e = 0; e < kEpochs; ++e) {
    WindowEpoch epoch;
    for (std::size_t i = 0; i < num_robots; ++i) {
      const model::Pose2 next = model::integrate_exact(pose[i], twist[i], kEpochS);
      const model::Pose2 step = model::between(pose[i], next);
      epoch.odometry.push_back({step.x + w.odometry_xy_std_m * unit(random), step.y + w.odometry_xy_std_m * unit(random),
                                step.theta + w.odometry_theta_std_rad * unit(random)});
      pose[i] = next;
    }
    for (std::size_t a = 0; a < num_robots; ++a) {
      for (std::size_t b = a + 1; b < num_robots; ++b) {
        const model::Pose2 rel = model::between(pose[a], pose[b]);
        epoch.uwb.push_back(PairMeasurement{a, b,
                                            {rel.x + w.uwb_xy_std_m * unit(random), rel.y + w.uwb_xy_std_m * unit(random),
                                             rel.theta + w.uwb_theta_std_rad * unit(random)}});
      }
    }
    out.push_back(std::move(epoch));
  }
  return out;
}

/// One iteration = one epoch of the window (add_epoch + optimize) through the 600 s sequence,
/// started over at its end. Arguments: the window (epochs) and the number of robots.
void BM_WindowEpoch(benchmark::State& state) {
  const auto window = static_cast<std::size_t>(state.range(0));
  const auto num_robots = static_cast<std::size_t>(state.range(1));
  const std::vector<WindowEpoch> sequence = make_window_epochs(num_robots);
  std::optional<SlidingWindowGraph> graph;
  std::size_t e = sequence.size();
  std::size_t not_converged = 0;
  for (auto _ : state) {
    if (e == sequence.size()) {
      state.PauseTiming();
      graph.emplace(num_robots, window, WindowWeights{});
      e = 0;
      state.ResumeTiming();
    }
    graph->add_epoch(sequence[e].odometry, sequence[e].uwb);
    not_converged += graph->optimize() ? 0 : 1;
    ++e;
  }
  state.counters["not_converged"] = static_cast<double>(not_converged);
}
BENCHMARK(BM_WindowEpoch)->Args({30, 3})->Args({30, 4})->Args({30, 8})->Iterations(3000)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
