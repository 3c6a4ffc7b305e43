#include "components/pf_estimator/particle_filter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "common/random.hpp"

namespace robodds::pf_estimator {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = kPi / 180.0;

// Paper 1: measurement variance 2.28 m^2 per axis.
const double kFixStd = std::sqrt(2.28);

// The paper's set-up, which these tests were written for: uniform particles over a 20 m x 20 m
// area and the sensor's std sqrt(2.28). Set explicitly: the struct's defaults are the scenarios'
// (first_fix, a 100 m field, 1.51 m) since the parameter table became the one source.
PfParams uniform_area_params() {
  PfParams params;
  params.init_mode = InitMode::kUniformArea;
  params.init_area_min_x = -10.0;
  params.init_area_max_x = 10.0;
  params.init_area_min_y = -10.0;
  params.init_area_max_y = 10.0;
  params.measurement_std_m = kFixStd;
  params.init_fix_std_m = kFixStd;
  return params;
}

PfParams first_fix_params() {
  PfParams params = uniform_area_params();
  params.init_mode = InitMode::kFirstFix;
  return params;
}

ParticleSet particles_at(Eigen::Index count, double x, double y, double theta) {
  ParticleSet particles;
  particles.resize(count);
  particles.x.setConstant(x);
  particles.y.setConstant(y);
  particles.theta.setConstant(theta);
  return particles;
}

bool same_state(const ParticleFilter& a, const ParticleFilter& b) {
  return (a.particles().x == b.particles().x).all() && (a.particles().y == b.particles().y).all() &&
         (a.particles().theta == b.particles().theta).all() && (a.weights() == b.weights()).all();
}

// ---- closed-loop-free simulation of a robot with noisy odometry and position fixes ----

struct SimulationConfig {
  double duration_s = 60.0;
  double odom_dt_s = 0.02;  // 50 Hz odometry
  int odom_steps_per_fix = 5;  // 10 Hz fixes
  double odom_v_noise_mps = 0.05;
  double odom_omega_noise_radps = 0.02;
  double fix_std_m = kFixStd;  // what the simulated sensor does (the filter may assume otherwise)
  model::Pose2 start{5.0, -3.0, 2.0};
};

struct SimulationResult {
  double estimate_rmse_m = 0.0;  // over all fixes, after the update
  double fix_rmse_m = 0.0;       // raw fixes against the truth
  double final_heading_error_rad = 0.0;
  std::vector<Eigen::Vector3d> estimates;
};

// Speed around 1 m/s and a turn rate that changes sign: the robot drives S-curves.
model::Twist true_twist(double t_s) {
  return {1.0 + 0.2 * std::sin(0.3 * t_s), 0.1 + 0.3 * std::sin(0.15 * t_s)};
}

SimulationResult simulate(ParticleFilter& filter, const SimulationConfig& config,
                          std::uint64_t world_seed) {
  RandomEngine world(derive_seed(world_seed, "world"));
  model::Pose2 truth = config.start;
  const int steps = static_cast<int>(std::lround(config.duration_s / config.odom_dt_s));
  double estimate_sq = 0.0;
  double fix_sq = 0.0;
  int fixes = 0;
  SimulationResult result;
  for (int step = 1; step <= steps; ++step) {
    const model::Twist twist = true_twist(step * config.odom_dt_s);
    truth = model::integrate_exact(truth, twist, config.odom_dt_s);
    filter.predict(twist.v + config.odom_v_noise_mps * standard_normal(world),
                   twist.omega + config.odom_omega_noise_radps * standard_normal(world),
                   config.odom_dt_s);
    if (step % config.odom_steps_per_fix != 0) {
      continue;
    }
    const double z_x = truth.x + config.fix_std_m * standard_normal(world);
    const double z_y = truth.y + config.fix_std_m * standard_normal(world);
    filter.update(z_x, z_y);
    const Eigen::Vector3d mean = filter.estimate().mean;
    result.estimates.push_back(mean);
    estimate_sq += std::pow(mean.x() - truth.x, 2) + std::pow(mean.y() - truth.y, 2);
    fix_sq += std::pow(z_x - truth.x, 2) + std::pow(z_y - truth.y, 2);
    ++fixes;
    result.final_heading_error_rad = std::abs(wrap_angle(mean.z() - truth.theta));
  }
  result.estimate_rmse_m = std::sqrt(estimate_sq / fixes);
  result.fix_rmse_m = std::sqrt(fix_sq / fixes);
  return result;
}

// ---- construction and initialisation ----

TEST(ParticleFilter, RejectsInvalidParams) {
  PfParams params;
  params.num_particles = 0;
  EXPECT_THROW(ParticleFilter(params, 1), std::invalid_argument);
}

TEST(ParticleFilter, UniformAreaModeStartsInsideTheAreaWithUniformHeading) {
  PfParams params = uniform_area_params();
  params.init_area_min_x = 2.0;
  params.init_area_max_x = 4.0;
  params.init_area_min_y = -7.0;
  params.init_area_max_y = -1.0;
  const ParticleFilter filter(params, 3);
  ASSERT_TRUE(filter.initialized());
  const ParticleSet& p = filter.particles();
  ASSERT_EQ(p.size(), 1000);
  EXPECT_TRUE((p.x >= 2.0).all() && (p.x < 4.0).all());
  EXPECT_TRUE((p.y >= -7.0).all() && (p.y < -1.0).all());
  EXPECT_NEAR(p.x.mean(), 3.0, 0.1);
  EXPECT_NEAR(p.y.mean(), -4.0, 0.3);
  EXPECT_TRUE((p.theta > -kPi).all() && (p.theta <= kPi).all());
  // Uniform heading: the mean resultant length is ~1/sqrt(M), far from 1.
  EXPECT_LT(std::hypot(p.theta.cos().mean(), p.theta.sin().mean()), 0.1);
  EXPECT_NEAR(filter.weights().sum(), 1.0, 1e-12);
  EXPECT_NEAR(filter.effective_sample_size(), 1000.0, 1e-6);
}

TEST(ParticleFilter, KnownHeadingIsGivenToEveryParticle) {
  PfParams params = uniform_area_params();
  params.init_theta_known = true;
  params.init_theta_rad = 3.0 * kPi;  // wrapped to pi
  const ParticleFilter filter(params, 3);
  EXPECT_TRUE((filter.particles().theta == kPi).all());
}

TEST(ParticleFilter, FirstFixModeWaitsForTheFirstFixAndSpreadsAroundIt) {
  PfParams params = first_fix_params();
  params.init_fix_std_m = 0.5;
  ParticleFilter filter(params, 4);
  EXPECT_FALSE(filter.initialized());
  EXPECT_THROW(filter.estimate(), std::logic_error);
  EXPECT_NO_THROW(filter.predict(1.0, 0.1, 0.02));  // ignored: no pose yet
  EXPECT_FALSE(filter.initialized());

  filter.update(12.0, -4.0);
  ASSERT_TRUE(filter.initialized());
  EXPECT_FALSE(filter.last_update_resampled());
  const ParticleSet& p = filter.particles();
  // Sample mean within ~5 standard errors (0.5 / sqrt(1000) = 0.016).
  EXPECT_NEAR(p.x.mean(), 12.0, 0.08);
  EXPECT_NEAR(p.y.mean(), -4.0, 0.08);
  const double std_x = std::sqrt((p.x - p.x.mean()).square().mean());
  EXPECT_NEAR(std_x, 0.5, 0.05);
  // The fix placed the cloud; it was not used as a likelihood too.
  EXPECT_NEAR(filter.effective_sample_size(), 1000.0, 1e-6);
}

// ---- prediction ----

TEST(ParticleFilter, NoiseFreePredictionFollowsTheExactArc) {
  PfParams params = first_fix_params();
  params.odom_v_std_mps = 0.0;
  params.odom_omega_std_radps = 0.0;
  params.odom_omega_std_per_mps = 0.0;
  params.odom_omega_std_fraction = 0.0;
  params.turn_slip_walk_std_radpm = 0.0;  // set_particles zeroes the slips
  params.process_pos_std_m = 0.0;
  params.process_theta_std_rad = 0.0;
  params.num_particles = 5;
  params.resample_threshold = 1.0;
  ParticleFilter filter(params, 5);
  ParticleSet start;
  start.resize(5);
  start.x << 0.0, 1.0, -2.0, 3.0, 0.5;
  start.y << 0.0, -1.0, 2.0, 0.5, 4.0;
  start.theta << 0.0, 1.0, -3.0, kPi, 2.5;
  filter.set_particles(start, Eigen::ArrayXd::Ones(5));
  filter.predict(1.5, -0.7, 0.3);
  for (Eigen::Index i = 0; i < 5; ++i) {
    const model::Pose2 expected =
        model::integrate_exact({start.x[i], start.y[i], start.theta[i]}, {1.5, -0.7}, 0.3);
    EXPECT_DOUBLE_EQ(filter.particles().x[i], expected.x);
    EXPECT_DOUBLE_EQ(filter.particles().y[i], expected.y);
    EXPECT_DOUBLE_EQ(filter.particles().theta[i], expected.theta);
  }
}

TEST(ParticleFilter, PredictionNoiseSpreadsTheCloudAndKeepsHeadingWrapped) {
  PfParams params = first_fix_params();
  params.process_pos_std_m = 0.1;
  params.process_theta_std_rad = 0.2;
  ParticleFilter filter(params, 6);
  filter.set_particles(particles_at(1000, 0.0, 0.0, kPi - 0.01), Eigen::ArrayXd::Ones(1000));
  filter.predict(0.0, 0.0, 0.1);
  const ParticleSet& p = filter.particles();
  // stated for 0.02 s (process_noise_interval_s), over 0.1 s: 0.1 x sqrt(5)
  EXPECT_NEAR(std::sqrt(p.x.square().mean()), 0.1 * std::sqrt(5.0), 0.02);
  EXPECT_TRUE((p.theta > -kPi).all() && (p.theta <= kPi).all());
  EXPECT_GT((p.theta < 0.0).count(), 100);  // some crossed +pi and were wrapped
  // Weights are untouched by prediction.
  EXPECT_TRUE((filter.weights() == 1.0 / 1000.0).all());
}

TEST(ParticleFilter, ZeroTimeStepChangesNothing) {
  ParticleFilter filter(uniform_area_params(), 7);
  const ParticleSet before = filter.particles();
  filter.predict(1.0, 1.0, 0.0);
  EXPECT_TRUE((filter.particles().x == before.x).all());
  EXPECT_TRUE((filter.particles().theta == before.theta).all());
}

// ---- update: eq. (5), normalisation, eq. (6), resampling ----

TEST(ParticleFilter, UpdateWeightsFollowTheGaussianLikelihoodAndSumToOne) {
  PfParams params = first_fix_params();
  params.num_particles = 4;
  params.resample_threshold = 1.0;  // N_eff >= 1 always: never resample here
  ParticleFilter filter(params, 8);
  ParticleSet particles = particles_at(4, 0.0, 0.0, 0.0);
  particles.x << 0.0, 1.0, 2.0, -1.0;
  particles.y << 0.0, 0.5, -1.0, 3.0;
  Eigen::ArrayXd prior(4);
  prior << 0.1, 0.2, 0.3, 0.4;
  filter.set_particles(particles, prior);
  filter.update(0.5, 0.5);
  ASSERT_FALSE(filter.last_update_resampled());
  const Eigen::ArrayXd& w = filter.weights();
  EXPECT_NEAR(w.sum(), 1.0, 1e-15);
  const double var = params.measurement_std_m * params.measurement_std_m;
  const Eigen::ArrayXd d2 = (particles.x - 0.5).square() + (particles.y - 0.5).square();
  const Eigen::ArrayXd expected_unnormalised = prior * (-d2 / (2.0 * var)).exp();
  const Eigen::ArrayXd expected = expected_unnormalised / expected_unnormalised.sum();
  for (Eigen::Index i = 0; i < 4; ++i) {
    EXPECT_NEAR(w[i], expected[i], 1e-14) << "particle " << i;
  }
  EXPECT_NEAR(filter.effective_sample_size(), 1.0 / expected.square().sum(), 1e-9);
}

TEST(ParticleFilter, FarFixDoesNotUnderflowTheWeights) {
  PfParams params = first_fix_params();
  params.resample_threshold = 1.0;
  params.gate_probability = 0.0;  // no gate and no recovery: the fix must be weighted
  params.recovery_nis = 0.0;
  ParticleFilter filter(params, 9);
  filter.update(0.0, 0.0);
  filter.update(3000.0, -2000.0);  // exp(-3e6): zero for every particle in linear space
  const Eigen::ArrayXd& w = filter.weights();
  EXPECT_TRUE(w.isFinite().all());
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
  EXPECT_LT(filter.effective_sample_size(), 1000.0);  // informative, not reset to uniform
}

TEST(ParticleFilter, DegenerateWeightsAreResetToUniformNotNan) {
  PfParams params = first_fix_params();
  params.num_particles = 10;
  params.resample_threshold = 5.0;
  params.gate_probability = 0.0;
  params.recovery_nis = 0.0;
  ParticleFilter filter(params, 10);
  ParticleSet particles = particles_at(10, 0.0, 0.0, 0.0);
  particles.x.setLinSpaced(-1e200, 1e200);
  filter.set_particles(particles, Eigen::ArrayXd::Ones(10));
  filter.update(1e300, 0.0);  // squared distance overflows to inf: every log-weight is -inf
  EXPECT_TRUE((filter.weights() == 0.1).all());
  EXPECT_NEAR(filter.effective_sample_size(), 10.0, 1e-12);
  EXPECT_FALSE(filter.last_update_resampled());
  EXPECT_TRUE(filter.estimate().mean.allFinite());
}

// Particles all at the fix, so the update leaves the prior weights as they are and N_eff is
// known exactly: 500 particles with weight 1/500, 500 with weight 0 -> N_eff = 500.
ParticleFilter filter_with_half_dead_weights(double resample_threshold, ResamplingScheme scheme,
                                             double regularization_scale = 0.0) {
  PfParams params = first_fix_params();
  params.resample_threshold = resample_threshold;
  params.resampling = scheme;
  params.regularization_scale = regularization_scale;
  ParticleFilter filter(params, 11);
  ParticleSet particles = particles_at(1000, 1.0, 2.0, 0.0);
  particles.theta.setLinSpaced(-3.0, 3.0);  // labels to see who survived
  Eigen::ArrayXd weights = Eigen::ArrayXd::Zero(1000);
  weights.head(500).setOnes();
  filter.set_particles(particles, weights);
  return filter;
}

TEST(ParticleFilter, NoResamplingWhileNeffIsAtOrAboveThreshold) {
  ParticleFilter filter = filter_with_half_dead_weights(499.5, ResamplingScheme::kSystematic);
  filter.update(1.0, 2.0);
  EXPECT_NEAR(filter.last_update_effective_sample_size(), 500.0, 1e-6);
  EXPECT_FALSE(filter.last_update_resampled());
  EXPECT_EQ(filter.resample_count(), 0u);
  EXPECT_EQ((filter.weights() == 0.0).count(), 500);
}

TEST(ParticleFilter, ResamplesWhenNeffDropsBelowThreshold) {
  for (const auto scheme : {ResamplingScheme::kSystematic, ResamplingScheme::kResidual}) {
    ParticleFilter filter = filter_with_half_dead_weights(500.5, scheme);
    filter.update(1.0, 2.0);
    EXPECT_NEAR(filter.last_update_effective_sample_size(), 500.0, 1e-6);
    EXPECT_TRUE(filter.last_update_resampled());
    EXPECT_EQ(filter.resample_count(), 1u);
    EXPECT_TRUE((filter.weights() == 1.0 / 1000.0).all());
    EXPECT_NEAR(filter.effective_sample_size(), 1000.0, 1e-6);
    // Only live particles (the first 500, theta <= 0) survive, each exactly twice.
    EXPECT_TRUE((filter.particles().theta < 0.0).all());
    for (Eigen::Index i = 0; i < 1000; i += 2) {
      EXPECT_EQ(filter.particles().theta[i], filter.particles().theta[i + 1]);
    }
  }
}

TEST(ParticleFilter, RegularizationJittersTheCopiesButKeepsTheCloudSpread) {
  const double scale = 0.5;
  ParticleFilter filter = filter_with_half_dead_weights(500.5, ResamplingScheme::kSystematic, scale);
  // Weighted cloud before resampling: x, y constant, theta uniform on the live half [-3, ~0].
  const PoseEstimate before = filter.estimate();
  filter.update(1.0, 2.0);
  ASSERT_TRUE(filter.last_update_resampled());
  const ParticleSet& p = filter.particles();
  // No spread in x and y (up to the rounding of the weighted mean), so no jitter there.
  EXPECT_LT((p.x - 1.0).abs().maxCoeff(), 1e-9);
  EXPECT_LT((p.y - 2.0).abs().maxCoeff(), 1e-9);
  // Copies are no longer identical pairs ...
  int identical_pairs = 0;
  for (Eigen::Index i = 0; i < 1000; i += 2) {
    identical_pairs += p.theta[i] == p.theta[i + 1] ? 1 : 0;
  }
  EXPECT_EQ(identical_pairs, 0);
  // ... but the heading variance is kept (shrinkage + jitter), not grown by (1 + h^2): the
  // issue-12 standstill drift. h = scale h_opt = 0.18, so growth would be +3.3 % per resampling.
  const double var = filter.estimate().covariance(2, 2);
  EXPECT_NEAR(var, before.covariance(2, 2), 0.015 * before.covariance(2, 2));
  EXPECT_NEAR(filter.estimate().mean.z(), before.mean.z(), 0.02);
}

TEST(ParticleFilter, ResamplingDecisionAlwaysMatchesTheThreshold) {
  PfParams params = first_fix_params();
  params.resample_threshold = 700.0;
  ParticleFilter filter(params, 12);
  RandomEngine world(99);
  filter.update(0.0, 0.0);
  std::size_t resamples = 0;
  for (int k = 0; k < 300; ++k) {
    filter.predict(0.0, 0.0, 0.1);
    filter.update(kFixStd * standard_normal(world), kFixStd * standard_normal(world));
    EXPECT_EQ(filter.last_update_resampled(), filter.last_update_effective_sample_size() < 700.0);
    resamples += filter.last_update_resampled() ? 1 : 0;
  }
  EXPECT_EQ(filter.resample_count(), resamples);
  // Both branches were exercised.
  EXPECT_GT(resamples, 0u);
  EXPECT_LT(resamples, 300u);
}

// ---- invalid input ----

TEST(ParticleFilter, NonFiniteInputThrowsAndLeavesTheStateUntouched) {
  ParticleFilter filter(uniform_area_params(), 13);
  ParticleFilter twin(uniform_area_params(), 13);
  filter.update(1.0, 1.0);
  twin.update(1.0, 1.0);
  EXPECT_THROW(filter.predict(kNan, 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(filter.predict(1.0, kInf, 0.1), std::invalid_argument);
  EXPECT_THROW(filter.predict(1.0, 0.0, kNan), std::invalid_argument);
  EXPECT_THROW(filter.predict(1.0, 0.0, -0.1), std::invalid_argument);
  EXPECT_THROW(filter.update(kNan, 0.0), std::invalid_argument);
  EXPECT_THROW(filter.update(0.0, -kInf), std::invalid_argument);
  EXPECT_THROW(filter.initialize_around(kNan, 0.0), std::invalid_argument);
  EXPECT_TRUE(same_state(filter, twin));
  // Not even the random stream moved: both continue identically.
  filter.predict(1.0, 0.2, 0.1);
  twin.predict(1.0, 0.2, 0.1);
  filter.update(1.2, 1.1);
  twin.update(1.2, 1.1);
  EXPECT_TRUE(same_state(filter, twin));
}

TEST(ParticleFilter, SetParticlesRejectsBadInput) {
  PfParams params = first_fix_params();
  params.num_particles = 3;
  params.resample_threshold = 1.0;
  ParticleFilter filter(params, 14);
  EXPECT_THROW(filter.set_particles(particles_at(4, 0, 0, 0), Eigen::ArrayXd::Ones(4)),
               std::invalid_argument);
  EXPECT_THROW(filter.set_particles(particles_at(3, kNan, 0, 0), Eigen::ArrayXd::Ones(3)),
               std::invalid_argument);
  EXPECT_THROW(filter.set_particles(particles_at(3, 0, 0, 0), Eigen::ArrayXd::Zero(3)),
               std::invalid_argument);
  EXPECT_THROW(filter.set_particles(particles_at(3, 0, 0, 0), -Eigen::ArrayXd::Ones(3)),
               std::invalid_argument);
  EXPECT_FALSE(filter.initialized());
}

// ---- estimation quality ----

TEST(ParticleFilter, ConvergesOnAStaticTargetFromTheUniformPrior) {
  // The paper's set-up: uniform particles over the area, position fixes with variance 2.28 m^2.
  double sum_error = 0.0;
  const int seeds = 10;
  for (int seed = 0; seed < seeds; ++seed) {
    ParticleFilter filter(uniform_area_params(), derive_seed(static_cast<std::uint64_t>(seed), "static"));
    RandomEngine world(derive_seed(static_cast<std::uint64_t>(seed), "static-world"));
    const double target_x = 3.0;
    const double target_y = -2.0;
    for (int k = 0; k < 40; ++k) {
      filter.predict(0.0, 0.0, 0.1);
      filter.update(target_x + kFixStd * standard_normal(world),
                    target_y + kFixStd * standard_normal(world));
    }
    const PoseEstimate estimate = filter.estimate();
    const double error = std::hypot(estimate.mean.x() - target_x, estimate.mean.y() - target_y);
    EXPECT_LT(error, 0.75) << "seed " << seed;  // half the measurement std, every run
    // The reported spread agrees with the information in 40 fixes (std ~ 1.51 / sqrt(40)).
    EXPECT_LT(std::sqrt(estimate.covariance(0, 0)), 0.5) << "seed " << seed;
    sum_error += error;
    RecordProperty("seed" + std::to_string(seed) + "_error_m", std::to_string(error));
  }
  // Mean 2D error of the average of 40 fixes is ~0.3 m; require well below s = 1.51 m.
  EXPECT_LT(sum_error / seeds, 0.45);
}

TEST(ParticleFilter, TracksATurningRobotAtLeastTwiceAsWellAsTheRawFixes) {
  for (const auto scheme : {ResamplingScheme::kSystematic, ResamplingScheme::kResidual}) {
    PfParams params = first_fix_params();
    params.resampling = scheme;
    SimulationConfig config;
    params.init_theta_known = true;
    params.init_theta_rad = config.start.theta;
    ParticleFilter filter(params, 21);
    const SimulationResult result = simulate(filter, config, 21);
    RecordProperty(to_string(scheme) + "_estimate_rmse_m", std::to_string(result.estimate_rmse_m));
    RecordProperty(to_string(scheme) + "_fix_rmse_m", std::to_string(result.fix_rmse_m));
    RecordProperty(to_string(scheme) + "_heading_error_deg",
                   std::to_string(result.final_heading_error_rad / kDeg));
    EXPECT_NEAR(result.fix_rmse_m, std::sqrt(2.0 * 2.28), 0.15);  // the simulated sensor is right
    EXPECT_LT(result.estimate_rmse_m, 0.5 * result.fix_rmse_m)
        << to_string(scheme) << ": estimate RMSE " << result.estimate_rmse_m << " m, fix RMSE "
        << result.fix_rmse_m << " m";
    EXPECT_LT(result.final_heading_error_rad, 5.0 * kDeg);
    EXPECT_GT(filter.resample_count(), 0u);
  }
}

TEST(ParticleFilter, LearnsAnUnknownHeadingWhileTheRobotMoves) {
  for (const std::uint64_t seed : {31u, 32u, 33u, 34u, 35u}) {
    PfParams params = first_fix_params();
    params.init_theta_known = false;
    SimulationConfig config;
    config.duration_s = 60.0;
    config.start.theta = 2.0;  // nowhere near the particles' circular mean at the start
    ParticleFilter filter(params, seed);
    const SimulationResult result = simulate(filter, config, seed);
    RecordProperty("seed" + std::to_string(seed) + "_heading_error_deg",
                   std::to_string(result.final_heading_error_rad / kDeg));
    RecordProperty("seed" + std::to_string(seed) + "_estimate_rmse_m",
                   std::to_string(result.estimate_rmse_m));
    EXPECT_LT(result.final_heading_error_rad, 5.0 * kDeg) << "seed " << seed;
    EXPECT_LT(std::sqrt(filter.estimate().covariance(2, 2)), 5.0 * kDeg) << "seed " << seed;
    EXPECT_LT(result.estimate_rmse_m, 0.5 * result.fix_rmse_m) << "seed " << seed;
  }
}

// ---- robustness (issue 12) ----

// A robot that stands for 600 s with fixes at 10 Hz and odometry (zero) at 50 Hz: nothing
// observes the heading, so its spread must not grow (the issue measured 2 -> 100 degrees).
TEST(ParticleFilter, HeadingSpreadDoesNotGrowAtStandstill) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  ParticleFilter filter(params, 41);
  RandomEngine world(derive_seed(41, "standstill"));
  // A known-ish heading: 2 degrees of spread around 0.5 rad.
  ParticleSet start = particles_at(1000, 0.0, 0.0, 0.5);
  for (Eigen::Index i = 0; i < 1000; ++i) {
    start.x[i] = kFixStd * standard_normal(world);
    start.y[i] = kFixStd * standard_normal(world);
    start.theta[i] = 0.5 + 2.0 * kDeg * standard_normal(world);
  }
  filter.set_particles(start, Eigen::ArrayXd::Ones(1000));
  const double std_start = std::sqrt(filter.estimate().covariance(2, 2));
  double std_max = std_start;
  for (int fix = 0; fix < 6000; ++fix) {
    for (int k = 0; k < 5; ++k) {
      filter.predict(0.0, 0.0, 0.02);
    }
    filter.update(kFixStd * standard_normal(world), kFixStd * standard_normal(world));
    std_max = std::max(std_max, std::sqrt(filter.estimate().covariance(2, 2)));
  }
  RecordProperty("heading_std_start_deg", std::to_string(std_start / kDeg));
  RecordProperty("heading_std_max_deg", std::to_string(std_max / kDeg));
  EXPECT_GT(filter.resample_count(), 100u);  // the regularisation ran many times
  EXPECT_LT(std_max - std_start, 1.0 * kDeg);
}

// Issue 27, finding 4: an odometry that says its turn rate is noisy also at standstill (the
// simulated one: white wheel noise, var_omega 0.0089 (rad/s)^2 per 50 Hz sample) turns the
// heading there; the spread must follow, or the filter is over-confident while nothing observes it.
double heading_std_after_standing(bool use_odometry_variance, double omega_var) {
  PfParams params = first_fix_params();
  params.init_theta_known = true;
  params.use_odometry_variance = use_odometry_variance;
  ParticleFilter filter(params, 12);
  filter.update(0.0, 0.0);
  for (int step = 0; step < 3000; ++step) {  // 60 s
    filter.predict(0.0, 0.0, 0.02, omega_var);
  }
  return std::sqrt(filter.estimate().covariance(2, 2));
}

// ... and while driving, before the fixes see the heading: the wheel model's 0.025 rad/s at 1 m/s
// alone would let the estimate turn away from a known start heading at a spread of a quarter of
// the claim's (the first seconds of standstill_600s: 2-6 deg off at 0.7-1.8 deg reported).
TEST(ParticleFilter, HeadingSpreadFollowsTheTurnNoiseTheOdometryClaimsWhileDriving) {
  PfParams params = first_fix_params();
  params.init_theta_known = true;
  params.turn_slip_std_radpm = 0.0;  // only the turn noise
  params.turn_slip_walk_std_radpm = 0.0;
  ParticleFilter filter(params, 12);
  filter.update(0.0, 0.0);
  for (int step = 0; step < 3000; ++step) {  // 60 s at 1 m/s, no fixes
    filter.predict(1.0, 0.0, 0.02, 0.0089);
  }
  const double expected = std::sqrt(3000.0) * std::sqrt(0.0089) * 0.02;  // 0.103 rad
  EXPECT_NEAR(std::sqrt(filter.estimate().covariance(2, 2)), expected, 0.1 * expected);
}

TEST(ParticleFilter, HeadingSpreadFollowsTheTurnNoiseTheOdometryClaimsAtStandstill) {
  const double expected = std::sqrt(3000.0) * std::sqrt(0.0089) * 0.02;  // random walk: 0.103 rad
  EXPECT_NEAR(heading_std_after_standing(true, 0.0089), expected, 0.1 * expected);
  EXPECT_LT(heading_std_after_standing(false, 0.0089), 0.1 * expected) << "the claim ignored";
  EXPECT_LT(heading_std_after_standing(true, 0.0), 0.1 * expected) << "no claim: the wheel model";
}

// Issue 27: the process noises are densities stated for samples process_noise_interval_s apart
// (0.02 s), scaled by each sample's dt, so the filter adds the same variance per second whatever
// the odometry rate. Before, they were applied once per predict(): 10 Hz odometry diffused the
// position 5x less per second and 100 Hz twice as much (paper1_waypoints at 100 Hz: seed 6 never
// valid).
TEST(ParticleFilter, ProcessNoiseScalesKeepTheVariancePerSecond) {
  const NoiseScales same = process_noise_scales(0.02, 0.02);
  EXPECT_EQ(same.rate, 1.0);  // exactly: 50 Hz odometry gives the figures it gave before
  EXPECT_EQ(same.diffusion, 1.0);
  const NoiseScales slow = process_noise_scales(0.02, 0.1);
  EXPECT_NEAR(slow.rate * slow.rate * 0.1 * 0.1 * 10.0, 0.02 * 0.02 * 50.0, 1e-12);  // (s dt)^2 per sample x rate
  EXPECT_NEAR(slow.diffusion * slow.diffusion * 10.0, 50.0, 1e-12);
  const NoiseScales per_sample = process_noise_scales(0.0, 0.1);
  EXPECT_EQ(per_sample.rate, 1.0);
  EXPECT_EQ(per_sample.diffusion, 1.0);
}

struct SpreadAfterDriving {
  double var_x = 0.0;      // along the track: the additive diffusion (and the speed noise)
  double var_theta = 0.0;  // the wheel model's turn noise
};

SpreadAfterDriving spread_after_driving(double dt_s, double interval_s, double omega_var = 0.0) {
  PfParams params = first_fix_params();
  params.num_particles = 4000;
  params.resample_threshold = 2000.0;
  params.init_theta_known = true;
  params.init_fix_std_m = 1e-6;
  params.turn_slip_std_radpm = 0.0;  // only the process noises
  params.turn_slip_walk_std_radpm = 0.0;
  params.process_noise_interval_s = interval_s;
  ParticleFilter filter(params, 31);
  filter.update(0.0, 0.0);
  const int steps = static_cast<int>(std::lround(20.0 / dt_s));  // 20 s at 1 m/s, no fixes
  for (int step = 0; step < steps; ++step) {
    filter.predict(1.0, 0.0, dt_s, omega_var);
  }
  const PoseEstimate e = filter.estimate();
  return {e.covariance(0, 0), e.covariance(2, 2)};
}

TEST(ParticleFilter, TheProcessNoiseAddsTheSameVariancePerSecondAtAnyOdometryRate) {
  const SpreadAfterDriving at_50hz = spread_after_driving(0.02, 0.02);
  // the reference: 1000 samples of process_pos_std_m 0.02 along x (0.4 m^2; the speed noise adds
  // 0.001), 1000 of 0.025 rad/s x 0.02 s on theta (2.5e-4 rad^2)
  EXPECT_NEAR(at_50hz.var_x, 0.401, 0.06 * 0.401);
  EXPECT_NEAR(at_50hz.var_theta, 2.5e-4, 0.06 * 2.5e-4);
  for (const double dt_s : {0.1, 0.01}) {
    const SpreadAfterDriving other = spread_after_driving(dt_s, 0.02);
    EXPECT_NEAR(other.var_x / at_50hz.var_x, 1.0, 0.1) << "dt " << dt_s;
    EXPECT_NEAR(other.var_theta / at_50hz.var_theta, 1.0, 0.1) << "dt " << dt_s;
  }
  // per sample (process_noise_interval_s 0, before): 10 Hz diffuses x 5x less, theta 5x more
  const SpreadAfterDriving per_sample = spread_after_driving(0.1, 0.0);
  EXPECT_LT(per_sample.var_x / at_50hz.var_x, 0.3);
  EXPECT_GT(per_sample.var_theta / at_50hz.var_theta, 3.0);
}

// The odometry's claimed var_omega is the variance of this sample's turn rate (the simulated
// sensor's white wheel noise per reading, whatever its rate): used as it comes, its heading random
// walk is var_omega dt^2 per sample, 5x more per second at 10 Hz than at 50 Hz, as the sensor's.
TEST(ParticleFilter, TheTurnNoiseTheOdometryClaimsIsPerSampleAndNotScaled) {
  for (const double dt_s : {0.1, 0.02}) {
    const double expected = 0.0089 * dt_s * 20.0;  // (20 / dt) samples of 0.0089 dt^2
    EXPECT_NEAR(spread_after_driving(dt_s, 0.02, 0.0089).var_theta, expected, 0.08 * expected) << "dt " << dt_s;
  }
}

// Issue 27, finding 2: a heading the cloud learned is checked against the fixes' track before the
// filter says confirmed(). The cloud is put on a heading 115 deg wrong (as with fixes 3x noisier than
// configured, seed 3: valid at 22 s, 92-121 deg off), the robot creeps straight at 0.3 m/s with
// fixes of std 4.53 m against the configured 1.51 m (variance 20.5 m^2). Counts the fixes after which the filter says
// confirmed() with a heading more than 30 deg off.
struct WrongHeadingRun {
  int confirmed_while_wrong = 0;
  std::size_t redraws = 0;
  double position_var_after_redraw_m2 = 0.0;  // the cloud's x and y variance (mean) right after the first redraw
  double fix_var_m2 = 0.0;                    // the fix noise estimated then (per axis)
  bool confirmed_at_end = false;
  double final_heading_error_rad = 0.0;
};

WrongHeadingRun creep_from_a_wrong_heading(int track_check_window_fixes, bool widen_positions = true) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  params.track_check_window_fixes = track_check_window_fixes;
  params.track_redraw_widens_position = widen_positions;
  params.recovery_nis = 0.0;  // the lost-filter monitor would redraw too: this is about the check
  ParticleFilter filter(params, 21);
  RandomEngine world(derive_seed(21, "world"));
  model::Pose2 truth{10.0, 20.0, 0.5};
  filter.initialize_around(truth.x, truth.y);
  ParticleSet wrong = particles_at(1000, truth.x, truth.y, truth.theta + 2.0);
  for (Eigen::Index i = 0; i < 1000; ++i) {
    wrong.x[i] += 0.5 * standard_normal(world);
    wrong.y[i] += 0.5 * standard_normal(world);
    wrong.theta[i] += 0.05 * standard_normal(world);
  }
  filter.set_particles(wrong, Eigen::ArrayXd::Ones(1000));
  WrongHeadingRun run;
  const model::Twist twist{0.3, 0.0};
  for (int step = 1; step <= 2500; ++step) {  // 50 s, 50 Hz odometry, 10 Hz fixes
    truth = model::integrate_exact(truth, twist, 0.02);
    filter.predict(twist.v + 0.014 * standard_normal(world), twist.omega + 0.094 * standard_normal(world), 0.02,
                   0.0089);
    if (step % 5 != 0) {
      continue;
    }
    const std::size_t redraws_before = filter.track_redraw_count();
    filter.update(truth.x + 4.53 * standard_normal(world), truth.y + 4.53 * standard_normal(world));
    if (redraws_before == 0 && filter.track_redraw_count() == 1) {
      const PoseEstimate cloud = filter.estimate();
      run.position_var_after_redraw_m2 = 0.5 * (cloud.covariance(0, 0) + cloud.covariance(1, 1));
      run.fix_var_m2 = filter.measurement_std_estimate_m() * filter.measurement_std_estimate_m();
    }
    run.final_heading_error_rad = std::abs(wrap_angle(filter.estimate().mean.z() - truth.theta));
    if (filter.confirmed() && run.final_heading_error_rad > 30.0 * kDeg) {
      ++run.confirmed_while_wrong;
    }
  }
  run.redraws = filter.track_redraw_count();
  run.confirmed_at_end = filter.confirmed();
  return run;
}

TEST(ParticleFilter, ALearnedHeadingIsConfirmedOnlyWhenTheFixesTrackAgrees) {
  const WrongHeadingRun checked = creep_from_a_wrong_heading(300);
  EXPECT_EQ(checked.confirmed_while_wrong, 0);
  EXPECT_GE(checked.redraws, 1u);  // the cloud's headings were redrawn around the track's
  EXPECT_TRUE(checked.confirmed_at_end);
  EXPECT_LT(checked.final_heading_error_rad, 20.0 * kDeg);
  const WrongHeadingRun unchecked = creep_from_a_wrong_heading(0);  // the check off: before
  EXPECT_GT(unchecked.confirmed_while_wrong, 100);
  EXPECT_EQ(unchecked.redraws, 0u);
}

// The positions had followed the wrong heading: a redraw widens them to at least the fix noise the
// filter estimates (track_redraw_widens_position); kept, they stayed narrow (fixes 3x noisier,
// seed 3: 3.8 m off at d^2 54 for 8.6 s after the redraw).
TEST(ParticleFilter, ARedrawByTheTrackCheckWidensThePositionsToTheFixNoise) {
  const WrongHeadingRun widened = creep_from_a_wrong_heading(300);
  ASSERT_GE(widened.redraws, 1u);
  EXPECT_GE(widened.position_var_after_redraw_m2, 0.99 * widened.fix_var_m2);
  const WrongHeadingRun kept = creep_from_a_wrong_heading(300, false);
  ASSERT_GE(kept.redraws, 1u);
  EXPECT_LT(kept.position_var_after_redraw_m2, 0.5 * kept.fix_var_m2);
}

// Issue 27, fixes 2-5x noisier than configured: after the track check passed once, the cloud could
// narrow onto a wrong heading while driving (1,000 particles, 11-16 deg off at a reported 2-3 deg
// for 50 s: the cloud had learned a wrong turn slip and bent its heading). The check keeps running
// while driving (track_check_while_driving): a cloud that differs from the track beyond
// track_check_inflate_sigmas combined sigmas gets its heading and slip spread widened; beyond
// track_check_sigmas (and at most prior_heading_tolerance_rad) its headings are redrawn.
// A robot weaving at 1.5 m/s for 90 s, fixes of std 2.14 m (variance 2x the configured 2.28 m^2),
// 50 Hz odometry whose turn rate reads k v too much (a wheel reading fast; k = 0.02 rad/m) while the
// cloud starts sure that k is about 0 (turn_slip_std_radpm 0.002). Counts the fixes after which
// the filter is confirmed() with a heading error beyond 3 of its reported sigmas.
struct DrivenRun {
  int confirmed = 0;
  int overconfident = 0;
  std::size_t inflations = 0;
  std::size_t driving_redraws = 0;
};

DrivenRun drive_on_a_wrong_slip(bool while_driving, double inflate_sigmas, std::uint64_t seed) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  params.turn_slip_std_radpm = 0.002;
  params.recovery_nis = 0.0;  // the lost-filter monitor would redraw too: this is about the check
  params.track_check_while_driving = while_driving;
  params.track_check_inflate_sigmas = inflate_sigmas;
  ParticleFilter filter(params, seed);
  RandomEngine world(derive_seed(seed, "world"));
  model::Pose2 truth{10.0, 20.0, 0.5};
  filter.initialize_around(truth.x, truth.y);
  DrivenRun run;
  for (int step = 1; step <= 4500; ++step) {  // 90 s
    const model::Twist twist{1.5, 0.15 * std::sin(0.2 * 0.02 * step)};
    truth = model::integrate_exact(truth, twist, 0.02);
    filter.predict(twist.v + 0.014 * standard_normal(world),
                   twist.omega + 0.02 * twist.v + 0.094 * standard_normal(world), 0.02, 0.0089);
    if (step % 5 != 0) {
      continue;
    }
    filter.update(truth.x + 2.14 * standard_normal(world), truth.y + 2.14 * standard_normal(world));
    if (filter.confirmed()) {
      const PoseEstimate estimate = filter.estimate();
      ++run.confirmed;
      run.overconfident += std::abs(wrap_angle(estimate.mean.z() - truth.theta)) > 3.0 * std::sqrt(estimate.covariance(2, 2));
    }
  }
  run.inflations = filter.track_inflation_count();
  run.driving_redraws = filter.track_redraw_while_driving_count();
  return run;
}

