#include "components/uwb_relative_estimator/relative_pose_tracker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/angle.hpp"
#include "common/random.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

constexpr double kEpochS = 0.1;  // 10 Hz epochs, as the estimator of issue 11

Eigen::MatrixXd noisy_ranges(const UwbArray& own, const UwbArray& peer, const model::Pose2& pose, double sigma_m,
                             RandomEngine& engine) {
  Eigen::MatrixXd ranges(own.nodes_m.size(), peer.nodes_m.size());
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    for (std::size_t l = 0; l < peer.nodes_m.size(); ++l) {
      const double noise = sigma_m * standard_normal(engine);
      ranges(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) =
          std::max(0.0, predicted_range(pose, own.nodes_m[k], peer.nodes_m[l]) + noise);
    }
  }
  return ranges;
}

/// Right = in the basin of the truth: wrong minima are 90-180 deg off in heading.
bool right(const model::Pose2& estimate, const model::Pose2& truth) {
  return std::hypot(estimate.x - truth.x, estimate.y - truth.y) < 1.0 &&
         std::abs(wrap_angle(estimate.theta - truth.theta)) < 30.0 * kPi / 180.0;
}

model::Pose2 random_pose(RandomEngine& engine, double min_m, double max_m) {
  const double distance = min_m + (max_m - min_m) * uniform01(engine);
  const double bearing = 2.0 * kPi * uniform01(engine);
  const double heading = kPi - 2.0 * kPi * uniform01(engine);
  return {distance * std::cos(bearing), distance * std::sin(bearing), heading};
}

TEST(RelativePoseTracker, RecoversFromAHeadingJumpWithinOneColdStart) {
  // Issue 11: started 150-180 deg off in heading, the warm start ends in a wrong minimum in about a
  // third of the trials. Here the peer turns by 150-180 deg between two epochs (frames lost while it
  // turned) at 3-10 m; the tracker must be right from its first cold start after the jump on, and
  // that cold start must come within cold_start_period_s. The plain warm-start chain on the same
  // ranges shows that the case bites.
  const UwbArray array = square_array(0.5);
  constexpr int kTrials = 100;
  constexpr int kJumpEpoch = 25;   // t = 2.5 s; the last cold start was the first epoch, t = 0
  constexpr int kEpochs = 125;     // to t = 12.4 s: the periodic cold start at 10 s is inside
  int tracker_wrong = 0, plain_wrong = 0, caught_at_jump = 0, published_wrong = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    RandomEngine engine(derive_seed(static_cast<std::uint64_t>(trial), "tracker_recovery"));
    model::Pose2 truth = random_pose(engine, 3.0, 10.0);
    const double turn = (150.0 + 30.0 * uniform01(engine)) * kPi / 180.0 * (uniform01(engine) < 0.5 ? -1.0 : 1.0);
    RelativePoseTracker tracker(array, array, SolverOptions{}, TrackerParams{});
    std::optional<model::Pose2> plain;
    bool recovered = false;  // the first cold start after the jump has happened
    bool trial_wrong = false;
    double last_cold_s = 0.0;
    for (int e = 0; e < kEpochs; ++e) {
      const double t = kEpochS * e;
      if (e == kJumpEpoch) {
        truth.theta = wrap_angle(truth.theta + turn);
      }
      const Eigen::MatrixXd ranges = noisy_ranges(array, array, truth, 0.02, engine);
      const TrackerOutput out = tracker.update(ranges, t);
      plain = solve_relative_pose(array, array, ranges, plain, SolverOptions{}).pose;
      if (out.cold_start != ColdStart::kNone) {
        EXPECT_LE(t - last_cold_s, TrackerParams{}.cold_start_period_s + 1e-9);
        last_cold_s = t;
        if (e >= kJumpEpoch && !recovered) {
          recovered = true;
          caught_at_jump += e == kJumpEpoch ? 1 : 0;
        }
      }
      if (out.status == TrackStatus::kOk && !right(out.pose, truth)) {
        ++published_wrong;
      }
      if (e < kJumpEpoch || recovered) {
        trial_wrong = trial_wrong || !right(out.pose, truth);
      }
    }
    EXPECT_TRUE(recovered) << "trial " << trial;
    tracker_wrong += trial_wrong ? 1 : 0;
    plain_wrong += right(*plain, truth) ? 0 : 1;
  }
  std::printf("heading jump of 150-180 deg at 3-10 m, %d trials: plain warm start wrong at the end in %d, tracker wrong "
              "after its first cold start in %d (cold start at the jump itself in %d); kOk outputs that were wrong: %d\n",
              kTrials, plain_wrong, tracker_wrong, caught_at_jump, published_wrong);
  EXPECT_EQ(tracker_wrong, 0);
  EXPECT_EQ(published_wrong, 0);  // a wrong minimum is never returned as kOk
  EXPECT_GE(plain_wrong, 15);  // the defect is there without recovery (issue 11: 32-36 %)
}

