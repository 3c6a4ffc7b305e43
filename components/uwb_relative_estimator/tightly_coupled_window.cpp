#include "components/uwb_relative_estimator/tightly_coupled_window.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <ceres/ceres.h>

#include "common/angle.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

/// compose(between(m_i, x), m_j) on arrays, and its Jacobian with respect to x (3 x 3).
void predict_pose(const double* x, const model::Pose2& mi, const model::Pose2& mj, double* out,
                  Eigen::Matrix3d* jacobian) {
  const double ci = std::cos(mi.theta);
  const double si = std::sin(mi.theta);
  const double dx = x[0] - mi.x;
  const double dy = x[1] - mi.y;
  const double yx = ci * dx + si * dy;
  const double yy = -si * dx + ci * dy;
  const double yt = x[2] - mi.theta;
  const double c = std::cos(yt);
  const double s = std::sin(yt);
  out[0] = yx + c * mj.x - s * mj.y;
  out[1] = yy + s * mj.x + c * mj.y;
  out[2] = yt + mj.theta;
  if (jacobian != nullptr) {
    *jacobian << ci, si, -s * mj.x - c * mj.y,  //
        -si, ci, c * mj.x - s * mj.y,           //
        0.0, 0.0, 1.0;
  }
}

/// The K x L ranges of one epoch: (d_kl(x) + c + b_kl - r_kl) / sigma.
class RangeCost : public ceres::CostFunction {
 public:
  RangeCost(const model::UwbArray& own, const model::UwbArray& peer, const Eigen::VectorXd& ranges, double sigma,
            bool links)
      : own_(own), peer_(peer), ranges_(ranges), inv_sigma_(1.0 / sigma), links_(links) {
    const int n = static_cast<int>(ranges.size());
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(3);
    mutable_parameter_block_sizes()->push_back(1);
    if (links_) {
      mutable_parameter_block_sizes()->push_back(n);
    }
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* x = parameters[0];
    const double common = parameters[1][0];
    const double c = std::cos(x[2]);
    const double s = std::sin(x[2]);
    const int n = static_cast<int>(ranges_.size());
    const std::size_t cols = peer_.nodes_m.size();
    if (jacobians != nullptr && links_ && jacobians[2] != nullptr) {
      std::fill(jacobians[2], jacobians[2] + n * n, 0.0);
    }
    for (std::size_t k = 0; k < own_.nodes_m.size(); ++k) {
      for (std::size_t l = 0; l < cols; ++l) {
        const int i = static_cast<int>(k * cols + l);
        const Eigen::Vector2d& nj = peer_.nodes_m[l];
        const Eigen::Vector2d& ni = own_.nodes_m[k];
        const double rx = c * nj.x() - s * nj.y();
        const double ry = s * nj.x() + c * nj.y();
        const double vx = x[0] + rx - ni.x();
        const double vy = x[1] + ry - ni.y();
        const double d = std::sqrt(vx * vx + vy * vy);
        const double bias = links_ ? parameters[2][i] : 0.0;
        residuals[i] = (d + common + bias - ranges_(i)) * inv_sigma_;
        if (jacobians != nullptr) {
          if (jacobians[0] != nullptr) {
            const double inv_d = d > 1e-9 ? inv_sigma_ / d : 0.0;
            jacobians[0][3 * i + 0] = vx * inv_d;
            jacobians[0][3 * i + 1] = vy * inv_d;
            jacobians[0][3 * i + 2] = (vx * -ry + vy * rx) * inv_d;
          }
          if (jacobians[1] != nullptr) {
            jacobians[1][i] = inv_sigma_;
          }
          if (links_ && jacobians[2] != nullptr) {
            jacobians[2][i * n + i] = inv_sigma_;
          }
        }
      }
    }
    return true;
  }

 private:
  const model::UwbArray& own_;
  const model::UwbArray& peer_;
  Eigen::VectorXd ranges_;
  double inv_sigma_;
  bool links_;
};

/// Gauss-Markov step of n independent states: (b_t - a b_{t-1}) / sigma_q.
class GaussMarkovCost : public ceres::CostFunction {
 public:
  GaussMarkovCost(int n, double a, double sigma_q) : n_(n), a_(a), inv_(1.0 / sigma_q) {
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(n);
    mutable_parameter_block_sizes()->push_back(n);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    for (int i = 0; i < n_; ++i) {
      residuals[i] = (parameters[1][i] - a_ * parameters[0][i]) * inv_;
    }
    if (jacobians != nullptr) {
      for (int b = 0; b < 2; ++b) {
        if (jacobians[b] != nullptr) {
          std::fill(jacobians[b], jacobians[b] + n_ * n_, 0.0);
          for (int i = 0; i < n_; ++i) {
            jacobians[b][i * n_ + i] = b == 0 ? -a_ * inv_ : inv_;
          }
        }
      }
    }
    return true;
  }