TEST(ParticleFilter, WhileDrivingTheHeadingStaysCheckedAgainstTheFixesTrack) {
  DrivenRun off, on;
  for (const std::uint64_t seed : {1u, 3u}) {
    const DrivenRun a = drive_on_a_wrong_slip(false, 0.0, seed);  // the check stops once passed: before
    const DrivenRun b = drive_on_a_wrong_slip(true, 2.0, seed);   // the defaults
    EXPECT_EQ(a.inflations + a.driving_redraws, 0u);
    EXPECT_GE(b.inflations, 3u) << seed;
    off.confirmed += a.confirmed;
    off.overconfident += a.overconfident;
    on.confirmed += b.confirmed;
    on.overconfident += b.overconfident;
  }
  // Before: most confirmed fixes over-confident (the cloud's heading bent by its wrong slip).
  EXPECT_GT(off.overconfident, off.confirmed / 2);
  EXPECT_LT(on.overconfident, on.confirmed / 10);
  EXPECT_GT(on.confirmed, off.confirmed * 9 / 10);  // and it is as often confirmed
  // The redraws alone (no widening) help, less.
  const DrivenRun redraw_only = drive_on_a_wrong_slip(true, 0.0, 1);
  EXPECT_EQ(redraw_only.inflations, 0u);
  EXPECT_GE(redraw_only.driving_redraws, 1u);
  EXPECT_LT(redraw_only.overconfident, off.overconfident / 4);
}

