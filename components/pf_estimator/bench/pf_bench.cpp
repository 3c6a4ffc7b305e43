// Cost of one filter cycle (predict + update) and of its parts, for M = 100 ... 5000.
// The truth drives a turning path so the cloud stays realistic (resampling happens at its
// natural rate, counted in the "resample_rate" counter).

#include <benchmark/benchmark.h>

#include <cmath>

#include "common/model/diff_drive_kinematics.hpp"
#include "common/random.hpp"
#include "components/pf_estimator/particle_filter.hpp"

namespace {

using robodds::RandomEngine;
using robodds::pf_estimator::ParticleFilter;
using robodds::pf_estimator::PfParams;

constexpr double kDt = 0.02;

PfParams params_for(benchmark::State& state) {
  PfParams params;
  params.num_particles = static_cast<int>(state.range(0));
  params.resample_threshold = 0.5 * params.num_particles;
  params.init_mode = robodds::pf_estimator::InitMode::kFirstFix;
  params.init_theta_known = true;
  return params;
}

// One predict + one update per iteration (the spec'd cycle; a real 50 Hz / 10 Hz loop makes
// five predictions per update).
void BM_PredictUpdate(benchmark::State& state) {
  ParticleFilter filter(params_for(state), 1);
  RandomEngine world(2);
  robodds::model::Pose2 truth{0.0, 0.0, 0.0};
  const robodds::model::Twist twist{1.0, 0.2};
  filter.update(0.0, 0.0);
  for (auto _ : state) {
    truth = robodds::model::integrate_exact(truth, twist, kDt);
    filter.predict(twist.v, twist.omega, kDt);
    filter.update(truth.x + 1.5 * robodds::standard_normal(world),
                  truth.y + 1.5 * robodds::standard_normal(world));
    benchmark::DoNotOptimize(filter.weights().data());
  }
  state.counters["resample_rate"] = benchmark::Counter(
      static_cast<double>(filter.resample_count()) / static_cast<double>(state.iterations()));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_Predict(benchmark::State& state) {
  ParticleFilter filter(params_for(state), 1);
  filter.update(0.0, 0.0);
  for (auto _ : state) {
    filter.predict(1.0, 0.2, kDt);
    benchmark::DoNotOptimize(filter.particles().x.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// Repeated updates with fixes scattered like the paper's sensor (std 1.5 m) around the origin.
void run_updates(benchmark::State& state, const PfParams& params) {
  ParticleFilter filter(params, 1);
  RandomEngine world(2);
  filter.update(0.0, 0.0);
  for (auto _ : state) {
    filter.update(1.5 * robodds::standard_normal(world), 1.5 * robodds::standard_normal(world));
    benchmark::DoNotOptimize(filter.weights().data());
  }
  state.counters["resample_rate"] = benchmark::Counter(
      static_cast<double>(filter.resample_count()) / static_cast<double>(state.iterations()));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_Update(benchmark::State& state) { run_updates(state, params_for(state)); }

// Worst-case update latency: N_s = M, so every update resamples (and regularises).
void BM_UpdateAlwaysResampling(benchmark::State& state) {
  PfParams params = params_for(state);
  params.resample_threshold = static_cast<double>(params.num_particles);
  run_updates(state, params);
}

void BM_Estimate(benchmark::State& state) {
  ParticleFilter filter(params_for(state), 1);
  filter.update(0.0, 0.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(filter.estimate());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_PredictUpdate)->Arg(100)->Arg(500)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Predict)->Arg(100)->Arg(500)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Update)->Arg(100)->Arg(500)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_UpdateAlwaysResampling)->Arg(100)->Arg(500)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Estimate)->Arg(100)->Arg(500)->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
