#include "components/uwb_relative_estimator/relative_pf.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/angle.hpp"
#include "components/pf_estimator/resampling.hpp"
#include "components/uwb_relative_estimator/relative_pf_likelihood.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

void require_finite_increment(const char* which, const model::Pose2& increment) {
  if (!std::isfinite(increment.x) || !std::isfinite(increment.y) || !std::isfinite(increment.theta)) {
    throw std::invalid_argument(std::string("RelativePoseFilter::predict: ") + which + " is not finite (got " +
                                model::to_text(increment) + ")");
  }
}

}  // namespace

RelativePoseFilter::RelativePoseFilter(const RelativePfParams& params) : params_(params) {
  params_.validate();
  num_particles_ = params_.num_particles;
  particles_.resize(num_particles_);
  resample_buffer_.resize(num_particles_);
  weights_.resize(num_particles_);
  log_weights_.resize(num_particles_);
  log_likelihood_.resize(num_particles_);
  ancestor_indices_.reserve(static_cast<std::size_t>(num_particles_));
  set_uniform_weights();
  last_update_ess_ = static_cast<double>(num_particles_);
}

void RelativePoseFilter::initialize(const model::Pose2& pose, RandomEngine& engine) {
  require_finite_pose("RelativePoseFilter::initialize", pose);
  for (Eigen::Index s = 0; s < num_particles_; ++s) {
    particles_.x[s] = pose.x + params_.lambda_d_m * standard_normal(engine);
    particles_.y[s] = pose.y + params_.lambda_d_m * standard_normal(engine);
    particles_.theta[s] = wrap_angle(pose.theta + params_.lambda_theta_rad * standard_normal(engine));
  }
  set_uniform_weights();
  last_update_ess_ = static_cast<double>(num_particles_);
  last_update_resampled_ = false;
  initialized_ = true;
}

void RelativePoseFilter::predict(const model::Pose2& own_increment, const model::Pose2& other_increment,
                                 RandomEngine& engine) {
  require_finite_increment("own_increment", own_increment);
  require_finite_increment("other_increment", other_increment);
  if (!initialized_) {
    return;
  }
  const double xy_std = params_.odometry_xy_std_m;
  const double theta_std = params_.odometry_theta_std_rad;
  for (Eigen::Index s = 0; s < num_particles_; ++s) {
    const model::Pose2 own{own_increment.x + xy_std * standard_normal(engine),
                           own_increment.y + xy_std * standard_normal(engine),
                           own_increment.theta + theta_std * standard_normal(engine)};
    const model::Pose2 other{other_increment.x + xy_std * standard_normal(engine),
                             other_increment.y + xy_std * standard_normal(engine),
                             other_increment.theta + theta_std * standard_normal(engine)};
    // j at t-1 seen from i at t, then j at t: inverse(m_i) * x * m_j.
    const model::Pose2 moved = model::compose(model::between(own, particle(s)), other);
    particles_.x[s] = moved.x;
    particles_.y[s] = moved.y;
    particles_.theta[s] = moved.theta;
  }
}

void RelativePoseFilter::update_with_pose(const model::Pose2& measured, RandomEngine& engine) {
  require_finite_pose("RelativePoseFilter::update_with_pose", measured);
  if (!initialized_) {
    initialize(measured, engine);
    return;
  }
  for (Eigen::Index s = 0; s < num_particles_; ++s) {
    log_likelihood_[s] = pose_log_likelihood(particle(s), measured, params_.lambda_d_m, params_.lambda_theta_rad);
  }
  apply_log_likelihood(engine);
}

