// RelativeEstimator: every stage of paper 3 for each peer of one robot. Motion: this robot (i)
// static at the origin, heading 0; peers drive circles around it. Ranges from the UWB sensor's
// error model (components/uwb_sensor: white + link bias + common mode), seeded.
#include "components/uwb_relative_estimator/relative_estimator.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

constexpr double kEpochS = 0.1;

/// A peer on a circle of radius v / omega about the origin, counter-clockwise.
struct CirclingPeer {
  std::uint32_t id;
  model::Pose2 pose;
  model::Twist twist{0.2, 0.05};
};

model::Pose2 increment_of(const model::Twist& twist) { return model::integrate_exact(model::Pose2{}, twist, kEpochS); }

struct Errors {
  double position_m = 0.0;
  double heading_deg = 0.0;
  int count = 0;
  int overconfident = 0;  // outside the reported 3 sigma (x-y ellipse or heading), as the evaluator judges
  double d2_sum = 0.0;    // x-y Mahalanobis distance squared against the reported covariance (2 if consistent)
  void add(const model::Pose2& estimate, const model::Pose2& truth, const Eigen::Matrix3d& covariance) {
    const Eigen::Vector2d e(estimate.x - truth.x, estimate.y - truth.y);
    const double e_theta = wrap_angle(estimate.theta - truth.theta);
    position_m += e.norm();
    heading_deg += std::abs(e_theta) * 180.0 / M_PI;
    ++count;
    const Eigen::Matrix2d xy = covariance.topLeftCorner<2, 2>();
    const double d2 = xy.determinant() > 0.0 ? e.dot(xy.inverse() * e) : std::numeric_limits<double>::infinity();
    d2_sum += d2;
    if (d2 > 11.829 || !(e_theta * e_theta <= 9.0 * covariance(2, 2))) {
      ++overconfident;
    }
  }
  double overconfident_fraction() const { return static_cast<double>(overconfident) / count; }
  double mean_d2() const { return d2_sum / count; }
  double mean_position_m() const { return position_m / count; }
  double mean_heading_deg() const { return heading_deg / count; }
};

/// Runs `epochs` epochs of two circling peers and returns the mean error of each stage over the
/// epochs after `settle` (valid estimates only; every stage must be valid by then).
/// `params`, `side_m` (both arrays) and `truth` (the peers) as given.
std::array<Errors, kStageCount> run(const uwb_sensor::UwbErrorParams& noise, int epochs, int settle, std::uint64_t seed,
                                    const RelativeEstimatorParams& params, double side_m, std::vector<CirclingPeer> truth) {
  const model::UwbArray array = square_array(side_m);
  std::vector<PeerSetup> setups;
  std::vector<uwb_sensor::PairErrors> errors;
  RandomEngine white(derive_seed(seed, "white"));
  RandomEngine nlos(derive_seed(seed, "nlos"));
  for (const CirclingPeer& p : truth) {
    setups.push_back(PeerSetup{p.id, array, p.pose});
    errors.emplace_back(4, 4, 0.0, noise, RandomEngine(derive_seed(seed, "bias" + std::to_string(p.id))),
                        RandomEngine(derive_seed(seed, "common" + std::to_string(p.id))));
  }
  RelativeEstimator estimator(array, setups, params, seed);
  std::array<Errors, kStageCount> out;
  for (int e = 1; e <= epochs; ++e) {
    const double t = e * kEpochS;
    std::vector<PeerEpoch> inputs;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      truth[k].pose = model::integrate_exact(truth[k].pose, truth[k].twist, kEpochS);
      errors[k].advance_to(t);
      const Eigen::MatrixXd d = model::array_ranges(array, model::Pose2{}, array, truth[k].pose);
      inputs.push_back(PeerEpoch{increment_of(truth[k].twist),
                                 uwb_sensor::measure_ranges(d, errors[k].link_bias_m(true), errors[k].common_m(), noise, white, nlos)});
    }
    const EpochResult result = estimator.step(t, model::Pose2{}, inputs);
    if (e <= settle) {
      continue;
    }
    for (std::size_t k = 0; k < truth.size(); ++k) {
      for (std::size_t s = 0; s < kStageCount; ++s) {
        const StageEstimate& stage = result.peers[k].stages[s];
        if (stage.valid) {
          out[s].add(stage.pose, truth[k].pose, stage.covariance);
        }
      }
    }
  }
  return out;
}

std::array<Errors, kStageCount> run(const uwb_sensor::UwbErrorParams& noise, int epochs, int settle, std::uint64_t seed) {
  return run(noise, epochs, settle, seed, RelativeEstimatorParams{}, 0.5,
             {{2, {4.0, 0.0, M_PI / 2}}, {3, {-5.0, 0.0, -M_PI / 2}}});
}

uwb_sensor::UwbErrorParams no_noise() {
  uwb_sensor::UwbErrorParams p;
  p.white_sigma_m = 0.0;
  p.link_bias_sigma_m = 0.0;
  p.common_sigma_m = 0.0;
  return p;
}