// Issue 27, fixes 2-5x noisier than configured: right after the track check passed, while driving,
// the track fits the turn slip too and knows the heading only to more than
// track_check_heading_std_rad, so it does not judge yet, while 1,000 particles had narrowed their
// turn slips (and with them the heading) faster than the fixes justify: clouds 25-40 deg off at a
// reported 5-10 deg in the first ~20 s after `valid` (std 2x seed 9, 5x variance seed 9, std 5x
// seed 7). With track_check_floor, until the track first judges, the cloud's slip spread is at
// least what the track's fit with the filter's own slip prior leaves. A robot creeping at 0.3 m/s
// (as the controller does before `valid`), then weaving at 1.5 m/s, fixes of std `fix_std` m
// against the configured 1.51 m.
struct EarlyRun {
  int confirmed_before_judged = 0;  // fixes after which the filter is confirmed, the track not judging yet
  int narrower_than_track = 0;      // ... with the cloud's slip std below the track's (with the prior)
  int overconfident = 0;            // ... with a heading error beyond 3 reported sigmas
  std::size_t floors = 0;
};

EarlyRun creep_then_drive(bool floor, double fix_std, std::uint64_t seed) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  params.measurement_std_m = 1.51;
  params.init_fix_std_m = 1.51;
  params.track_check_floor = floor;
  params.track_doubt_std_rad = 0.0;  // about the spread, not the restart
  ParticleFilter filter(params, seed);
  RandomEngine world(derive_seed(seed, "world"));
  model::Pose2 truth{10.0, 20.0, 0.5};
  filter.initialize_around(truth.x + fix_std * standard_normal(world), truth.y + fix_std * standard_normal(world));
  EarlyRun run;
  bool driving = false;
  for (int step = 1; step <= 4500; ++step) {  // at most 90 s
    driving = driving || filter.confirmed();
    const model::Twist twist = driving ? model::Twist{1.5, 0.3 * std::sin(0.3 * 0.02 * step)} : model::Twist{0.3, 0.0};
    truth = model::integrate_exact(truth, twist, 0.02);
    filter.predict(twist.v + 0.014 * standard_normal(world), twist.omega + 0.094 * standard_normal(world), 0.02, 0.0089);
    if (step % 5 != 0) {
      continue;
    }
    filter.update(truth.x + fix_std * standard_normal(world), truth.y + fix_std * standard_normal(world));
    if (!filter.confirmed() || filter.track_judged_while_driving()) {
      continue;
    }
    ++run.confirmed_before_judged;
    const double track_slip_std = filter.heading_track_check().slip_std_with_prior_radpm(params.turn_slip_std_radpm);
    run.narrower_than_track += filter.turn_slip_std_radpm() < 0.999 * track_slip_std;
    const PoseEstimate estimate = filter.estimate();
    run.overconfident += std::abs(wrap_angle(estimate.mean.z() - truth.theta)) > 3.0 * std::sqrt(estimate.covariance(2, 2));
  }
  run.floors = filter.track_floor_count();
  return run;
}