 private:
  int n_;
  double a_;
  double inv_;
};

/// Relative motion between consecutive epochs: S (x_t - compose(between(m_i, x_{t-1}), m_j)).
class MotionCost : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  MotionCost(const model::Pose2& mi, const model::Pose2& mj, const Eigen::Matrix3d& sqrt_information)
      : mi_(mi), mj_(mj), s_(sqrt_information) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    double predicted[3];
    Eigen::Matrix3d jp;
    predict_pose(parameters[0], mi_, mj_, predicted, &jp);
    const Eigen::Vector3d e(parameters[1][0] - predicted[0], parameters[1][1] - predicted[1],
                            wrap_angle(parameters[1][2] - predicted[2]));
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = s_ * e;
    if (jacobians != nullptr) {
      if (jacobians[0] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobians[0]);
        j = -s_ * jp;
      }
      if (jacobians[1] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> j(jacobians[1]);
        j = s_;
      }
    }
    return true;
  }

 private:
  model::Pose2 mi_;
  model::Pose2 mj_;
  Eigen::Matrix3d s_;
};

/// Dense prior on one epoch's states [pose, common, links]: S (p - p0) + s0, heading wrapped.
class PriorCost : public ceres::CostFunction {
 public:
  PriorCost(const Eigen::MatrixXd& s, const Eigen::VectorXd& offset, const Eigen::VectorXd& p0, bool links)
      : s_(s), offset_(offset), p0_(p0), links_(links) {
    set_num_residuals(static_cast<int>(s.rows()));
    mutable_parameter_block_sizes()->push_back(3);
    mutable_parameter_block_sizes()->push_back(1);
    if (links_) {
      mutable_parameter_block_sizes()->push_back(static_cast<int>(s.cols()) - 4);
    }
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = static_cast<int>(s_.cols());
    Eigen::VectorXd dp(n);
    for (int i = 0; i < 3; ++i) {
      dp(i) = parameters[0][i] - p0_(i);
    }
    dp(2) = wrap_angle(dp(2));
    dp(3) = parameters[1][0] - p0_(3);
    for (int i = 4; i < n; ++i) {
      dp(i) = parameters[2][i - 4] - p0_(i);
    }
    Eigen::Map<Eigen::VectorXd> r(residuals, n);
    r = s_ * dp + offset_;
    if (jacobians != nullptr) {
      const int sizes[3] = {3, 1, n - 4};
      int column = 0;
      for (int b = 0; b < (links_ ? 3 : 2); ++b) {
        if (jacobians[b] != nullptr) {
          Eigen::Map<RowMatrix>(jacobians[b], n, sizes[b]) = s_.middleCols(column, sizes[b]);
        }
        column += sizes[b];
      }
    }
    return true;
  }

 private:
  Eigen::MatrixXd s_;
  Eigen::VectorXd offset_;
  Eigen::VectorXd p0_;
  bool links_;
};

/// A residual block and the parameter blocks it reads.
struct Factor {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<double*> parameters;
};

/// The factors between consecutive epochs `prev` and `next` (the window's Epoch): the relative
/// motion of both odometries, and the Gauss-Markov transitions of the pair's common mode and of
/// the link biases (exact discretisation over their time step) when they are states. `kl`: links.
template <class Epoch>
void add_transition_factors(std::vector<Factor>& factors, const TightWindowParams& params, int kl, Epoch& prev,
                            Epoch& next) {
  const double dt = next.time_s - prev.time_s;
  factors.push_back(Factor{std::make_unique<MotionCost>(next.own_increment, next.peer_increment, next.motion_sqrt_information),
                           {prev.pose, next.pose}});
  if (params.common_bias_state) {
    const double a = std::exp(-dt / params.common_time_s);
    const double q = params.common_std_m * std::sqrt(std::max(1.0 - a * a, 1e-12));
    factors.push_back(Factor{std::make_unique<GaussMarkovCost>(1, a, q), {&prev.common, &next.common}});
  }
  if (params.link_bias_states) {
    const double a = std::exp(-dt / params.link_bias_time_s);
    const double q = params.link_bias_std_m * std::sqrt(std::max(1.0 - a * a, 1e-12));
    factors.push_back(Factor{std::make_unique<GaussMarkovCost>(kl, a, q), {prev.links.data(), next.links.data()}});
  }
}