/// Epochs of a static pose with white range noise; returns the outputs. Times are summed in
/// steps of 0.1 s, as a node would, to exercise the slack of the period.
std::vector<TrackerOutput> run_static(RelativePoseTracker& tracker, const model::Pose2& truth, int epochs, double sigma_m,
                                      RandomEngine& engine) {
  const UwbArray array = square_array(0.5);
  std::vector<TrackerOutput> outputs;
  double t = 0.0;
  for (int e = 0; e < epochs; ++e, t += kEpochS) {
    outputs.push_back(tracker.update(noisy_ranges(array, array, truth, sigma_m, engine), t));
  }
  return outputs;
}

TEST(RelativePoseTracker, ColdStartsAtTheFirstEpochAndThenEveryPeriod) {
  RelativePoseTracker tracker(square_array(0.5), square_array(0.5), SolverOptions{}, TrackerParams{});
  RandomEngine engine(derive_seed(1, "tracker_periodic"));
  const model::Pose2 truth{4.0, -2.0, 1.0};
  const std::vector<TrackerOutput> out = run_static(tracker, truth, 251, 0.02, engine);
  for (std::size_t e = 0; e < out.size(); ++e) {
    const ColdStart expected = e == 0 ? ColdStart::kFirst : (e == 100 || e == 200) ? ColdStart::kPeriodic : ColdStart::kNone;
    EXPECT_EQ(out[e].cold_start, expected) << "epoch " << e << ": " << to_string(out[e].cold_start);
    EXPECT_EQ(out[e].status, TrackStatus::kOk) << "epoch " << e << ": " << out[e].reason;
    EXPECT_TRUE(right(out[e].pose, truth)) << "epoch " << e;
  }
  EXPECT_EQ(tracker.counts().cold_starts, 3u);
  EXPECT_EQ(tracker.counts().ok, 251u);
}

TEST(RelativePoseTracker, ACostSpikeTriggersAColdStartAndIsNotPublished) {
  const UwbArray array = square_array(0.5);
  RelativePoseTracker tracker(array, array, SolverOptions{}, TrackerParams{});
  RandomEngine engine(derive_seed(2, "tracker_spike"));
  const model::Pose2 truth{5.0, 1.0, -0.5};
  run_static(tracker, truth, 20, 0.02, engine);
  Eigen::MatrixXd ranges = noisy_ranges(array, array, truth, 0.02, engine);
  ranges(0, 1) += 1.0;  // non-line-of-sight on three links
  ranges(2, 2) += 1.2;
  ranges(3, 0) += 0.8;
  const TrackerOutput spike = tracker.update(ranges, 2.0);
  EXPECT_EQ(spike.cold_start, ColdStart::kCostSpike);
  EXPECT_EQ(spike.status, TrackStatus::kSuspect);
  EXPECT_NE(spike.reason.find("above 5 x the running median even after a cold start"), std::string::npos) << spike.reason;
  const TrackerOutput next = tracker.update(noisy_ranges(array, array, truth, 0.02, engine), 2.1);
  EXPECT_EQ(next.cold_start, ColdStart::kNone);
  EXPECT_EQ(next.status, TrackStatus::kOk);
  EXPECT_EQ(tracker.counts().suspect, 1u);
  EXPECT_EQ(tracker.counts().cold_starts, 2u);

  // The same spike below the ratio (ratio 1000): warm start only, published.
  TrackerParams lenient;
  lenient.cost_ratio = 1000.0;
  RelativePoseTracker relaxed(array, array, SolverOptions{}, lenient);
  RandomEngine engine2(derive_seed(2, "tracker_spike"));
  run_static(relaxed, truth, 20, 0.02, engine2);
  EXPECT_EQ(relaxed.update(ranges, 2.0).cold_start, ColdStart::kNone);
}