TEST(RelativeEstimator, EveryStageFindsThePeersWithoutNoise) {
  const auto errors = run(no_noise(), 100, 40, 1);
  for (std::size_t s = 0; s < kStageCount; ++s) {
    SCOPED_TRACE(stage_name(static_cast<Stage>(s)));
    ASSERT_EQ(errors[s].count, 2 * 60) << "every stage valid for both peers once settled";
    // The filters keep their odometry noise (5 mm, 3 mrad per epoch): a few cm; the rest is exact.
    EXPECT_LT(errors[s].mean_position_m(), 0.05);
    EXPECT_LT(errors[s].mean_heading_deg(), 1.0);
  }
  EXPECT_LT(errors[static_cast<std::size_t>(Stage::kUwb)].mean_position_m(), 1e-4);
  EXPECT_LT(errors[static_cast<std::size_t>(Stage::kOdometry)].mean_position_m(), 1e-9) << "exact increments, known start";
}

TEST(RelativeEstimator, WithStructuredRangeErrorsEachStageImprovesOnTheLast) {
  // Issue 11's error model (no outliers), 150 s: the window must beat single epochs and the
  // filter the window, as in the paper's tables (the system test checks the figures).
  const auto errors = run(uwb_sensor::UwbErrorParams{}, 1500, 200, 7);
  const auto mean = [&](Stage s) { return errors[static_cast<std::size_t>(s)].mean_position_m(); };
  const auto heading = [&](Stage s) { return errors[static_cast<std::size_t>(s)].mean_heading_deg(); };
  EXPECT_GT(mean(Stage::kUwb), mean(Stage::kWindow));
  EXPECT_GT(mean(Stage::kWindow), mean(Stage::kPf));
  EXPECT_GT(heading(Stage::kUwb), heading(Stage::kWindow));
  EXPECT_GT(heading(Stage::kWindow), heading(Stage::kPf));
  // The 0.9 x baseline is checked on the whole system (odometry noise, the paper's routes).
  EXPECT_LT(mean(Stage::kPf), mean(Stage::kPfBaseline));
  std::printf("mean position / heading error, 2 peers, 130 s: uwb %.3f m / %.2f deg, window %.3f / %.2f, pf %.3f / %.2f, "
              "pf_baseline %.3f / %.2f, odometry %.3f / %.2f\n",
              mean(Stage::kUwb), heading(Stage::kUwb), mean(Stage::kWindow), heading(Stage::kWindow), mean(Stage::kPf),
              heading(Stage::kPf), mean(Stage::kPfBaseline), heading(Stage::kPfBaseline), mean(Stage::kOdometry),
              heading(Stage::kOdometry));
}

TEST(RelativeEstimator, EveryStageReportsACovarianceTheErrorsStayWithin) {
  // Issue 27: issue 11's structured range errors, 150 s, 2 peers. A consistent estimate leaves
  // ~0.3-0.5 % outside its 3 sigma; 2 % allows for the heavier tails of biases that last seconds.
  // The filters' particles agree to a few cm (every epoch's measurement weighed as new) while the
  // range errors behind it last seconds: they report the covariance of their error under those
  // errors (FilterErrorCovariance), not their spread.
  const auto errors = run(uwb_sensor::UwbErrorParams{}, 1500, 200, 7);
  for (const Stage s : {Stage::kUwb, Stage::kWindow, Stage::kPf, Stage::kPfBaseline, Stage::kOdometry}) {
    const Errors& e = errors[static_cast<std::size_t>(s)];
    SCOPED_TRACE(stage_name(s));
    EXPECT_LE(e.overconfident_fraction(), 0.02);
    std::printf("%s: %.2f %% over-confident, mean d^2 %.2f (2 if consistent)\n", stage_name(s),
                100.0 * e.overconfident_fraction(), e.mean_d2());
  }
  // Not so wide that it says nothing: the single-epoch fit's is consistent on average, and the
  // filters' is not the window's (they do average the part of the errors that changes).
  // (1.53 without the per-node bias term, uncertainty.node_bias_std_m: this error model has no
  // node biases, so the term's 0.06 m makes the fit under-confident here: 0.92.)
  EXPECT_GT(errors[static_cast<std::size_t>(Stage::kUwb)].mean_d2(), 0.8);
  for (const Stage s : {Stage::kPf, Stage::kPfBaseline}) {
    EXPECT_GT(errors[static_cast<std::size_t>(s)].mean_d2(), 0.5) << stage_name(s);
  }
}

/// tc's issue-27 terms off (what it reported before them: its information at its minimum, scaled
/// by the uwb stage's fix check).
RelativeEstimatorParams tc_terms_off() {
  RelativeEstimatorParams p;
  p.tc.node_bias_term = false;
  p.tc.bearing_curvature_term = false;
  p.tc.innovation_check = false;
  p.tc.jump_check_epochs = 0;
  return p;
}

TEST(RelativeEstimator, SameSeedSameEstimates) {
  const auto a = run(uwb_sensor::UwbErrorParams{}, 200, 0, 3);
  const auto b = run(uwb_sensor::UwbErrorParams{}, 200, 0, 3);
  for (std::size_t s = 0; s < kStageCount; ++s) {
    EXPECT_EQ(a[s].position_m, b[s].position_m) << stage_name(static_cast<Stage>(s));
    EXPECT_EQ(a[s].heading_deg, b[s].heading_deg) << stage_name(static_cast<Stage>(s));
  }
}