/// Adds J^T J and J^T r of `factors` to H and g, for the parameter blocks `offset_of` maps to an
/// index (others ignored).
template <class OffsetOf>
void accumulate(const std::vector<Factor>& factors, const OffsetOf& offset_of, Eigen::MatrixXd& h, Eigen::VectorXd& g) {
  for (const Factor& factor : factors) {
    const ceres::CostFunction& cost = *factor.cost;
    const int m = cost.num_residuals();
    const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
    std::vector<RowMatrix> jac(sizes.size());
    std::vector<double*> jp(sizes.size());
    for (std::size_t b = 0; b < sizes.size(); ++b) {
      jac[b].resize(m, sizes[b]);
      jp[b] = jac[b].data();
    }
    Eigen::VectorXd r(m);
    cost.Evaluate(factor.parameters.data(), r.data(), jp.data());
    for (std::size_t a = 0; a < sizes.size(); ++a) {
      const int oa = offset_of(factor.parameters[a]);
      if (oa < 0) {
        continue;
      }
      g.segment(oa, sizes[a]) += jac[a].transpose() * r;
      for (std::size_t b = 0; b < sizes.size(); ++b) {
        const int ob = offset_of(factor.parameters[b]);
        if (ob >= 0) {
          h.block(oa, ob, sizes[a], sizes[b]) += jac[a].transpose() * jac[b];
        }
      }
    }
  }
}

}  // namespace

const params::ParamTable<TightWindowParams>& tight_window_param_table() {
  using P = TightWindowParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Tightly coupled fixed-lag estimator (issue 28): ranges, both odometries, range biases as states.")
          .add("window_epochs", &P::window_epochs, "epochs", params::at_least(2),
               "epochs in the fixed-lag window (older ones are marginalised into a prior)")
          .add("white_std_m", &P::white_std_m, "m", params::positive(), "white range noise std (sensor white_sigma_m)")
          .add("link_bias_std_m", &P::link_bias_std_m, "m", params::positive(),
               "Gauss-Markov bias of each link: std (sensor link_bias_sigma_m)")
          .add("link_bias_time_s", &P::link_bias_time_s, "s", params::positive(),
               "Gauss-Markov bias of each link: time constant (sensor link_bias_tau_s)")
          .add("common_std_m", &P::common_std_m, "m", params::positive(),
               "Gauss-Markov common mode of the pair: std (sensor common_sigma_m)")
          .add("common_time_s", &P::common_time_s, "s", params::positive(),
               "Gauss-Markov common mode of the pair: time constant (sensor common_tau_s)")
          .add("common_bias_state", &P::common_bias_state, "", params::any<bool>(),
               "the common mode as a state (false: held at 0, the ablation)")
          .add("link_bias_states", &P::link_bias_states, "", params::any<bool>(),
               "one bias state per link (false: their variance added to the white noise)")
          .add("odometry_xy_std_m", &P::odometry_xy_std_m, "m", params::positive(),
               "odometry increment position std per robot and epoch")
          .add("odometry_theta_std_rad", &P::odometry_theta_std_rad, "rad", params::positive(),
               "odometry increment heading std per robot and epoch")
          .add("start_xy_std_m", &P::start_xy_std_m, "m", params::positive(), "prior std of the first position around its fix")
          .add("start_theta_std_rad", &P::start_theta_std_rad, "rad", params::positive(),
               "prior std of the first heading around its fix")
          .add("max_iterations", &P::max_iterations, "", params::at_least(1), "Levenberg-Marquardt iterations per epoch")
          .add("restart_after_gap_s", &P::restart_after_gap_s, "s", params::positive(),
               "restart from the next eq. (1) fix after this long without ranges")
          .add("disagreement_position_m", &P::disagreement_position_m, "m", params::positive(),
               "restart from the fix when further from it than this ...")
          .add("disagreement_heading_rad", &P::disagreement_heading_rad, "rad", params::positive(),
               "... or than this in heading ...")
          .add("disagreement_epochs", &P::disagreement_epochs, "epochs", params::at_least(1),
               "... for this many epochs in a row");
  return table;
}

