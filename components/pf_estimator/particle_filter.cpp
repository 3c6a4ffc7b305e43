#include "components/pf_estimator/particle_filter.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "components/pf_estimator/likelihood.hpp"
#include "components/pf_estimator/regularization.hpp"
#include "components/pf_estimator/resampling.hpp"

namespace robodds::pf {
namespace {

void require_finite_input(const char* function, const char* name, double value) {
  if (!std::isfinite(value)) {
    std::ostringstream message;
    message << function << ": " << name << " must be finite (got " << value << ")";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

ParticleFilter::ParticleFilter(const PfParams& params, std::uint64_t seed)
    : params_(params), engine_(seed), num_particles_(0), last_update_ess_(0.0) {
  params_.validate();
  num_particles_ = params_.num_particles;
  particles_.resize(num_particles_);
  resample_buffer_.resize(num_particles_);
  ancestor_indices_.reserve(static_cast<std::size_t>(num_particles_));
  weights_.resize(num_particles_);
  log_weights_.resize(num_particles_);
  reset_weights_to_uniform();
  last_update_ess_ = static_cast<double>(num_particles_);
  if (params_.init_mode == InitMode::kUniformArea) {
    initialize_uniform();
  }
}

double ParticleFilter::draw_heading() {
  if (params_.init_theta_known) {
    return wrap_angle(params_.init_theta_rad);
  }
  // uniform01 is in [0, 1), so this is uniform in (-pi, pi].
  return kPi - 2.0 * kPi * uniform01(engine_);
}

double ParticleFilter::noise(double std_dev) {
  // No draw for a zero std: cheaper, and still deterministic since params are fixed.
  return std_dev > 0.0 ? std_dev * standard_normal(engine_) : 0.0;
}

void ParticleFilter::reset_weights_to_uniform() {
  const double m = static_cast<double>(num_particles_);
  weights_.setConstant(1.0 / m);
  log_weights_.setConstant(-std::log(m));
}

void ParticleFilter::initialize_uniform() {
  const double width = params_.init_area_max_x - params_.init_area_min_x;
  const double height = params_.init_area_max_y - params_.init_area_min_y;
  for (Eigen::Index i = 0; i < num_particles_; ++i) {
    particles_.x[i] = params_.init_area_min_x + width * uniform01(engine_);
    particles_.y[i] = params_.init_area_min_y + height * uniform01(engine_);
    particles_.theta[i] = draw_heading();
  }
  reset_weights_to_uniform();
  initialized_ = true;
}

void ParticleFilter::initialize_around(double x_m, double y_m) {
  require_finite_input("initialize_around", "x_m", x_m);
  require_finite_input("initialize_around", "y_m", y_m);
  for (Eigen::Index i = 0; i < num_particles_; ++i) {
    particles_.x[i] = x_m + params_.init_fix_std_m * standard_normal(engine_);
    particles_.y[i] = y_m + params_.init_fix_std_m * standard_normal(engine_);
    particles_.theta[i] = draw_heading();
  }
  reset_weights_to_uniform();
  initialized_ = true;
}

void ParticleFilter::predict(double v_mps, double omega_radps, double dt_s) {
  require_finite_input("predict", "v_mps", v_mps);
  require_finite_input("predict", "omega_radps", omega_radps);
  require_finite_input("predict", "dt_s", dt_s);
  if (dt_s < 0.0) {
    std::ostringstream message;
    message << "predict: dt_s must be >= 0 (got " << dt_s << ")";
    throw std::invalid_argument(message.str());
  }
  if (!initialized_ || dt_s == 0.0) {
    return;
  }
  const bool diffuse_theta = params_.process_theta_std_rad > 0.0;
  for (Eigen::Index i = 0; i < num_particles_; ++i) {
    const model::Twist noisy_odometry{v_mps + noise(params_.odom_v_std_mps),
                                      omega_radps + noise(params_.odom_omega_std_radps)};
    const model::Pose2 moved = model::integrate_exact(
        {particles_.x[i], particles_.y[i], particles_.theta[i]}, noisy_odometry, dt_s);
    particles_.x[i] = moved.x + noise(params_.process_pos_std_m);
    particles_.y[i] = moved.y + noise(params_.process_pos_std_m);
    // integrate_exact already wraps; only re-wrap when diffusion can leave (-pi, pi].
    particles_.theta[i] = diffuse_theta
                              ? wrap_angle(moved.theta + noise(params_.process_theta_std_rad))
                              : moved.theta;
  }
}

void ParticleFilter::update(double z_x_m, double z_y_m) {
  require_finite_input("update", "z_x_m", z_x_m);
  require_finite_input("update", "z_y_m", z_y_m);
  if (!initialized_) {
    // Only reachable in kFirstFix mode: the fix places the cloud, so using it again as a
    // likelihood would count it twice.
    initialize_around(z_x_m, z_y_m);
    last_update_ess_ = static_cast<double>(num_particles_);
    last_update_resampled_ = false;
    return;
  }
  add_position_log_likelihood(particles_, z_x_m, z_y_m, params_.measurement_std_m, log_weights_);
  if (!normalize_log_weights(log_weights_, weights_)) {
    reset_weights_to_uniform();
  }
  last_update_ess_ = pf::effective_sample_size(weights_);
  last_update_resampled_ = last_update_ess_ < params_.resample_threshold;
  if (last_update_resampled_) {
    resample();
  }
}

void ParticleFilter::resample() {
  const bool regularize = params_.regularization_scale > 0.0;
  Eigen::Matrix3d jitter_sqrt = Eigen::Matrix3d::Zero();
  if (regularize) {
    // Spread of the weighted cloud *before* resampling: the density the copies are drawn from.
    jitter_sqrt = kernel_square_root(
        weighted_pose_estimate(particles_, weights_).covariance,
        params_.regularization_scale * optimal_kernel_bandwidth(num_particles_));
  }
  if (params_.resampling == ResamplingScheme::kResidual) {
    residual_resample_into(weights_, engine_, ancestor_indices_);
  } else {
    const double u0 = uniform01(engine_) / static_cast<double>(num_particles_);
    systematic_resample_into(weights_, u0, ancestor_indices_);
  }
  for (Eigen::Index j = 0; j < num_particles_; ++j) {
    const auto ancestor = static_cast<Eigen::Index>(ancestor_indices_[static_cast<std::size_t>(j)]);
    resample_buffer_.x[j] = particles_.x[ancestor];
    resample_buffer_.y[j] = particles_.y[ancestor];
    resample_buffer_.theta[j] = particles_.theta[ancestor];
  }
  // Swapping dynamic Eigen arrays exchanges their buffers: no copy, no allocation.
  particles_.x.swap(resample_buffer_.x);
  particles_.y.swap(resample_buffer_.y);
  particles_.theta.swap(resample_buffer_.theta);
  if (regularize) {
    for (Eigen::Index j = 0; j < num_particles_; ++j) {
      const Eigen::Vector3d unit_noise(standard_normal(engine_), standard_normal(engine_),
                                       standard_normal(engine_));
      const Eigen::Vector3d jitter = jitter_sqrt * unit_noise;
      particles_.x[j] += jitter.x();
      particles_.y[j] += jitter.y();
      particles_.theta[j] = wrap_angle(particles_.theta[j] + jitter.z());
    }
  }
  reset_weights_to_uniform();
  ++resample_count_;
}

double ParticleFilter::effective_sample_size() const {
  return pf::effective_sample_size(weights_);
}

PoseEstimate ParticleFilter::estimate() const {
  if (!initialized_) {
    throw std::logic_error("estimate: the particle filter is not initialised yet");
  }
  return weighted_pose_estimate(particles_, weights_);
}

void ParticleFilter::set_particles(const ParticleSet& particles, const Eigen::ArrayXd& weights) {
  const Eigen::Index m = num_particles_;
  if (particles.x.size() != m || particles.y.size() != m || particles.theta.size() != m ||
      weights.size() != m) {
    std::ostringstream message;
    message << "set_particles: every array must have num_particles = " << m << " entries";
    throw std::invalid_argument(message.str());
  }
  if (!particles.x.isFinite().all() || !particles.y.isFinite().all() ||
      !particles.theta.isFinite().all()) {
    throw std::invalid_argument("set_particles: particle states must be finite");
  }
  if (!weights.isFinite().all() || !(weights >= 0.0).all() || !(weights.sum() > 0.0) ||
      !std::isfinite(weights.sum())) {
    throw std::invalid_argument("set_particles: weights must be finite, >= 0, with a positive sum");
  }
  particles_.x = particles.x;
  particles_.y = particles.y;
  particles_.theta = particles.theta.unaryExpr([](double t) { return wrap_angle(t); });
  weights_ = weights / weights.sum();
  log_weights_ = weights_.log();
  initialized_ = true;
}

}  // namespace robodds::pf