TEST(ParticleFilter, UntilTheTrackJudgesTheCloudsSlipsAreAsUncertainAsTheFixesLeaveThem) {
  // Fixes of std 3.02 m (twice the configured std, as std 2x). Measured: off, the slips narrower than
  // the track's on 36-72 of 48-73 confirmed fixes (seeds 1-6), 12 over-confident on seed 1; on, none
  // narrower, 4 over-confident on seed 1, the others 0.
  int overconfident_on = 0, overconfident_off = 0;
  for (const std::uint64_t seed : {1u, 4u}) {
    const EarlyRun on = creep_then_drive(true, 3.02, seed);
    const EarlyRun off = creep_then_drive(false, 3.02, seed);
    ASSERT_GT(on.confirmed_before_judged, 20) << seed;
    EXPECT_EQ(on.confirmed_before_judged, off.confirmed_before_judged) << seed << ": the same run until then";
    EXPECT_GE(on.floors, 1u) << seed;
    EXPECT_EQ(on.narrower_than_track, 0) << seed;
    EXPECT_EQ(off.floors, 0u) << seed;
    EXPECT_GT(off.narrower_than_track, off.confirmed_before_judged / 2) << seed;
    overconfident_on += on.overconfident;
    overconfident_off += off.overconfident;
  }
  EXPECT_LT(overconfident_on, overconfident_off / 2);
}