/// Every epoch's result of three circling peers (structured range errors, the links between them,
/// peer 3's frames missing for 3 s from t = 10 s: its filters and tc restart) with `threads`.
std::vector<EpochResult> run_with_threads(int threads, EstimatorCounts& counts) {
  const model::UwbArray array = square_array(0.5);
  std::vector<CirclingPeer> truth{{2, {4.0, 0.0, M_PI / 2}}, {3, {-5.0, 0.0, -M_PI / 2}}, {4, {0.0, 6.0, M_PI}, {0.2, 0.04}}};
  const uwb_sensor::UwbErrorParams noise;
  RandomEngine white(derive_seed(5, "white"));
  RandomEngine nlos(derive_seed(5, "nlos"));
  std::vector<PeerSetup> setups;
  std::vector<uwb_sensor::PairErrors> errors;
  for (std::size_t k = 0; k < truth.size() + 3; ++k) {  // each peer's pair, then the three links
    errors.emplace_back(4, 4, 0.0, noise, RandomEngine(derive_seed(5, "bias" + std::to_string(k))),
                        RandomEngine(derive_seed(5, "common" + std::to_string(k))));
  }
  for (const CirclingPeer& p : truth) {
    setups.push_back(PeerSetup{p.id, array, std::nullopt});
  }
  RelativeEstimatorParams params;
  params.threads = threads;
  RelativeEstimator estimator(array, setups, params, 5);
  std::vector<EpochResult> out;
  for (int e = 1; e <= 250; ++e) {
    const double t = e * kEpochS;
    std::vector<PeerEpoch> inputs;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      truth[k].pose = model::integrate_exact(truth[k].pose, truth[k].twist, kEpochS);
    }
    for (std::size_t k = 0; k < errors.size(); ++k) {
      errors[k].advance_to(t);
    }
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const Eigen::MatrixXd d = model::array_ranges(array, model::Pose2{}, array, truth[k].pose);
      std::optional<Eigen::MatrixXd> ranges =
          uwb_sensor::measure_ranges(d, errors[k].link_bias_m(true), errors[k].common_m(), noise, white, nlos);
      if (k == 1 && t > 10.0 && t < 13.0) {
        ranges.reset();
      }
      inputs.push_back(PeerEpoch{increment_of(truth[k].twist), ranges});
    }
    std::vector<std::optional<Eigen::MatrixXd>> links;
    std::size_t stream = truth.size();
    for (const PeerLink& link : estimator.links()) {
      const Eigen::MatrixXd d = model::array_ranges(array, truth[link.first].pose, array, truth[link.second].pose);
      links.push_back(uwb_sensor::measure_ranges(d, errors[stream].link_bias_m(true), errors[stream].common_m(), noise,
                                                 white, nlos));
      ++stream;
    }
    out.push_back(estimator.step(t, model::Pose2{}, inputs, links));
  }
  counts = estimator.counts();
  return out;
}

/// The bytes of a double (NaN equals NaN, 0.0 differs from -0.0): "bit for bit".
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(RelativeEstimator, TheEstimatesDoNotDependOnTheNumberOfThreads) {
  EstimatorCounts one_counts;
  const std::vector<EpochResult> one = run_with_threads(1, one_counts);
  for (int threads : {2, 3, 8}) {
    EstimatorCounts counts;
    const std::vector<EpochResult> many = run_with_threads(threads, counts);
    ASSERT_EQ(many.size(), one.size());
    int differences = 0;
    for (std::size_t e = 0; e < one.size(); ++e) {
      for (std::size_t k = 0; k < one[e].peers.size(); ++k) {
        const PeerResult& a = one[e].peers[k];
        const PeerResult& b = many[e].peers[k];
        EXPECT_EQ(a.had_ranges, b.had_ranges);
        EXPECT_EQ(a.uwb_status, b.uwb_status);
        EXPECT_EQ(a.uwb_reason, b.uwb_reason);
        for (std::size_t s = 0; s < kStageCount; ++s) {
          const StageEstimate& x = a.stages[s];
          const StageEstimate& y = b.stages[s];
          bool same = x.valid == y.valid && same_bits(x.pose.x, y.pose.x) && same_bits(x.pose.y, y.pose.y) &&
                      same_bits(x.pose.theta, y.pose.theta);
          for (int i = 0; i < 9; ++i) {
            same = same && same_bits(x.covariance(i / 3, i % 3), y.covariance(i / 3, i % 3));
          }
          if (!same && ++differences <= 5) {
            ADD_FAILURE() << threads << " threads: epoch " << e << " peer " << k << " stage "
                          << stage_name(static_cast<Stage>(s)) << " differs from 1 thread's";
          }
        }
      }
    }
    EXPECT_EQ(differences, 0) << threads << " threads";
    EXPECT_EQ(counts.epochs, one_counts.epochs);
    EXPECT_EQ(counts.frames_missing, one_counts.frames_missing);
    EXPECT_EQ(counts.window_not_converged, one_counts.window_not_converged);
    EXPECT_EQ(counts.filter_restarts, one_counts.filter_restarts);
    EXPECT_EQ(counts.baseline_restarts, one_counts.baseline_restarts);
  }
  // The run exercises what the threads share out: every stage valid at the end, frames missed.
  EXPECT_EQ(one_counts.frames_missing, 29u);
  for (std::size_t s = 0; s < kStageCount; ++s) {
    EXPECT_TRUE(one.back().peers[1].stages[s].valid) << stage_name(static_cast<Stage>(s));
  }
}