void RelativePoseFilter::update_with_ranges(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                                            RandomEngine& engine) {
  require_valid_ranges("RelativePoseFilter::update_with_ranges", own, other, ranges_m);
  if (!initialized_) {
    throw std::logic_error("RelativePoseFilter::update_with_ranges: not initialised (call initialize() first, e.g. "
                           "with a single-epoch solve of eq. 1)");
  }
  // range_log_likelihood for every particle, range by range over all particles at once (Eigen's
  // packet arithmetic; sqrt is correctly rounded there too): each particle's terms in its order,
  // so bit for bit its value (issue 29, session 13; uwb_relative_pf_test checks it).
  const Eigen::ArrayXd& x = particles_.x;
  const Eigen::ArrayXd& y = particles_.y;
  Eigen::ArrayXd c(num_particles_);
  Eigen::ArrayXd sn(num_particles_);
  for (Eigen::Index i = 0; i < num_particles_; ++i) {
    c[i] = std::cos(particles_.theta[i]);
    sn[i] = std::sin(particles_.theta[i]);
  }
  Eigen::ArrayXd sum_sq = Eigen::ArrayXd::Zero(num_particles_);
  Eigen::ArrayXd dx(num_particles_);
  Eigen::ArrayXd dy(num_particles_);
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    const Eigen::Vector2d& node_i = own.nodes_m[k];
    for (std::size_t l = 0; l < other.nodes_m.size(); ++l) {
      const Eigen::Vector2d& node_j = other.nodes_m[l];
      dx = x + c * node_j.x() - sn * node_j.y() - node_i.x();
      dy = y + sn * node_j.x() + c * node_j.y() - node_i.y();
      sum_sq += (ranges_m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) - (dx * dx + dy * dy).sqrt()).square();
    }
  }
  log_likelihood_ = -0.5 * sum_sq / (params_.range_std_m * params_.range_std_m);
  apply_log_likelihood(engine);
}

void RelativePoseFilter::apply_log_likelihood(RandomEngine& engine) {
  log_weights_ += log_likelihood_;
  const double max_log = log_weights_.maxCoeff();
  if (!std::isfinite(max_log)) {
    // Every particle impossible (an overflowing residual): no information left, start uniform.
    set_uniform_weights();
  } else {
    log_weights_ -= max_log;
    weights_ = log_weights_.exp();
    const double total = weights_.sum();  // >= 1: the best particle has weight exp(0)
    weights_ /= total;
    log_weights_ -= std::log(total);
  }
  last_update_ess_ = pf_estimator::effective_sample_size(weights_);
  last_update_resampled_ = params_.resample_ess_fraction >= 1.0 ||
                           last_update_ess_ < params_.resample_ess_fraction * static_cast<double>(num_particles_);
  if (last_update_resampled_) {
    resample(engine);
  }
}

void RelativePoseFilter::resample(RandomEngine& engine) {
  const double u0 = uniform01(engine) / static_cast<double>(num_particles_);
  pf_estimator::systematic_resample_into(weights_, u0, ancestor_indices_);
  for (Eigen::Index s = 0; s < num_particles_; ++s) {
    const auto a = static_cast<Eigen::Index>(ancestor_indices_[static_cast<std::size_t>(s)]);
    resample_buffer_.x[s] = particles_.x[a];
    resample_buffer_.y[s] = particles_.y[a];
    resample_buffer_.theta[s] = particles_.theta[a];
  }
  std::swap(particles_, resample_buffer_);
  set_uniform_weights();
  ++resample_count_;
}

void RelativePoseFilter::set_uniform_weights() {
  weights_.setConstant(1.0 / static_cast<double>(num_particles_));
  log_weights_.setConstant(-std::log(static_cast<double>(num_particles_)));
}

pf_estimator::PoseEstimate RelativePoseFilter::estimate() const {
  if (!initialized_) {
    throw std::logic_error("RelativePoseFilter::estimate: not initialised");
  }
  return pf_estimator::weighted_pose_estimate(particles_, weights_);
}

model::Pose2 RelativePoseFilter::estimated_pose() const {
  const pf_estimator::PoseEstimate e = estimate();
  return {e.mean[0], e.mean[1], wrap_angle(e.mean[2])};
}

}  // namespace robodds::uwb_relative_estimator
