// Cost of one epoch (predict + update) of the relative-pose particle filter of paper 3: the
// paper's filter weighted by a relative pose (eq. 5-6) and the baseline [22] weighted by the 16
// ranges of two 4-node arrays. Issue 11's prototype: 0.13 ms per PF epoch with 500 particles.
// Resampling happens after every update (the default, as the paper).

#include <benchmark/benchmark.h>

#include <cmath>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/relative_pf.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"

namespace {

using robodds::RandomEngine;
using robodds::model::Pose2;
using robodds::uwb_relative_estimator::RelativePfParams;
using robodds::uwb_relative_estimator::RelativePoseFilter;

// Robot i drives a 2 m circle at 0.4 m/s, j (starting 4 m ahead) turns on the spot: the
// increments of one 10 Hz epoch.
const Pose2 kOwnIncrement{0.04, 0.0, 0.02};
const Pose2 kOtherIncrement{0.0, 0.0, 0.03};
const Pose2 kStart{4.0, 0.0, 0.0};

// The true relative pose one epoch later (eq. 4 without noise), so the measurements follow the
// cloud without timing the filter's own estimate.
Pose2 advance(const Pose2& truth) {
  return robodds::model::compose(robodds::model::between(kOwnIncrement, truth), kOtherIncrement);
}

RelativePoseFilter make_filter(benchmark::State& state, RandomEngine& engine) {
  RelativePfParams params;
  params.num_particles = static_cast<int>(state.range(0));
  RelativePoseFilter filter(params);
  filter.initialize(kStart, engine);
  return filter;
}

void BM_RelativePfEpoch(benchmark::State& state) {
  RandomEngine engine(1);
  RandomEngine world(2);
  RelativePoseFilter filter = make_filter(state, engine);
  Pose2 truth = kStart;
  for (auto _ : state) {
    truth = advance(truth);
    filter.predict(kOwnIncrement, kOtherIncrement, engine);
    filter.update_with_pose({truth.x + 0.3 * robodds::standard_normal(world), truth.y + 0.3 * robodds::standard_normal(world),
                             robodds::wrap_angle(truth.theta + 0.1 * robodds::standard_normal(world))},
                            engine);
    benchmark::DoNotOptimize(filter.weights().data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_BaselinePfEpoch(benchmark::State& state) {
  RandomEngine engine(1);
  RandomEngine world(2);
  RelativePoseFilter filter = make_filter(state, engine);
  Pose2 truth = kStart;
  const robodds::model::UwbArray array = robodds::model::square_array(0.5);
  Eigen::MatrixXd ranges(4, 4);
  for (auto _ : state) {
    truth = advance(truth);
    filter.predict(kOwnIncrement, kOtherIncrement, engine);
    for (Eigen::Index k = 0; k < 4; ++k) {
      for (Eigen::Index l = 0; l < 4; ++l) {
        ranges(k, l) = robodds::uwb_relative_estimator::predicted_range(truth, array.nodes_m[static_cast<std::size_t>(k)],
                                                     array.nodes_m[static_cast<std::size_t>(l)]) +
                       0.05 * robodds::standard_normal(world);
      }
    }
    filter.update_with_ranges(array, array, ranges, engine);
    benchmark::DoNotOptimize(filter.weights().data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_RelativePfEstimate(benchmark::State& state) {
  RandomEngine engine(1);
  RelativePoseFilter filter = make_filter(state, engine);
  for (auto _ : state) {
    benchmark::DoNotOptimize(filter.estimate());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_RelativePfPredict(benchmark::State& state) {
  RandomEngine engine(1);
  RelativePoseFilter filter = make_filter(state, engine);
  for (auto _ : state) {
    filter.predict(kOwnIncrement, kOtherIncrement, engine);
    benchmark::DoNotOptimize(filter.particles().x.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

}  // namespace

BENCHMARK(BM_RelativePfEpoch)->Arg(100)->Arg(500)->Arg(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BaselinePfEpoch)->Arg(100)->Arg(500)->Arg(2000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RelativePfEstimate)->Arg(500)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RelativePfPredict)->Arg(500)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