TEST(RelativePoseTracker, AColdStartThatDisagreesWithTheWarmStartIsSuspect) {
  // The peer turns by 180 deg between two epochs; the cold start at the jump (cost spike or
  // periodic) lands far from the warm start: suspect, and the next epoch is right again.
  const UwbArray array = square_array(0.5);
  TrackerParams params;
  params.cold_start_period_s = 2.0;  // the jump epoch is also a periodic cold start
  RelativePoseTracker tracker(array, array, SolverOptions{}, params);
  RandomEngine engine(derive_seed(3, "tracker_disagree"));
  model::Pose2 truth{3.0, 4.0, 0.3};
  const TrackerOutput before = run_static(tracker, truth, 20, 0.02, engine).back();
  truth.theta = wrap_angle(truth.theta + kPi);
  const Eigen::MatrixXd ranges = noisy_ranges(array, array, truth, 0.02, engine);
  // The case bites: from the previous estimate alone the solver stays in a wrong minimum.
  ASSERT_FALSE(right(solve_relative_pose(array, array, ranges, before.pose, SolverOptions{}).pose, truth));
  const TrackerOutput jump = tracker.update(ranges, 2.0);
  EXPECT_NE(jump.cold_start, ColdStart::kNone);
  EXPECT_EQ(jump.status, TrackStatus::kSuspect);
  EXPECT_NE(jump.reason.find("from the warm start (a wrong minimum"), std::string::npos) << jump.reason;
  EXPECT_TRUE(right(jump.pose, truth));  // the lower cost (the cold start's) is kept
  const TrackerOutput next = tracker.update(noisy_ranges(array, array, truth, 0.02, engine), 2.1);
  EXPECT_EQ(next.status, TrackStatus::kOk) << next.reason;
  EXPECT_TRUE(right(next.pose, truth));
}

TEST(RelativePoseTracker, FailedSolvesAreReportedAndTheNextEpochColdStarts) {
  const UwbArray array = square_array(0.5);
  RandomEngine engine(derive_seed(4, "tracker_failed"));
  const model::Pose2 truth{6.0, 0.0, 0.0};
  {
    SolverOptions one_iteration;  // no start converges in one iteration from noisy ranges
    one_iteration.max_iterations = 1;
    RelativePoseTracker tracker(array, array, one_iteration, TrackerParams{});
    const TrackerOutput a = tracker.update(noisy_ranges(array, array, truth, 0.02, engine), 0.0);
    EXPECT_EQ(a.status, TrackStatus::kFailed);
    EXPECT_NE(a.reason.find("cold start failed"), std::string::npos) << a.reason;
    const TrackerOutput b = tracker.update(noisy_ranges(array, array, truth, 0.02, engine), 0.1);
    EXPECT_EQ(b.cold_start, ColdStart::kFirst);  // nothing to warm-start from after a failure
    EXPECT_EQ(tracker.counts().failed, 2u);
    EXPECT_EQ(tracker.counts().ok, 0u);
  }
  {
    RelativePoseTracker tracker(array, array, SolverOptions{}, TrackerParams{});
    run_static(tracker, truth, 5, 0.02, engine);
    // Finite but absurd ranges: the cost overflows, Ceres fails; never a corrupted estimate.
    const TrackerOutput huge = tracker.update(Eigen::MatrixXd::Constant(4, 4, 1e200), 0.5);
    EXPECT_EQ(huge.status, TrackStatus::kFailed);
    EXPECT_EQ(huge.cold_start, ColdStart::kWarmFailed);
    const TrackerOutput after = tracker.update(noisy_ranges(array, array, truth, 0.02, engine), 0.6);
    EXPECT_EQ(after.cold_start, ColdStart::kFirst);
    EXPECT_EQ(after.status, TrackStatus::kOk) << after.reason;
    EXPECT_TRUE(right(after.pose, truth));
  }
}