// A recovery keeps half the particles' turn slips: the cloud then knows more of the slip than the
// track's new window, which is no floor for it until the next initialisation (with the floor after
// the 10 m kidnap of kidnap_10m the slips were widened to the prior again). The robot of
// creep_then_drive's set-up, moved 15 m once the filter is confirmed and driving (the monitor
// redraws the cloud around the fixes), then creeping and driving again.
TEST(ParticleFilter, TheSlipFloorActsAfterAnInitialisationNotAfterARecovery) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  params.measurement_std_m = 1.51;
  params.init_fix_std_m = 1.51;
  params.track_doubt_std_rad = 0.0;
  ParticleFilter filter(params, 2);
  RandomEngine world(derive_seed(2, "world"));
  model::Pose2 truth{10.0, 20.0, 0.5};
  filter.initialize_around(truth.x + 3.02 * standard_normal(world), truth.y + 3.02 * standard_normal(world));
  std::size_t floors_before_recovery = 0;
  bool kidnapped = false;
  int confirmed_after_recovery = 0;
  for (int step = 1; step <= 6000; ++step) {
    const bool driving = filter.confirmed();
    const model::Twist twist = driving ? model::Twist{1.5, 0.3 * std::sin(0.3 * 0.02 * step)} : model::Twist{0.3, 0.0};
    truth = model::integrate_exact(truth, twist, 0.02);
    if (!kidnapped && driving && filter.track_floor_count() > 0 && filter.track_judged_while_driving()) {
      truth.x += 15.0;  // kidnapped: the fixes jump, the odometry does not
      kidnapped = true;
      floors_before_recovery = filter.track_floor_count();
    }
    filter.predict(twist.v + 0.014 * standard_normal(world), twist.omega + 0.094 * standard_normal(world), 0.02, 0.0089);
    if (step % 5 == 0) {
      filter.update(truth.x + 3.02 * standard_normal(world), truth.y + 3.02 * standard_normal(world));
      confirmed_after_recovery += kidnapped && filter.recovery_count() > 0 && filter.confirmed();
    }
  }
  ASSERT_TRUE(kidnapped) << "the floor never acted, or the track never judged";
  ASSERT_GE(filter.recovery_count(), 1u);
  EXPECT_GT(confirmed_after_recovery, 50) << "confirmed and driving again after the recovery";
  EXPECT_EQ(filter.track_floor_count(), floors_before_recovery) << "the floor acted after the recovery";
}