void TightWindowParams::validate() const { tight_window_param_table().check_ranges(*this); }

TightlyCoupledWindow::TightlyCoupledWindow(model::UwbArray own_array, model::UwbArray peer_array, TightWindowParams params)
    : own_array_(std::move(own_array)), peer_array_(std::move(peer_array)), params_(params) {
  params_.validate();
  model::check_array("own_array", own_array_);
  model::check_array("peer_array", peer_array_);
}

int TightlyCoupledWindow::epoch_size() const {
  return 4 + (params_.link_bias_states ? static_cast<int>(own_array_.nodes_m.size() * peer_array_.nodes_m.size()) : 0);
}

model::Pose2 TightlyCoupledWindow::pose() const {
  if (epochs_.empty()) {
    return model::Pose2{};
  }
  const Epoch& e = epochs_.back();
  return model::Pose2{e.pose[0], e.pose[1], wrap_angle(e.pose[2])};
}

double TightlyCoupledWindow::common_bias_m() const { return epochs_.empty() ? 0.0 : epochs_.back().common; }

void TightlyCoupledWindow::start(double time_s, const model::Pose2& fix) {
  epochs_.clear();
  Epoch e;
  e.time_s = time_s;
  e.pose[0] = fix.x;
  e.pose[1] = fix.y;
  e.pose[2] = fix.theta;
  const int n = epoch_size();
  e.links.assign(static_cast<std::size_t>(n - 4), 0.0);
  epochs_.push_back(std::move(e));
  Eigen::VectorXd inv_std(n);
  inv_std << 1.0 / params_.start_xy_std_m, 1.0 / params_.start_xy_std_m, 1.0 / params_.start_theta_std_rad,
      1.0 / params_.common_std_m, Eigen::VectorXd::Constant(n - 4, 1.0 / params_.link_bias_std_m);
  prior_.sqrt_information = inv_std.asDiagonal();
  prior_.offset = Eigen::VectorXd::Zero(n);
  prior_.linearization = Eigen::VectorXd::Zero(n);
  prior_.linearization.head<3>() << fix.x, fix.y, fix.theta;
  disagreements_ = 0;
}

bool TightlyCoupledWindow::step(double time_s, const model::Pose2& own_increment, const model::Pose2& peer_increment,
                                const std::optional<Eigen::MatrixXd>& ranges_m, const std::optional<model::Pose2>& fix) {
  if (!std::isfinite(time_s) || !finite(own_increment) || !finite(peer_increment) || (fix && !finite(*fix))) {
    throw std::invalid_argument("TightlyCoupledWindow::step: non-finite time, increment or fix");
  }
  if (!epochs_.empty() && time_s < epochs_.back().time_s) {
    throw std::invalid_argument("TightlyCoupledWindow::step: time goes back");
  }
  std::optional<Eigen::VectorXd> ranges;
  if (ranges_m) {
    if (ranges_m->rows() != static_cast<Eigen::Index>(own_array_.nodes_m.size()) ||
        ranges_m->cols() != static_cast<Eigen::Index>(peer_array_.nodes_m.size()) || !ranges_m->allFinite()) {
      throw std::invalid_argument("TightlyCoupledWindow::step: ranges do not fit the arrays or are not finite");
    }
    Eigen::VectorXd flat(ranges_m->size());
    for (Eigen::Index k = 0; k < ranges_m->rows(); ++k) {
      for (Eigen::Index l = 0; l < ranges_m->cols(); ++l) {
        flat(k * ranges_m->cols() + l) = (*ranges_m)(k, l);
      }
    }
    ranges = std::move(flat);
  }
  if (!epochs_.empty() && fix && last_ranges_s_ && time_s - *last_ranges_s_ > params_.restart_after_gap_s) {
    epochs_.clear();
    ++restarts_;
  }
  if (epochs_.empty()) {
    if (!fix) {
      return false;
    }
    start(time_s, *fix);
  } else {
    const Epoch& prev = epochs_.back();
    Epoch e;
    e.time_s = time_s;
    e.own_increment = own_increment;
    e.peer_increment = peer_increment;
    predict_pose(prev.pose, own_increment, peer_increment, e.pose, nullptr);
    const double dt = time_s - prev.time_s;
    e.common = std::exp(-dt / params_.common_time_s) * prev.common;
    const double a = std::exp(-dt / params_.link_bias_time_s);
    e.links.resize(prev.links.size());
    for (std::size_t i = 0; i < prev.links.size(); ++i) {
      e.links[i] = a * prev.links[i];
    }
    // Noise of both increments through the composition, at the previous estimate.
    const model::Pose2 at{prev.pose[0], prev.pose[1], prev.pose[2]};
    const Eigen::Matrix<double, 3, 9> j = relative_motion_jacobian(at, own_increment, peer_increment);
    const double vxy = params_.odometry_xy_std_m * params_.odometry_xy_std_m;
    const double vt = params_.odometry_theta_std_rad * params_.odometry_theta_std_rad;
    const Eigen::Matrix3d increment = Eigen::Vector3d(vxy, vxy, vt).asDiagonal();
    const Eigen::Matrix3d q = j.middleCols<3>(3) * increment * j.middleCols<3>(3).transpose() +
                              j.middleCols<3>(6) * increment * j.middleCols<3>(6).transpose();
    const Eigen::Matrix3d l = q.llt().matrixL();
    e.motion_sqrt_information = l.inverse();
    epochs_.push_back(std::move(e));
  }
  epochs_.back().ranges = ranges;
  if (ranges) {
    last_ranges_s_ = time_s;
  }
  bool converged = solve();
  while (epochs_.size() > static_cast<std::size_t>(params_.window_epochs)) {
    marginalize_oldest();
  }
  if (fix) {
    const model::Pose2 p = pose();
    const bool far = std::hypot(p.x - fix->x, p.y - fix->y) > params_.disagreement_position_m ||
                     std::abs(wrap_angle(p.theta - fix->theta)) > params_.disagreement_heading_rad;
    disagreements_ = far ? disagreements_ + 1 : 0;
    if (disagreements_ >= params_.disagreement_epochs) {
      ++restarts_;
      start(time_s, *fix);
      epochs_.back().ranges = ranges;
      converged = solve();
    }
  }
  const model::Pose2 p = pose();
  return converged && finite(p) && covariance_.allFinite() && last_ranges_s_ &&
         time_s - *last_ranges_s_ <= params_.restart_after_gap_s;
}