TEST(RelativePoseTracker, BadInputIsRejectedCountedAndChangesNothing) {
  const UwbArray array = square_array(0.5);
  RelativePoseTracker tracker(array, array, SolverOptions{}, TrackerParams{});
  RandomEngine engine(derive_seed(5, "tracker_bad_input"));
  const model::Pose2 truth{4.0, 3.0, 2.0};
  run_static(tracker, truth, 10, 0.02, engine);  // t = 0 .. 0.9
  const std::optional<double> median = tracker.cost_median();
  Eigen::MatrixXd ranges = noisy_ranges(array, array, truth, 0.02, engine);
  const auto rejected = [&](const Eigen::MatrixXd& r, double t) {
    const TrackerOutput out = tracker.update(r, t);
    EXPECT_EQ(out.status, TrackStatus::kRejected);
    return out.reason;
  };
  Eigen::MatrixXd bad = ranges;
  bad(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(rejected(bad, 1.0), "RelativePoseTracker: range (1, 3): must be >= 0 and finite (got nan)");
  bad(1, 3) = -0.5;
  EXPECT_EQ(rejected(bad, 1.0), "RelativePoseTracker: range (1, 3): must be >= 0 and finite (got -0.5)");
  EXPECT_EQ(rejected(Eigen::MatrixXd::Ones(4, 3), 1.0), "RelativePoseTracker: ranges are 4 x 3, the arrays need 4 x 4");
  EXPECT_EQ(rejected(ranges, std::numeric_limits<double>::infinity()), "time inf s is not finite");
  EXPECT_EQ(rejected(ranges, 0.5), "time 0.5 s is before the previous epoch's 0.8999999999999999 s");  // nine 0.1 s steps
  EXPECT_EQ(tracker.counts().rejected, 5u);
  EXPECT_EQ(tracker.cost_median(), median);
  const TrackerOutput good = tracker.update(ranges, 1.0);  // still warm: nothing was reset
  EXPECT_EQ(good.cold_start, ColdStart::kNone);
  EXPECT_EQ(good.status, TrackStatus::kOk);
  EXPECT_TRUE(right(good.pose, truth));
}

TEST(RelativePoseTracker, TheRunningMedianCoversTheLastWindowOfCosts) {
  TrackerParams params;
  params.cost_median_window = 3;
  RelativePoseTracker tracker(square_array(0.5), square_array(0.5), SolverOptions{}, params);
  EXPECT_FALSE(tracker.cost_median().has_value());
  RandomEngine engine(derive_seed(6, "tracker_median"));
  const std::vector<TrackerOutput> out = run_static(tracker, model::Pose2{5.0, 0.0, 0.0}, 7, 0.05, engine);
  std::vector<double> last{out[4].cost, out[5].cost, out[6].cost};
  std::sort(last.begin(), last.end());
  EXPECT_DOUBLE_EQ(*tracker.cost_median(), last[1]);
}

TEST(RelativePoseTracker, BadParamsAndArraysNameTheKey) {
  const UwbArray square = square_array(0.5);
  const auto message = [&](const UwbArray& own, const UwbArray& peer, const TrackerParams& params) -> std::string {
    try {
      const RelativePoseTracker tracker(own, peer, SolverOptions{}, params);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  TrackerParams p;
  p.cold_start_period_s = 0.0;
  EXPECT_EQ(message(square, square, p), "cold_start_period_s: must be > 0 and finite (got 0)");
  p = TrackerParams{};
  p.cost_ratio = 1.0;
  EXPECT_EQ(message(square, square, p), "cost_ratio: must be > 1 and finite (got 1)");
  p = TrackerParams{};
  p.cost_median_window = 0;
  EXPECT_EQ(message(square, square, p), "cost_median_window: must be >= 1 (got 0)");
  const UwbArray two{{{0.25, 0.25}, {-0.25, 0.25}}};
  EXPECT_EQ(message(two, square, TrackerParams{}), "own_array: needs at least 3 nodes (a relative heading needs them) (got 2 nodes)");
  UwbArray coincident = square;
  coincident.nodes_m[2] = coincident.nodes_m[0];
  EXPECT_EQ(message(square, coincident, TrackerParams{}),
            "peer_array: nodes 0 and 2 coincide (closer than 0.001 m) (got 0 m apart)");
  const params::ParamDoc doc = tracker_param_table().doc();
  ASSERT_EQ(doc.params.size(), 6u);
  EXPECT_EQ(doc.params[1].key, "cost_ratio");
  EXPECT_EQ(doc.params[1].range, "> 1");
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