Eigen::MatrixXd exact_ranges(const model::Pose2& peer) {
  return model::array_ranges(square_array(0.5), model::Pose2{}, square_array(0.5), peer);
}

const StageEstimate& stage(const EpochResult& r, std::size_t peer, Stage s) { return r.peers[peer].stages[static_cast<std::size_t>(s)]; }

TEST(RelativeEstimator, APeerNotMeasuredYetBlocksNoOtherAndIsPlacedByItsFirstFix) {
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 1.0, 0.3};
  const model::Pose2 p3{-3.0, 2.0, -1.0};
  RelativeEstimator estimator(array, {PeerSetup{2, array, std::nullopt}, PeerSetup{3, array, std::nullopt}},
                              RelativeEstimatorParams{}, 1);
  EpochResult r;
  for (int e = 1; e <= 40; ++e) {  // peer 3 unseen for 4 s, longer than the window
    r = estimator.step(0.1 * e, {}, {PeerEpoch{{}, exact_ranges(p2)}, PeerEpoch{{}, std::nullopt}});
  }
  EXPECT_EQ(r.peers[1].uwb_reason, "no frame");
  for (Stage s : {Stage::kUwb, Stage::kWindow, Stage::kPf, Stage::kPfBaseline, Stage::kOdometry}) {
    EXPECT_TRUE(stage(r, 0, s).valid) << "peer 2 " << stage_name(s) << ": not held back by peer 3";
  }
  for (Stage s : {Stage::kUwb, Stage::kWindow, Stage::kPf, Stage::kPfBaseline, Stage::kOdometry}) {
    EXPECT_FALSE(stage(r, 1, s).valid) << "peer 3 " << stage_name(s) << ": never measured";
  }
  EXPECT_EQ(estimator.counts().frames_missing, 40u);

  r = estimator.step(4.1, {}, {PeerEpoch{{}, exact_ranges(p2)}, PeerEpoch{{}, exact_ranges(p3)}});
  for (std::size_t k = 0; k < 2; ++k) {
    for (Stage s : {Stage::kUwb, Stage::kWindow, Stage::kPf, Stage::kPfBaseline, Stage::kOdometry}) {
      EXPECT_TRUE(stage(r, k, s).valid) << "peer " << k << " " << stage_name(s);
    }
  }
  const model::Pose2& w3 = stage(r, 1, Stage::kWindow).pose;
  EXPECT_NEAR(w3.x, p3.x, 1e-3) << "placed by its first fix, not dragged from a guess";
  EXPECT_NEAR(w3.y, p3.y, 1e-3);
  EXPECT_NEAR(w3.theta, p3.theta, 1e-3);
  EXPECT_NEAR(stage(r, 1, Stage::kOdometry).pose.x, p3.x, 1e-6) << "no known start: odometry starts at the first fix";
}