bool TightlyCoupledWindow::solve() {
  const bool links = params_.link_bias_states;
  const int n = epoch_size();
  const int kl = static_cast<int>(own_array_.nodes_m.size() * peer_array_.nodes_m.size());
  double white = params_.white_std_m;
  if (!links) {
    white = std::hypot(params_.white_std_m, params_.link_bias_std_m);
  }
  std::vector<Factor> factors;
  factors.reserve(4 * epochs_.size() + 1);
  auto blocks = [&](Epoch& e) {
    std::vector<double*> p{e.pose, &e.common};
    if (links) {
      p.push_back(e.links.data());
    }
    return p;
  };
  factors.push_back(Factor{std::make_unique<PriorCost>(prior_.sqrt_information, prior_.offset, prior_.linearization, links),
                           blocks(epochs_.front())});
  for (std::size_t t = 0; t < epochs_.size(); ++t) {
    Epoch& e = epochs_[t];
    if (e.ranges) {
      factors.push_back(Factor{std::make_unique<RangeCost>(own_array_, peer_array_, *e.ranges, white, links), blocks(e)});
    }
    if (t == 0) {
      continue;
    }
    add_transition_factors(factors, params_, kl, epochs_[t - 1], e);
  }

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const Factor& f : factors) {
    problem.AddResidualBlock(f.cost.get(), nullptr, f.parameters);
  }
  if (!params_.common_bias_state) {
    for (Epoch& e : epochs_) {
      e.common = 0.0;
      problem.SetParameterBlockConstant(&e.common);
    }
  }
  ceres::Solver::Options options;
  // A dense Schur complement after eliminating an independent set of blocks that Ceres picks (issue
  // 29): BM_TcEpoch 0.275 -> 0.25 ms CPU per epoch against the sparse normal Cholesky of the whole
  // window (EIGEN_SPARSE; its 20 x 20 blocks are dense). No user ordering: Ceres then takes the set
  // in the order the blocks were added (ComputeStableSchurOrdering), deterministic; a user ordering's
  // groups are sets ordered by address, which made the estimates follow the heap.
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.max_num_iterations = params_.max_iterations;
  // Warm-started like the window: the first step nearly Gauss-Newton's (Ceres' default radius 1e4
  // damps it), as the window's solver options (issue 29): 0.33 -> 0.28 ms CPU per epoch
  // (relative_estimator_bench BM_TcEpoch).
  options.initial_trust_region_radius = 1e6;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  const bool converged = summary.termination_type == ceres::CONVERGENCE ||
                         (summary.termination_type == ceres::NO_CONVERGENCE && summary.iterations.size() > 1);

  // Information of the whole window at the solution, then block-tridiagonal elimination from the
  // oldest epoch to the newest: the newest epoch's marginal covariance.
  const int epochs = static_cast<int>(epochs_.size());
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(epochs * n, epochs * n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(epochs * n);
  const auto offset_of = [&](const double* p) {
    for (int t = 0; t < epochs; ++t) {
      const Epoch& e = epochs_[static_cast<std::size_t>(t)];
      if (p == e.pose) return t * n;
      if (p == &e.common) return t * n + 3;
      if (links && p == e.links.data()) return t * n + 4;
    }
    return -1;
  };
  accumulate(factors, offset_of, h, g);
  if (!params_.common_bias_state) {
    for (int t = 0; t < epochs; ++t) {
      h(t * n + 3, t * n + 3) += 1e12;  // held at zero
    }
  }
  Eigen::MatrixXd d = h.topLeftCorner(n, n);
  for (int t = 1; t < epochs; ++t) {
    const Eigen::MatrixXd coupling = h.block(t * n, (t - 1) * n, n, n);
    d = h.block(t * n, t * n, n, n) - coupling * d.ldlt().solve(coupling.transpose());
  }
  const Eigen::MatrixXd newest = d.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  covariance_ = 0.5 * (newest.topLeftCorner<3, 3>() + newest.topLeftCorner<3, 3>().transpose());
  common_std_ = params_.common_bias_state ? std::sqrt(std::max(newest(3, 3), 0.0)) : 0.0;
  return converged;
}

