// Cost of one observer update (issues 10 and 28: "the observer step under 1 us"): a range sample in, the
// estimate out, on a noisy range at 50 Hz so that every branch of the law is exercised.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "common/random.hpp"
#include "components/range_rate_observer/range_rate_observer.hpp"

namespace {

using robodds::range_rate_observer::KalmanObserverParams;
using robodds::range_rate_observer::KalmanRangeRateObserver;
using robodds::range_rate_observer::LinearObserverParams;
using robodds::range_rate_observer::LinearRangeRateObserver;
using robodds::range_rate_observer::SuperTwistingObserver;
using robodds::range_rate_observer::SuperTwistingParams;

/// One period (4096 samples at 50 Hz, 81.92 s) of a range swinging 100 m around 200 m (peak rate
/// 7.7 m/s, acceleration 0.59 m/s^2 < b, so no restart), sigma 0.5 m; precomputed: the benchmark
/// times the observer, not the noise.
std::vector<double> noisy_ranges() {
  robodds::RandomEngine engine(1);
  std::vector<double> ranges;
  for (int i = 0; i < 4096; ++i) {
    const double phase = 2.0 * 3.141592653589793 * i / 4096.0;
    ranges.push_back(200.0 + 100.0 * std::sin(phase) + 0.5 * robodds::standard_normal(engine));
  }
  return ranges;
}

template <class Observer, class Params>
void run(benchmark::State& state) {
  const std::vector<double> ranges = noisy_ranges();
  Observer observer{Params{}};
  double t = 0.0;
  std::size_t i = 0;
  for (auto _ : state) {
    t += 0.02;
    benchmark::DoNotOptimize(observer.update(t, ranges[i++ & 4095]));
  }
  state.counters["restarts"] = static_cast<double>(observer.restarts());
}

void BM_SuperTwistingUpdate(benchmark::State& state) { run<SuperTwistingObserver, SuperTwistingParams>(state); }
void BM_LinearUpdate(benchmark::State& state) { run<LinearRangeRateObserver, LinearObserverParams>(state); }
void BM_KalmanUpdate(benchmark::State& state) { run<KalmanRangeRateObserver, KalmanObserverParams>(state); }  // issue 28
BENCHMARK(BM_SuperTwistingUpdate);
BENCHMARK(BM_LinearUpdate);
BENCHMARK(BM_KalmanUpdate);

}  // namespace

BENCHMARK_MAIN();