TEST(RelativeEstimator, AfterAGapInTheFramesTheWindowLapsesAndTheFiltersRestartAroundTheNextFix) {
  // Peer 2 stands at p2; for 4 s (longer than the window, 3 s) no frames come while its odometry
  // reports a turn that never happens (a biased wheel): the dead-reckoned clouds drift away.
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 1.0, 0.3};
  RelativeEstimator estimator(array, {PeerSetup{2, array, p2}}, RelativeEstimatorParams{}, 1);
  EpochResult r;
  double t = 0.0;
  for (int e = 0; e < 30; ++e) {
    r = estimator.step(t += 0.1, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  }
  const model::Pose2 phantom_turn{0.02, 0.0, 0.02};  // per epoch: 0.2 m/s and 0.2 rad/s that are not there
  for (int e = 0; e < 40; ++e) {
    r = estimator.step(t += 0.1, {}, {PeerEpoch{phantom_turn, std::nullopt}});
  }
  EXPECT_FALSE(stage(r, 0, Stage::kWindow).valid) << "no edge left in the window";
  EXPECT_GT(std::hypot(stage(r, 0, Stage::kPf).pose.x - p2.x, stage(r, 0, Stage::kPf).pose.y - p2.y), 0.5)
      << "the filter drifted on the odometry alone";
  r = estimator.step(t += 0.1, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  for (Stage s : {Stage::kWindow, Stage::kPf, Stage::kPfBaseline}) {
    const model::Pose2& p = stage(r, 0, s).pose;
    EXPECT_TRUE(stage(r, 0, s).valid) << stage_name(s);
    EXPECT_LT(std::hypot(p.x - p2.x, p.y - p2.y), 0.35) << stage_name(s) << ": back at the fix at once";
    EXPECT_LT(std::abs(wrap_angle(p.theta - p2.theta)), 0.15) << stage_name(s);
  }
}

TEST(RelativeEstimator, TheUwbStageCoversRangeBiasesPerNode) {
  // Issue 27, experiment 1-b: every link of a node shares its bias (a board in view of some nodes,
  // an antenna's delay); the fit turns it into heading. 40 peers at random poses, each for 20
  // epochs with its own node biases (std 0.1 m, told to the estimator) and 0.02 m white noise:
  // the uwb stage's heading stays within its 3 sigma; without the node term it would not.
  const model::UwbArray array = square_array(0.5);
  RelativeEstimatorParams params;
  params.uncertainty.node_bias_std_m = 0.1;
  RandomEngine random(3);
  int count = 0;
  int outside = 0;
  for (int run = 0; run < 40; ++run) {
    const double bearing = 2.0 * M_PI * uniform01(random);
    const model::Pose2 peer{5.0 * std::cos(bearing), 5.0 * std::sin(bearing), wrap_angle(2.0 * M_PI * uniform01(random))};
    Eigen::VectorXd own(4);
    Eigen::VectorXd other(4);
    for (int n = 0; n < 4; ++n) {
      own(n) = 0.1 * standard_normal(random);
      other(n) = 0.1 * standard_normal(random);
    }
    RelativeEstimator estimator(array, {PeerSetup{2, array, peer}}, params, 1);
    for (int e = 1; e <= 20; ++e) {
      Eigen::MatrixXd ranges = exact_ranges(peer);
      for (Eigen::Index k = 0; k < 4; ++k) {
        for (Eigen::Index l = 0; l < 4; ++l) {
          ranges(k, l) += own(k) + other(l) + 0.02 * standard_normal(random);
        }
      }
      const EpochResult r = estimator.step(0.1 * e, {}, {PeerEpoch{{}, ranges}});
      const StageEstimate& uwb = stage(r, 0, Stage::kUwb);
      if (uwb.valid) {
        ++count;
        const double e_theta = wrap_angle(uwb.pose.theta - peer.theta);
        outside += e_theta * e_theta > 9.0 * uwb.covariance(2, 2) ? 1 : 0;
      }
    }
  }
  ASSERT_GT(count, 700);
  EXPECT_LT(static_cast<double>(outside) / count, 0.02) << outside << " of " << count;
}

/// A peer circling this robot for `epochs` epochs; the links of this robot's node 0 carry a bias
/// 0.3 m x sin(2 pi t / 30 s), those of the opposite node 2 its negative, beyond the configured
/// node term (0.06 m) (a board coming into view and going,
/// a node shadowed as the peer turns), plus 0.02 m white noise. Per epoch: the uwb, pf and
/// pf_baseline estimates, and the truth.
struct BiasRun {
  std::vector<EpochResult> results;
  std::vector<model::Pose2> truth;
};
BiasRun run_changing_node_bias(const RelativeEstimatorParams& params, int epochs) {
  CirclingPeer peer{2, {4.0, 0.0, M_PI / 2}};
  RelativeEstimator estimator(square_array(0.5), {PeerSetup{2, square_array(0.5), peer.pose}}, params, 1);
  RandomEngine random(5);
  BiasRun out;
  for (int e = 1; e <= epochs; ++e) {
    const double t = e * kEpochS;
    peer.pose = model::integrate_exact(peer.pose, peer.twist, kEpochS);
    out.truth.push_back(peer.pose);
    Eigen::MatrixXd ranges = exact_ranges(peer.pose);
    ranges.row(0).array() += 0.3 * std::sin(2.0 * M_PI * t / 30.0);
    ranges.row(2).array() -= 0.3 * std::sin(2.0 * M_PI * t / 30.0);
    for (Eigen::Index k = 0; k < ranges.size(); ++k) {
      ranges(k) += 0.02 * standard_normal(random);
    }
    out.results.push_back(estimator.step(t, model::Pose2{}, {PeerEpoch{increment_of(peer.twist), ranges}}));
  }
  return out;
}

TEST(RelativeEstimator, TheUwbStageWidensWhenItsFixesDisagreeWithTheirDeadReckonedPast) {
  // Issue 27: an error that one epoch's residuals cannot show (a node's bias, here larger than the
  // configured node term and changing) is seen by the uwb stage's check of each fix against the
  // fix of 20 s ago carried forward by odometry (FixTrackCheck), which widens what it reports. The
  // filters compare their estimates with the model's covariance, not the widened one: their
  // outputs do not change.
  RelativeEstimatorParams off;
  off.uncertainty.fix_check_lag_s = 0.0;
  const BiasRun checked = run_changing_node_bias(RelativeEstimatorParams{}, 1200);
  const BiasRun unchecked = run_changing_node_bias(off, 1200);
  const std::vector<EpochResult>& with = checked.results;
  const std::vector<EpochResult>& without = unchecked.results;
  int count = 0;
  int outside_with = 0;
  int outside_without = 0;
  for (std::size_t e = 300; e < with.size(); ++e) {
    const StageEstimate& a = stage(with[e], 0, Stage::kUwb);
    const StageEstimate& b = stage(without[e], 0, Stage::kUwb);
    ASSERT_EQ(a.valid, b.valid);
    if (!a.valid) {
      continue;
    }
    ASSERT_TRUE(a.pose.x == b.pose.x && a.pose.y == b.pose.y && a.pose.theta == b.pose.theta);  // no estimate changes
    const model::Pose2& truth = checked.truth[e];
    Errors ea;
    Errors eb;
    ea.add(a.pose, truth, a.covariance);
    eb.add(b.pose, truth, b.covariance);
    ++count;
    outside_with += ea.overconfident;
    outside_without += eb.overconfident;
    for (Stage s : {Stage::kPf, Stage::kPfBaseline}) {
      const model::Pose2& p = stage(with[e], 0, s).pose;
      const model::Pose2& q = stage(without[e], 0, s).pose;
      ASSERT_TRUE(p.x == q.x && p.y == q.y && p.theta == q.theta) << "epoch " << e;
      ASSERT_EQ(stage(with[e], 0, s).covariance, stage(without[e], 0, s).covariance) << "epoch " << e;
    }
  }
  EXPECT_GT(outside_without, count / 5) << outside_without << " of " << count;  // the case is one
  EXPECT_LT(outside_with, outside_without / 3) << outside_with << " vs " << outside_without << " of " << count;
}

TEST(RelativeEstimator, TheTcStageReportsACovarianceTheErrorsStayWithin) {
  // Issue 27: a node's range bias 5 x the configured node term and changing (as above). tc
  // models white noise, link biases and a common mode: its information at its minimum alone is
  // over-confident. With the uwb stage's consider terms (node biases, the bearing's second order)
  // and its checks against the fixes and against its own past (tc.node_bias_term,
  // bearing_curvature_term, innovation_check, jump_check_epochs) it is within its bound. Only the
  // covariance changes, not the estimate.
  const BiasRun checked = run_changing_node_bias(RelativeEstimatorParams{}, 1200);
  const BiasRun unchecked = run_changing_node_bias(tc_terms_off(), 1200);
  Errors with;
  Errors without;
  for (std::size_t e = 300; e < checked.results.size(); ++e) {
    const StageEstimate& a = stage(checked.results[e], 0, Stage::kTc);
    const StageEstimate& b = stage(unchecked.results[e], 0, Stage::kTc);
    ASSERT_EQ(a.valid, b.valid);
    if (!a.valid) {
      continue;
    }
    ASSERT_TRUE(a.pose.x == b.pose.x && a.pose.y == b.pose.y && a.pose.theta == b.pose.theta);  // no estimate changes
    with.add(a.pose, checked.truth[e], a.covariance);
    without.add(b.pose, checked.truth[e], b.covariance);
  }
  std::printf("tc: %.2f %% over-confident, mean d^2 %.2f; without its terms %.2f %%, %.2f\n",
              100.0 * with.overconfident_fraction(), with.mean_d2(), 100.0 * without.overconfident_fraction(), without.mean_d2());
  ASSERT_GT(with.count, 800);
  EXPECT_GT(without.overconfident_fraction(), 0.3);  // the case is one (47 %)
  // 13.6 %: the fixes share this bias (the innovation check cannot see it) and the fix check's
  // scale is sized for the fixes' covariance, not tc's; the shipped scenarios' figures are in
  // docs/results/consistency.md.
  EXPECT_LT(with.overconfident_fraction(), without.overconfident_fraction() / 3);
}

TEST(RelativeEstimator, TheOdometryStageSaysSoWhenItsDeadReckoningDriftsBeyondItsCovariance) {
  // Issue 27: the odometry stage propagates white per-epoch noise (its covariance grows as
  // sqrt(t)); a wheel slip drifts as t. The peer's odometry reports its turn rate 10 % low: after
  // a few minutes the dead reckoning is metres off, beyond its covariance. Its check against the
  // eq. (1) fixes (InnovationMonitor, what neither covariance explains) widens what it reports.
  CirclingPeer peer{2, {4.0, 0.0, M_PI / 2}};
  RelativeEstimator estimator(square_array(0.5), {PeerSetup{2, square_array(0.5), peer.pose}}, RelativeEstimatorParams{}, 1);
  RandomEngine random(7);
  const model::Twist reported{peer.twist.v, 0.9 * peer.twist.omega};
  int count = 0;
  int outside = 0;
  double worst_error_m = 0.0;
  for (int e = 1; e <= 3000; ++e) {
    const double t = e * kEpochS;
    peer.pose = model::integrate_exact(peer.pose, peer.twist, kEpochS);
    Eigen::MatrixXd ranges = exact_ranges(peer.pose);
    for (Eigen::Index k = 0; k < ranges.size(); ++k) {
      ranges(k) += 0.03 * standard_normal(random);
    }
    const EpochResult r = estimator.step(t, model::Pose2{}, {PeerEpoch{increment_of(reported), ranges}});
    const StageEstimate& odometry = stage(r, 0, Stage::kOdometry);
    ASSERT_TRUE(odometry.valid);
    if (e < 1500) {
      continue;
    }
    worst_error_m = std::max(worst_error_m, std::hypot(odometry.pose.x - peer.pose.x, odometry.pose.y - peer.pose.y));
    Errors reported_errors;
    reported_errors.add(odometry.pose, peer.pose, odometry.covariance);
    ++count;
    outside += reported_errors.overconfident;
  }
  EXPECT_GT(worst_error_m, 3.0);  // the case is one: the dead reckoning drifted metres
  EXPECT_LT(outside, count / 100) << outside << " of " << count;
}

TEST(RelativeEstimator, AFilterThatLostItsPeerIsRestartedByItsCheckAgainstTheFixes) {
  // The peer is at p2 for 3 s, then its ranges say p2b, 6 m away, while no odometry moved it (a
  // filter converged on a wrong pose): the range-weighted baseline's particles move only by their
  // odometry noise and would stay 6 m off for minutes; its check against the eq. (1) fixes
  // restarts it at the fixes' median.
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 1.0, 0.3};
  const model::Pose2 p2b{1.0, 6.0, -0.5};
  RelativeEstimator estimator(array, {PeerSetup{2, array, p2}}, RelativeEstimatorParams{}, 1);
  EpochResult r;
  double t = 0.0;
  for (int e = 0; e < 30; ++e) {
    r = estimator.step(t += 0.1, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  }
  EXPECT_EQ(estimator.counts().baseline_restarts, 0U);
  for (int e = 0; e < 50; ++e) {
    r = estimator.step(t += 0.1, {}, {PeerEpoch{{}, exact_ranges(p2b)}});
  }
  EXPECT_GE(estimator.counts().baseline_restarts, 1U);
  const StageEstimate& baseline = stage(r, 0, Stage::kPfBaseline);
  EXPECT_TRUE(baseline.valid);
  EXPECT_LT(std::hypot(baseline.pose.x - p2b.x, baseline.pose.y - p2b.y), 0.5) << "restarted at the fixes";
  EXPECT_LT(std::abs(wrap_angle(baseline.pose.theta - p2b.theta)), 0.2);
}

TEST(RelativeEstimator, EveryStageFollowsAPeerWhileThisRobotMovesToo) {
  // Both robots drive circles (noise-free): the own increment must be inverted on every stage.
  const model::UwbArray array = square_array(0.5);
  model::Pose2 own{0.0, 0.0, 0.0};
  model::Pose2 peer{4.0, 2.0, 1.0};
  const model::Twist own_twist{0.2, 0.1};
  const model::Twist peer_twist{0.15, -0.05};
  RelativeEstimator estimator(array, {PeerSetup{2, array, model::between(own, peer)}}, RelativeEstimatorParams{}, 1);
  EpochResult r;
  for (int e = 1; e <= 300; ++e) {
    own = model::integrate_exact(own, own_twist, kEpochS);
    peer = model::integrate_exact(peer, peer_twist, kEpochS);
    r = estimator.step(e * kEpochS, increment_of(own_twist),
                       {PeerEpoch{increment_of(peer_twist), model::array_ranges(array, own, array, peer)}});
  }
  const model::Pose2 truth = model::between(own, peer);
  for (Stage s : {Stage::kUwb, Stage::kWindow, Stage::kPf, Stage::kPfBaseline, Stage::kOdometry}) {
    const model::Pose2& p = stage(r, 0, s).pose;
    EXPECT_LT(std::hypot(p.x - truth.x, p.y - truth.y), 0.1) << stage_name(s);
    EXPECT_LT(std::abs(wrap_angle(p.theta - truth.theta)), 0.03) << stage_name(s);
  }
  EXPECT_LT(std::hypot(stage(r, 0, Stage::kOdometry).pose.x - truth.x, stage(r, 0, Stage::kOdometry).pose.y - truth.y), 1e-9);
}

TEST(RelativeEstimator, RangesBetweenPeersEnterTheWindowAsLinks) {
  // Noise-free links that contradict this robot's own measurements pull the window: proof that
  // they are edges of the graph. Peer 3 is where the own ranges say; the link says 3 is 1 m
  // further along x as seen from 2 (same heading as 2 here), so the window moves 3 towards it.
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 0.0, 0.0};
  const model::Pose2 p3{4.0, 3.0, 0.0};
  RelativeEstimator estimator(array, {PeerSetup{2, array, p2}, PeerSetup{3, array, p3}}, RelativeEstimatorParams{}, 1);
  ASSERT_EQ(estimator.links().size(), 1u);
  EXPECT_EQ(estimator.links()[0].first, 0u);
  EXPECT_EQ(estimator.links()[0].second, 1u);
  const Eigen::MatrixXd link = model::array_ranges(array, p2, array, model::Pose2{5.0, 3.0, 0.0});
  EpochResult without;
  EpochResult with;
  RelativeEstimator plain(array, {PeerSetup{2, array, p2}, PeerSetup{3, array, p3}}, RelativeEstimatorParams{}, 1);
  for (int e = 1; e <= 5; ++e) {
    const std::vector<PeerEpoch> inputs{PeerEpoch{{}, exact_ranges(p2)}, PeerEpoch{{}, exact_ranges(p3)}};
    with = estimator.step(0.1 * e, {}, inputs, {link});
    without = plain.step(0.1 * e, {}, inputs, {std::nullopt});
  }
  const auto window_x = [](const EpochResult& r) { return r.peers[1].stages[static_cast<std::size_t>(Stage::kWindow)].pose.x; };
  EXPECT_NEAR(window_x(without), 4.0, 1e-6) << "no link: the own measurements alone";
  EXPECT_GT(window_x(with), 4.2) << "the link pulls peer 3 towards x = 5";
  EXPECT_LT(window_x(with), 4.8);
  EXPECT_EQ(estimator.link_tracker_counts(0).ok, 5u);
  EXPECT_THROW(estimator.step(0.6, {}, {PeerEpoch{{}, exact_ranges(p2)}, PeerEpoch{{}, exact_ranges(p3)}}, {link, link}),
               std::invalid_argument);
}

