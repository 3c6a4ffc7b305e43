#pragma once
// Wall-clock compute time per named stage of one component, for summary.json's run.timing
// (docs/architecture.md, "Compute times"). A node measures a stage with ScopedComputeTimer (or
// add_ms()); the host reports every component's summaries with its health, across processes
// on run/health. Wall-clock figures: they depend on the machine and its load, never on the
// simulation, so they stay out of the deterministic comparison of summary.json.
//
// Memory: every sample is kept up to `max_samples` per stage (default 1e6 = 8 MB, i.e. 27 h of a
// 10 Hz stage; a 600 s run at 10 Hz gives 6000), so median and p99 are exact for every run we do.
// Beyond the cap a uniform reservoir of `max_samples` (Algorithm R, fixed seed) stands for all
// samples: median and p99 become unbiased estimates; count and max stay exact. A reservoir rather
// than a fixed-bin histogram: exact figures with no resolution to choose (a stage may take 2 us or
// 200 ms).
//
// Not thread-safe: a component's stages are recorded on its host's executor thread and summed
// up there after the last step.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace robodds {

/// Samples kept per stage before the reservoir takes over.
inline constexpr std::size_t kMaxComputeSamples = 1000000;

/// Wall-clock compute time per named stage of one component (ms), e.g. "window" or "cycle".
class ComputeTimes {
 public:
  explicit ComputeTimes(std::size_t max_samples = kMaxComputeSamples);

  /// One sample of `stage` (ms). A non-finite or negative value is ignored (counts nothing and
  /// does not create the stage).
  void add_ms(const std::string& stage, double ms);

  /// median_ms: the middle sample (the mean of the two middle ones for an even count);
  /// p99_ms: nearest rank, the ceil(0.99 n)-th smallest of n samples; max_ms: the largest.
  struct Summary {
    std::string stage;
    std::uint64_t count = 0;  // samples added (also those beyond the cap)
    double median_ms = 0.0;
    double p99_ms = 0.0;
    double max_ms = 0.0;
  };
  /// One per stage with at least one sample; stage order: first added first.
  std::vector<Summary> summaries() const;
  /// Samples held in memory over all stages (at most max_samples per stage).
  std::size_t samples_kept() const;

 private:
  struct Stage {
    std::string name;
    std::uint64_t count = 0;
    double max_ms = 0.0;
    std::vector<double> samples_ms;  // all of them, or the reservoir beyond the cap
  };
  Stage& stage(const std::string& name);
  std::uint64_t next_random();

  std::size_t max_samples_;
  std::vector<Stage> stages_;
  std::uint64_t random_state_ = 0x9e3779b97f4a7c15ULL;  // fixed seed of the reservoir
};

/// Adds the steady-clock time from construction to destruction to `times` under `stage`.
class ScopedComputeTimer {
 public:
  ScopedComputeTimer(ComputeTimes& times, std::string stage);
  ~ScopedComputeTimer();
  ScopedComputeTimer(const ScopedComputeTimer&) = delete;
  ScopedComputeTimer& operator=(const ScopedComputeTimer&) = delete;

 private:
  ComputeTimes& times_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
};

/// The p-th percentile (0 < p <= 100) of `sorted` (ascending, non-empty) by nearest rank: the
/// ceil(p/100 n)-th smallest.
double nearest_rank_percentile(const std::vector<double>& sorted, double p);

}  // namespace robodds