void TightlyCoupledWindow::marginalize_oldest() {
  const bool links = params_.link_bias_states;
  const int n = epoch_size();
  const int kl = n - 4;
  Epoch& old = epochs_[0];
  Epoch& next = epochs_[1];
  double white = params_.white_std_m;
  if (!links) {
    white = std::hypot(params_.white_std_m, params_.link_bias_std_m);
  }
  auto blocks = [&](Epoch& e) {
    std::vector<double*> p{e.pose, &e.common};
    if (links) {
      p.push_back(e.links.data());
    }
    return p;
  };
  std::vector<Factor> factors;
  factors.push_back(
      Factor{std::make_unique<PriorCost>(prior_.sqrt_information, prior_.offset, prior_.linearization, links), blocks(old)});
  if (old.ranges) {
    factors.push_back(Factor{std::make_unique<RangeCost>(own_array_, peer_array_, *old.ranges, white, links), blocks(old)});
  }
  add_transition_factors(factors, params_, kl, old, next);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * n);
  const auto offset_of = [&](const double* p) {
    if (p == old.pose) return 0;
    if (p == &old.common) return 3;
    if (links && p == old.links.data()) return 4;
    if (p == next.pose) return n;
    if (p == &next.common) return n + 3;
    if (links && p == next.links.data()) return n + 4;
    return -1;
  };
  accumulate(factors, offset_of, h, g);
  if (!params_.common_bias_state) {
    h(3, 3) += 1e12;      // held at zero: nothing of it passes on
    h(n + 3, n + 3) += 1.0;  // keeps the prior positive definite (the state is constant anyway)
  }
  const Eigen::LDLT<Eigen::MatrixXd> oo(h.topLeftCorner(n, n));
  const Eigen::MatrixXd no = h.block(n, 0, n, n);
  Eigen::MatrixXd hm = h.bottomRightCorner(n, n) - no * oo.solve(no.transpose());
  const Eigen::VectorXd gm = g.tail(n) - no * oo.solve(g.head(n));
  hm = 0.5 * (hm + hm.transpose()) + 1e-9 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::LLT<Eigen::MatrixXd> llt(hm);
  const Eigen::MatrixXd u = llt.matrixU();
  prior_.sqrt_information = u;
  prior_.offset = u.transpose().triangularView<Eigen::Lower>().solve(gm);
  prior_.linearization.resize(n);
  prior_.linearization << next.pose[0], next.pose[1], next.pose[2], next.common,
      Eigen::Map<const Eigen::VectorXd>(next.links.data(), kl);
  epochs_.pop_front();
}

}  // namespace robodds::uwb_relative_estimator