TEST(RelativeEstimator, BadFramesAreRejectedAndUsedByNoStage) {
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 1.0, 0.3};
  RelativeEstimator estimator(array, {PeerSetup{2, array, p2}}, RelativeEstimatorParams{}, 1);
  estimator.step(0.1, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  const model::Pose2 before = estimator.step(0.2, {}, {PeerEpoch{{}, exact_ranges(p2)}}).peers[0].stages[static_cast<std::size_t>(Stage::kPf)].pose;

  Eigen::MatrixXd nan = exact_ranges(p2);
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd negative = exact_ranges(p2);
  negative(0, 0) = -0.5;
  const Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Constant(4, 3, 4.0);
  double t = 0.2;
  for (const Eigen::MatrixXd& bad : {nan, negative, wrong_shape}) {
    t += 0.1;
    const EpochResult r = estimator.step(t, {}, {PeerEpoch{{}, bad}});
    EXPECT_EQ(r.peers[0].uwb_status, TrackStatus::kRejected);
    EXPECT_FALSE(r.peers[0].uwb_reason.empty());
    EXPECT_FALSE(r.peers[0].stages[static_cast<std::size_t>(Stage::kUwb)].valid);
    for (Stage s : {Stage::kPf, Stage::kPfBaseline, Stage::kWindow}) {
      const model::Pose2& p = r.peers[0].stages[static_cast<std::size_t>(s)].pose;
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta)) << stage_name(s);
      EXPECT_NEAR(p.x, before.x, 0.2) << stage_name(s) << ": a bad frame must not move the estimate";
    }
  }
  EXPECT_EQ(estimator.tracker_counts(0).rejected, 3u);
}