// Standing after driving (a way-point reached, the mission done), the fixes say nothing about the
// heading: the track check while driving neither stores nor judges them. Judged from a window of
// standing fixes, its slip fit passed a wrong heading and redrew a right cloud (nominal seed 1 with
// the estimate moved on to its step, 24 s after the mission: valid 27 deg off at a reported 11.5 deg).
TEST(ParticleFilter, TheTrackCheckWhileDrivingIgnoresTheFixesOfARobotStandingStill) {
  PfParams params = first_fix_params();
  params.init_theta_known = false;
  params.measurement_std_m = 1.51;
  params.init_fix_std_m = 1.51;
  ParticleFilter filter(params, 5);
  RandomEngine world(derive_seed(5, "world"));
  model::Pose2 truth{10.0, 20.0, 0.5};
  filter.initialize_around(truth.x, truth.y);
  std::size_t fixes_when_stopped = 0;
  int standing_fixes = 0;
  int steps_since_confirmed = -1;
  for (int step = 1; step <= 6000; ++step) {
    if (steps_since_confirmed < 0 && filter.confirmed() && filter.track_confirmed()) {
      steps_since_confirmed = 0;
    }
    const bool stopped = steps_since_confirmed > 1000;  // 20 s of driving after the check passed, then standing
    const model::Twist twist = stopped ? model::Twist{0.0, 0.0}
                                       : model::Twist{steps_since_confirmed >= 0 ? 1.5 : 0.3, 0.2 * std::sin(0.01 * step)};
    truth = model::integrate_exact(truth, twist, 0.02);
    filter.predict(twist.v + 0.014 * standard_normal(world), twist.omega + 0.094 * standard_normal(world), 0.02, 0.0089);
    if (steps_since_confirmed >= 0) {
      ++steps_since_confirmed;
    }
    if (step % 5 != 0) {
      continue;
    }
    filter.update(truth.x + 1.51 * standard_normal(world), truth.y + 1.51 * standard_normal(world));
    if (stopped && filter.last_update_standing()) {
      if (standing_fixes == 0) {
        fixes_when_stopped = filter.heading_track_check().fixes();
      }
      ++standing_fixes;
    }
  }
  ASSERT_GE(steps_since_confirmed, 0) << "never confirmed";
  ASSERT_GT(standing_fixes, 300) << "more than a window of standing fixes";
  EXPECT_GE(fixes_when_stopped, 200u) << "the driving filled the window";
  EXPECT_EQ(filter.heading_track_check().fixes(), fixes_when_stopped) << "standing fixes were stored";
  EXPECT_TRUE(filter.confirmed());
}

// Issue 27, finding 4: a fix after an interval in which the robot stood carries no heading
// information. When it resamples, only the position is drawn from the weighted cloud: every
// particle keeps its own heading and turn slip (before, whole particles were copied, thinning the
// heading at every resampling). A moving robot's fix resamples whole particles as always.
struct ResampledOnce {
  bool standing = false;
  bool resampled = false;
  bool headings_kept = false;
  bool positions_kept = false;
};

ResampledOnce resample_once(double v_mps, bool standstill_keeps_heading) {
  PfParams params = first_fix_params();
  params.resample_threshold = 1000.0;  // any uneven weights resample
  params.standstill_keeps_heading = standstill_keeps_heading;
  ParticleFilter filter(params, 44);
  RandomEngine world(derive_seed(44, "cloud"));
  ParticleSet start = particles_at(1000, 0.0, 0.0, 0.0);
  for (Eigen::Index i = 0; i < 1000; ++i) {
    start.x[i] = standard_normal(world);
    start.y[i] = standard_normal(world);
    start.theta[i] = 0.5 * standard_normal(world);
  }
  filter.set_particles(start, Eigen::ArrayXd::Ones(1000));
  for (int k = 0; k < 5; ++k) {
    filter.predict(v_mps, 0.0, 0.02);
  }
  const ParticleSet before = filter.particles();
  filter.update(0.5, 0.0);
  ResampledOnce out;
  out.standing = filter.last_update_standing();
  out.resampled = filter.last_update_resampled();
  out.headings_kept = (filter.particles().theta == before.theta).all();
  out.positions_kept = (filter.particles().x == before.x).all();
  return out;
}

TEST(ParticleFilter, AFixAfterStandingResamplesThePositionOnlyAndKeepsEveryHeading) {
  const ResampledOnce standing = resample_once(0.0, true);
  EXPECT_TRUE(standing.standing);
  ASSERT_TRUE(standing.resampled);
  EXPECT_TRUE(standing.headings_kept) << "a standing robot's fix must not resample the heading";
  EXPECT_FALSE(standing.positions_kept) << "the position is resampled";
  // Below standstill_speed_mps (0.05 m/s) on average: still standing.
  EXPECT_TRUE(resample_once(0.04, true).headings_kept);
  // Moving: whole particles are copied, the heading with them (the fixes observe it).
  const ResampledOnce moving = resample_once(0.3, true);
  EXPECT_FALSE(moving.standing);
  ASSERT_TRUE(moving.resampled);
  EXPECT_FALSE(moving.headings_kept);
  // Turned off: the behaviour before issue 27.
  const ResampledOnce off = resample_once(0.0, false);
  EXPECT_FALSE(off.standing);
  ASSERT_TRUE(off.resampled);
  EXPECT_FALSE(off.headings_kept);
}

// Issue 27, finding 4, the whole effect: a robot standing 600 s with fixes at 10 Hz and odometry
// at 50 Hz that claims the simulated sensor's turn noise (var_omega 0.0089 (rad/s)^2, white, also
// at standstill). The true heading error is a random walk of that noise, so an honest spread is
// sqrt(std_0^2 + 0.0089 dt^2 n) after n predictions (the filter's own wheel-model part adds a
// little). Copying whole particles at every resampling thinned it below that.
double heading_std_after_standing_with_fixes(bool standstill_keeps_heading, double* expected_rad) {
  PfParams params = first_fix_params();
  params.standstill_keeps_heading = standstill_keeps_heading;
  ParticleFilter filter(params, 45);
  RandomEngine world(derive_seed(45, "standstill"));
  ParticleSet start = particles_at(1000, 0.0, 0.0, 0.5);
  for (Eigen::Index i = 0; i < 1000; ++i) {
    start.x[i] = 0.3 * standard_normal(world);
    start.y[i] = 0.3 * standard_normal(world);
    start.theta[i] = 0.5 + 2.0 * kDeg * standard_normal(world);
  }
  filter.set_particles(start, Eigen::ArrayXd::Ones(1000));
  const double var_start = filter.estimate().covariance(2, 2);
  constexpr double kOmegaVar = 0.0089;
  constexpr double kDt = 0.02;
  constexpr int kFixes = 6000;
  for (int fix = 0; fix < kFixes; ++fix) {
    for (int k = 0; k < 5; ++k) {
      filter.predict(0.0, 0.0, kDt, kOmegaVar);
    }
    filter.update(kFixStd * standard_normal(world), kFixStd * standard_normal(world));
  }
  *expected_rad = std::sqrt(var_start + kOmegaVar * kDt * kDt * 5.0 * kFixes);
  EXPECT_GT(filter.resample_count(), 100u) << "the position was resampled";
  ::testing::Test::RecordProperty(standstill_keeps_heading ? "resamples" : "resamples_whole_particles",
                                  std::to_string(filter.resample_count()));
  return std::sqrt(filter.estimate().covariance(2, 2));
}

TEST(ParticleFilter, AtStandstillTheHeadingSpreadGrowsWithTheOdometrysTurnNoiseDespiteResampling) {
  double expected = 0.0;
  const double kept = heading_std_after_standing_with_fixes(true, &expected);
  RecordProperty("expected_heading_std_deg", std::to_string(expected / kDeg));
  RecordProperty("heading_std_deg", std::to_string(kept / kDeg));
  EXPECT_NEAR(kept, expected, 0.05 * expected);  // measured: 18.87 deg against 18.82
  // Copying whole particles (before): 17.16 deg, 9 % low after ~300 resamplings (a random
  // sub-sample of the headings each time); the same seed, so this is a fixed figure.
  const double thinned = heading_std_after_standing_with_fixes(false, &expected);
  RecordProperty("heading_std_whole_particles_deg", std::to_string(thinned / kDeg));
  EXPECT_LT(thinned, 0.95 * expected) << "whole-particle resampling thins the unobserved heading";
}

TEST(ParticleFilter, NoTurnNoiseWithoutWheelMotion) {
  PfParams params = first_fix_params();
  params.odom_omega_std_radps = 0.0;  // only the motion-proportional parts
  params.init_theta_known = true;
  ParticleFilter filter(params, 42);
  filter.update(0.0, 0.0);
  for (int k = 0; k < 100; ++k) {
    filter.predict(0.0, 0.0, 0.02);
  }
  EXPECT_TRUE((filter.particles().theta == 0.0).all());
  filter.predict(1.0, 0.0, 0.02);  // driving: the wheels' errors spread the heading
  EXPECT_GT(std::sqrt((filter.particles().theta.square()).mean()), 0.5 * 0.05 * 0.02);
}

// Fixes of a robot moved by 10 m: the gate rejects them; once 60 % of the recent fixes are
// rejected the cloud is redrawn around the median of the last five fixes, so an outlier that
// happens to be the last one does not capture it.
TEST(ParticleFilter, RecoversAroundTheMedianOfTheLastFixesAfterAJump) {
  PfParams params = first_fix_params();
  params.init_theta_known = true;
  ParticleFilter filter(params, 43);
  filter.update(0.0, 0.0);
  for (int k = 0; k < 50; ++k) {
    filter.update(0.0, 0.0);  // converge: a tight cloud at the origin
  }
  ASSERT_EQ(filter.recovery_count(), 0u);
  // Share of rejections 1 - 0.9^n > 0.6 first at the 9th inconsistent fix: make it an outlier.
  for (int k = 1; k <= 9; ++k) {
    const double x = k == 9 ? 110.0 : 10.0;
    filter.update(x, 0.0);
    EXPECT_EQ(filter.recovery_count(), k == 9 ? 1u : 0u) << "fix " << k;
    if (k < 9) {
      EXPECT_TRUE(filter.last_update_rejected()) << "fix " << k;
      EXPECT_NEAR(filter.estimate().mean.x(), 0.0, 0.5) << "a rejected fix moves nothing";
    }
  }
  EXPECT_NEAR(filter.estimate().mean.x(), 10.0, 0.5);
  EXPECT_NEAR(filter.estimate().mean.y(), 0.0, 0.5);
  // Half of the redrawn particles got a uniform heading, the others kept theirs (0).
  const double kept = (filter.particles().theta == 0.0).cast<double>().mean();
  EXPECT_NEAR(kept, 0.5, 0.05);
}

TEST(ParticleFilter, WithoutRecoveryAJumpIsNeverFollowed) {
  PfParams params = first_fix_params();
  params.init_theta_known = true;
  params.recovery_nis = 0.0;
  ParticleFilter filter(params, 43);
  for (int k = 0; k < 51; ++k) {
    filter.update(0.0, 0.0);
  }
  for (int k = 0; k < 50; ++k) {
    filter.update(10.0, 0.0);
  }
  EXPECT_NEAR(filter.estimate().mean.x(), 0.0, 0.5);
  EXPECT_EQ(filter.rejected_count(), 50u);
}

// A robot turned by 90 degrees while it creeps: it moves at 0.3 m/s along +y, the filter (heading
// known, wrongly, as 0) along +x. The fixes keep pulling the cloud back, so it stays within a few
// metres and few fixes are rejected, but they are always on the same side: the bias criterion
// notices it well before the others.
std::size_t recoveries_while_creeping_sideways(double recovery_bias_nis, double duration_s) {
  PfParams params = first_fix_params();
  params.init_theta_known = true;
  params.init_theta_rad = 0.0;
  params.recovery_bias_nis = recovery_bias_nis;
  params.prior_heading_tolerance_rad = 0.0;  // the prior check would catch this 90 deg error too
  ParticleFilter filter(params, 46);
  RandomEngine world(derive_seed(46, "creep"));
  double truth_y = 0.0;
  filter.update(0.0, 0.0);
  for (int step = 1; step <= static_cast<int>(duration_s / 0.02); ++step) {
    truth_y += 0.3 * 0.02;
    filter.predict(0.3, 0.0, 0.02);
    if (step % 5 == 0) {
      filter.update(kFixStd * standard_normal(world), truth_y + kFixStd * standard_normal(world));
    }
  }
  return filter.recovery_count();
}

TEST(ParticleFilter, FixesOnOneSideOfTheEstimateTriggerARecovery) {
  EXPECT_GE(recoveries_while_creeping_sideways(40.0, 20.0), 1u);
  EXPECT_EQ(recoveries_while_creeping_sideways(0.0, 20.0), 0u) << "without the bias criterion";
}

// 5 % of the fixes 100 m (or 30 m) off: the gate drops them, no recovery fires, and the track is
// as good as without outliers.
TEST(ParticleFilter, FivePercentOutliersAreRejectedWithoutHarm) {
  for (const double offset : {30.0, 100.0}) {
    PfParams params = first_fix_params();
    params.init_theta_known = true;
    const SimulationConfig config;
    RandomEngine world(derive_seed(44, "outliers"));
    model::Pose2 truth = config.start;
    params.init_theta_rad = truth.theta;
    ParticleFilter tracked(params, 44);
    double sq = 0.0;
    int fixes = 0;
    int outliers = 0;
    for (int step = 1; step <= 6000; ++step) {
      const model::Twist twist = true_twist(step * 0.02);
      truth = model::integrate_exact(truth, twist, 0.02);
      tracked.predict(twist.v + 0.05 * standard_normal(world), twist.omega + 0.02 * standard_normal(world), 0.02);
      if (step % 5 != 0) {
        continue;
      }
      const bool outlier = uniform01(world) < 0.05;
      outliers += outlier ? 1 : 0;
      tracked.update(truth.x + kFixStd * standard_normal(world) + (outlier ? offset : 0.0),
                     truth.y + kFixStd * standard_normal(world));
      const Eigen::Vector3d mean = tracked.estimate().mean;
      sq += std::pow(mean.x() - truth.x, 2) + std::pow(mean.y() - truth.y, 2);
      ++fixes;
    }
    const double rmse = std::sqrt(sq / fixes);
    RecordProperty("offset" + std::to_string(static_cast<int>(offset)) + "_rmse_m", std::to_string(rmse));
    EXPECT_EQ(tracked.recovery_count(), 0u) << offset;
    EXPECT_GE(tracked.rejected_count(), static_cast<std::size_t>(outliers)) << offset;
    EXPECT_LT(rmse, 0.5) << offset;
  }
}