TEST(RelativeEstimator, BadCallsThrowAndChangeNothing) {
  const model::UwbArray array = square_array(0.5);
  const model::Pose2 p2{4.0, 1.0, 0.3};
  RelativeEstimator estimator(array, {PeerSetup{2, array, p2}}, RelativeEstimatorParams{}, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(estimator.step(0.1, {}, {}), std::invalid_argument);
  EXPECT_THROW(estimator.step(0.1, model::Pose2{nan, 0, 0}, {PeerEpoch{{}, exact_ranges(p2)}}), std::invalid_argument);
  EXPECT_THROW(estimator.step(0.1, {}, {PeerEpoch{model::Pose2{0, 0, nan}, exact_ranges(p2)}}), std::invalid_argument);
  EXPECT_THROW(estimator.step(nan, {}, {PeerEpoch{{}, exact_ranges(p2)}}), std::invalid_argument);
  EXPECT_EQ(estimator.counts().epochs, 0u);
  EXPECT_EQ(estimator.tracker_counts(0).ok + estimator.tracker_counts(0).rejected, 0u);
  const EpochResult r = estimator.step(0.1, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  EXPECT_NEAR(r.peers[0].stages[static_cast<std::size_t>(Stage::kOdometry)].pose.x, p2.x, 1e-12)
      << "the odometry stage was not moved by a refused call";
  // Time going back: refused before anything moves (odometry, window and filters included).
  EXPECT_THROW(estimator.step(0.05, {}, {PeerEpoch{model::Pose2{1.0, 0.0, 0.0}, exact_ranges(p2)}}), std::invalid_argument);
  EXPECT_EQ(estimator.counts().epochs, 1u);
  const EpochResult again = estimator.step(0.2, {}, {PeerEpoch{{}, exact_ranges(p2)}});
  EXPECT_NEAR(again.peers[0].stages[static_cast<std::size_t>(Stage::kOdometry)].pose.x, p2.x, 1e-12);
}

std::string construction_error(const model::UwbArray& own, std::vector<PeerSetup> peers, RelativeEstimatorParams params) {
  try {
    RelativeEstimator(own, std::move(peers), params, 1);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RelativeEstimator, BadSetUpsNameTheProblem) {
  const model::UwbArray array = square_array(0.5);
  model::UwbArray two_nodes;
  two_nodes.nodes_m = {{0.2, 0.0}, {-0.2, 0.0}};
  model::UwbArray coincident = array;
  coincident.nodes_m[3] = coincident.nodes_m[0];
  EXPECT_NE(construction_error(array, {}, {}).find("peers"), std::string::npos);
  EXPECT_NE(construction_error(array, {PeerSetup{2, array, {}}, PeerSetup{2, array, {}}}, {}).find("robot 2 is listed twice"),
            std::string::npos);
  EXPECT_NE(construction_error(two_nodes, {PeerSetup{2, array, {}}}, {}).find("own_array"), std::string::npos);
  EXPECT_NE(construction_error(array, {PeerSetup{2, coincident, {}}}, {}).find("peer 2 array"), std::string::npos);
  RelativeEstimatorParams short_window;
  short_window.window_epochs = 1;
  EXPECT_NE(construction_error(array, {PeerSetup{2, array, {}}}, short_window).find("window_epochs"), std::string::npos);
  RelativeEstimatorParams no_particles;
  no_particles.pf.num_particles = 0;
  EXPECT_NE(construction_error(array, {PeerSetup{2, array, {}}}, no_particles).find("pf.num_particles"), std::string::npos);
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