// Issue 27, finding 2: fixes 3x noisier (variance) than configured. The filter estimates the noise
// it sees from its innovations and uses it; assuming the configured noise, it takes correct fixes
// for outliers and keeps redrawing its cloud.
struct NoisyRun {
  std::unique_ptr<ParticleFilter> filter;
  SimulationResult result;
};

NoisyRun run_with_noisier_fixes(int noise_window_fixes, std::uint64_t seed) {
  PfParams params = first_fix_params();
  params.noise_window_fixes = noise_window_fixes;
  SimulationConfig config;
  config.duration_s = 120.0;
  config.fix_std_m = std::sqrt(3.0 * 2.28);
  NoisyRun run{std::make_unique<ParticleFilter>(params, seed), {}};
  run.result = simulate(*run.filter, config, seed);
  return run;
}

TEST(ParticleFilter, EstimatesTheFixNoiseItSeesAndTracksWithFixesThreeTimesNoisier) {
  for (const std::uint64_t seed : {5u, 6u, 7u}) {
    const NoisyRun run = run_with_noisier_fixes(300, seed);
    const ParticleFilter* filter = run.filter.get();
    const SimulationResult& result = run.result;
    RecordProperty("seed" + std::to_string(seed) + "_noise_std_m", std::to_string(filter->measurement_std_estimate_m()));
    RecordProperty("seed" + std::to_string(seed) + "_recoveries", std::to_string(filter->recovery_count()));
    EXPECT_NEAR(filter->measurement_std_estimate_m(), std::sqrt(3.0 * 2.28), 0.15 * std::sqrt(3.0 * 2.28)) << seed;
    EXPECT_LE(filter->recovery_count(), 3u) << seed;
    EXPECT_LT(filter->rejected_count(), 36u) << seed;  // 3 % of 1200 correct fixes
    EXPECT_LT(result.estimate_rmse_m, 0.5 * result.fix_rmse_m) << seed;
    EXPECT_LT(result.final_heading_error_rad, 10.0 * kDeg) << seed;
  }
}

TEST(ParticleFilter, AssumingTheConfiguredNoiseFixesThreeTimesNoisierLookLikeALostFilter) {
  const NoisyRun run = run_with_noisier_fixes(0, 5);
  EXPECT_DOUBLE_EQ(run.filter->measurement_std_estimate_m(), kFixStd);
  // 1200 fixes, all correct: a fifth rejected as outliers (246 on this seed; with the estimate: < 3 %).
  EXPECT_GT(run.filter->rejected_count(), 180u);
}

TEST(ParticleFilter, NoiseEstimateStaysAtTheFloorWhenTheFixesAreAsConfigured) {
  PfParams params = first_fix_params();
  SimulationConfig config;
  ParticleFilter filter(params, 8);
  simulate(filter, config, 8);
  EXPECT_LT(filter.measurement_std_estimate_m(), 1.15 * kFixStd);
  EXPECT_GE(filter.measurement_std_estimate_m(), kFixStd);
}

// Issue 27, finding 3: a heading given as known is confirmed by the fixes' displacement before the
// filter says confirmed(); a wrong one is contradicted and redrawn. Returns the worst heading error
// while valid as the node says it (rad), the first time valid (s; -1 never) and the recoveries.
struct PriorRun {
  double worst_confirmed_error_rad = 0.0;
  double confirmed_at_s = -1.0;
  std::size_t recoveries = 0;
};

PriorRun drive_with_prior(double prior_error_rad, std::uint64_t seed) {
  PfParams params = first_fix_params();
  const SimulationConfig config;
  params.init_theta_known = true;
  params.init_theta_rad = config.start.theta + prior_error_rad;
  ParticleFilter filter(params, seed);
  RandomEngine world(derive_seed(seed, "prior"));
  model::Pose2 truth = config.start;
  PriorRun run;
  bool valid = false;
  for (int step = 1; step <= 3000; ++step) {  // 60 s
    const model::Twist twist{0.3, 0.02};  // creeping, as the controller does while not valid
    truth = model::integrate_exact(truth, twist, 0.02);
    filter.predict(twist.v + 0.05 * standard_normal(world), twist.omega + 0.02 * standard_normal(world), 0.02);
    if (step % 5 != 0) {
      continue;
    }
    filter.update(truth.x + kFixStd * standard_normal(world), truth.y + kFixStd * standard_normal(world));
    // What the node publishes as valid: confirmed and the spread within its default limits.
    valid = filter.confirmed() && next_validity(filter.estimate(), {3.0, 0.2, 0.35}, valid);
    if (valid) {
      const double error = std::abs(wrap_angle(filter.estimate().mean.z() - truth.theta));
      run.worst_confirmed_error_rad = std::max(run.worst_confirmed_error_rad, error);
      if (run.confirmed_at_s < 0.0) {
        run.confirmed_at_s = step * 0.02;
      }
    }
  }
  run.recoveries = filter.recovery_count();
  return run;
}

TEST(ParticleFilter, AHeadingGivenAsKnownButWrongIsNeverConfirmedAndIsRedrawn) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    for (const double error : {2.0944, -2.0944, kPi}) {
      const PriorRun run = drive_with_prior(error, seed);
      EXPECT_GE(run.recoveries, 1u) << seed << " " << error;
      EXPECT_LT(run.worst_confirmed_error_rad, 30.0 * kDeg) << seed << " " << error;
    }
  }
}

TEST(ParticleFilter, ARightHeadingGivenAsKnownIsConfirmedAfterAFewMetres) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const PriorRun run = drive_with_prior(0.05, seed);
    EXPECT_EQ(run.recoveries, 0u) << seed;
    EXPECT_GT(run.confirmed_at_s, 0.0) << seed;
    EXPECT_LT(run.confirmed_at_s, 30.0) << seed << ": 9 m at 0.3 m/s";
  }
}

// One wheel reading 2 % fast on a 0.3 m track: the odometry turn rate is off by 0.067 rad per m
// driven. The particles' turn slip learns it.
TEST(ParticleFilter, LearnsTheTurnSlipOfAWheelThatReadsFast) {
  PfParams params = first_fix_params();
  SimulationConfig config;
  params.init_theta_known = true;
  params.init_theta_rad = config.start.theta;
  ParticleFilter filter(params, 45);
  RandomEngine world(derive_seed(45, "slip"));
  const double track_m = 0.3;
  const double slip = 0.02;
  model::Pose2 truth = config.start;
  double sq = 0.0;
  int fixes = 0;
  for (int step = 1; step <= 6000; ++step) {
    const model::Twist twist = true_twist(step * 0.02);
    truth = model::integrate_exact(truth, twist, 0.02);
    const double right = twist.v + 0.5 * track_m * twist.omega;
    // The right wheel reads (1 + slip) x: v and omega as the odometry computes them.
    const double measured_omega = twist.omega + slip * right / track_m;
    const double measured_v = twist.v + 0.5 * slip * right;
    filter.predict(measured_v, measured_omega, 0.02);
    if (step % 5 == 0) {
      filter.update(truth.x + kFixStd * standard_normal(world), truth.y + kFixStd * standard_normal(world));
      if (step * 0.02 > 30.0) {
        const Eigen::Vector3d mean = filter.estimate().mean;
        sq += std::pow(mean.x() - truth.x, 2) + std::pow(mean.y() - truth.y, 2);
        ++fixes;
      }
    }
  }
  const double learned = (filter.weights() * filter.turn_slips()).sum();
  RecordProperty("turn_slip_learned_radpm", std::to_string(learned));
  RecordProperty("rmse_after_30s_m", std::to_string(std::sqrt(sq / fixes)));
  EXPECT_NEAR(learned, slip / track_m, 0.3 * slip / track_m);
  EXPECT_LT(std::sqrt(sq / fixes), 0.5);
  EXPECT_LT(std::abs(wrap_angle(filter.estimate().mean.z() - truth.theta)), 5.0 * kDeg);
}

// ---- determinism ----

TEST(ParticleFilter, SameSeedGivesABitIdenticalEstimateSequence) {
  for (const auto scheme : {ResamplingScheme::kSystematic, ResamplingScheme::kResidual}) {
    PfParams params = first_fix_params();
    params.resampling = scheme;
    SimulationConfig config;
    config.duration_s = 10.0;
    ParticleFilter a(params, 77);
    ParticleFilter b(params, 77);
    ParticleFilter other(params, 78);
    const SimulationResult run_a = simulate(a, config, 5);
    const SimulationResult run_b = simulate(b, config, 5);
    const SimulationResult run_other = simulate(other, config, 5);
    ASSERT_EQ(run_a.estimates.size(), run_b.estimates.size());
    ASSERT_GT(a.resample_count(), 0u);
    bool differs_from_other = false;
    for (std::size_t k = 0; k < run_a.estimates.size(); ++k) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(run_a.estimates[k][c], run_b.estimates[k][c]) << "fix " << k;  // bitwise
        differs_from_other |= run_a.estimates[k][c] != run_other.estimates[k][c];
      }
    }
    EXPECT_TRUE(same_state(a, b));
    EXPECT_TRUE(differs_from_other) << "the seed has no effect";
  }
}

}  // namespace
}  // namespace robodds::pf_estimator
