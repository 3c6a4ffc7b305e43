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
#include "components/uwb_relative_estimator/lm_trust_region.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

/// compose(between(m_i, x), m_j) on arrays, and its Jacobians with respect to x, m_i and m_j (3 x 3
/// each; those not wanted nullptr).
void predict_pose(const double* x, const model::Pose2& mi, const model::Pose2& mj, double* out,
                  Eigen::Matrix3d* jacobian, Eigen::Matrix3d* jacobian_mi = nullptr,
                  Eigen::Matrix3d* jacobian_mj = nullptr) {
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
  if (jacobian_mi != nullptr) {
    *jacobian_mi << -ci, -si, yy + s * mj.x + c * mj.y,  //
        si, -ci, -yx - c * mj.x + s * mj.y,              //
        0.0, 0.0, -1.0;
  }
  if (jacobian_mj != nullptr) {
    *jacobian_mj << c, -s, 0.0,  //
        s, c, 0.0,               //
        0.0, 0.0, 1.0;
  }
}

/// An odometry increment m corrected by its robot's slips: scale s (distance and turn read
/// (1 + s) x the true ones) and curvature k (rad per metre driven): the turn error is
/// e = s theta + k d (d the chord, signed by the direction of travel), the true turn theta - e,
/// the chord (1 - s) x the measured one turned by -e / 2 (a chord points half way through the
/// turn). First order in (s, k), as they are ~1e-2. `jacobian`: d(corrected) / d(s, k).
model::Pose2 corrected_increment(const model::Pose2& m, double scale, double curvature,
                                 Eigen::Matrix<double, 3, 2>* jacobian) {
  const double d = std::copysign(std::hypot(m.x, m.y), m.x);
  const double e = scale * m.theta + curvature * d;
  const double a = -0.5 * e;
  const double ca = std::cos(a);
  const double sa = std::sin(a);
  const double f = 1.0 - scale;
  const model::Pose2 out{f * (ca * m.x - sa * m.y), f * (sa * m.x + ca * m.y), m.theta - e};
  if (jacobian != nullptr) {
    // d(chord)/de = f R'(a) p (-1/2), R'(a) p = (-sa x - ca y, ca x - sa y).
    const double gx = -0.5 * f * (-sa * m.x - ca * m.y);
    const double gy = -0.5 * f * (ca * m.x - sa * m.y);
    *jacobian << -(ca * m.x - sa * m.y) + gx * m.theta, gx * d,  //
        -(sa * m.x + ca * m.y) + gy * m.theta, gy * d,           //
        -m.theta, -d;
  }
  return out;
}

/// The K x L ranges of one epoch: (d_kl(x) + c + b_kl - r_kl) / sigma_kl. With `first_estimate`,
/// the Jacobian with respect to the pose is taken there instead of at x (first-estimates Jacobian:
/// an epoch whose states the marginalisation prior holds keeps the linearisation point of that
/// prior, so the window does not gain information the prior and the factor would not have at one
/// point).
class RangeCost : public ceres::CostFunction {
 public:
  RangeCost(const model::UwbArray& own, const model::UwbArray& peer, const Eigen::VectorXd& ranges,
            Eigen::VectorXd inv_sigma, bool links, std::optional<Eigen::Vector3d> first_estimate = std::nullopt)
      : own_(own), peer_(peer), ranges_(ranges), inv_sigma_(std::move(inv_sigma)), links_(links),
        first_estimate_(first_estimate) {
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
    const double* xj = first_estimate_ ? first_estimate_->data() : x;
    const double common = parameters[1][0];
    const double c = std::cos(x[2]);
    const double s = std::sin(x[2]);
    const double cj = std::cos(xj[2]);
    const double sj = std::sin(xj[2]);
    const int n = static_cast<int>(ranges_.size());
    const std::size_t cols = peer_.nodes_m.size();
    if (jacobians != nullptr && links_ && jacobians[2] != nullptr) {
      std::fill(jacobians[2], jacobians[2] + n * n, 0.0);
    }
    for (std::size_t k = 0; k < own_.nodes_m.size(); ++k) {
      for (std::size_t l = 0; l < cols; ++l) {
        const int i = static_cast<int>(k * cols + l);
        const double w = inv_sigma_(i);
        const Eigen::Vector2d& nj = peer_.nodes_m[l];
        const Eigen::Vector2d& ni = own_.nodes_m[k];
        const NodePairGeometry g = node_pair_geometry(x[0], x[1], c, s, ni, nj);
        const double bias = links_ ? parameters[2][i] : 0.0;
        residuals[i] = (g.d + common + bias - ranges_(i)) * w;
        if (jacobians != nullptr) {
          if (jacobians[0] != nullptr) {
            // First-estimates Jacobians: the derivative at the linearisation point, not at x.
            const NodePairGeometry j = first_estimate_ ? node_pair_geometry(xj[0], xj[1], cj, sj, ni, nj) : g;
            const double inv_d = j.d > 1e-9 ? w / j.d : 0.0;
            jacobians[0][3 * i + 0] = j.dx * inv_d;
            jacobians[0][3 * i + 1] = j.dy * inv_d;
            jacobians[0][3 * i + 2] = (j.dx * -j.ry + j.dy * j.rx) * inv_d;
          }
          if (jacobians[1] != nullptr) {
            jacobians[1][i] = w;
          }
          if (links_ && jacobians[2] != nullptr) {
            jacobians[2][i * n + i] = w;
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
  Eigen::VectorXd inv_sigma_;
  bool links_;
  std::optional<Eigen::Vector3d> first_estimate_;
};

/// Gauss-Markov step of n independent states of one time constant: (b_t - a b_{t-1}) / sigma_q,
/// sigma_q per state (one for all when `inv` has one entry: 1 / sigma_q).
class GaussMarkovCost : public ceres::CostFunction {
 public:
  GaussMarkovCost(int n, double a, std::vector<double> inv) : n_(n), a_(a), inv_(std::move(inv)) {
    set_num_residuals(n);
    mutable_parameter_block_sizes()->push_back(n);
    mutable_parameter_block_sizes()->push_back(n);
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    for (int i = 0; i < n_; ++i) {
      residuals[i] = (parameters[1][i] - a_ * parameters[0][i]) * inv(i);
    }
    if (jacobians != nullptr) {
      for (int b = 0; b < 2; ++b) {
        if (jacobians[b] != nullptr) {
          std::fill(jacobians[b], jacobians[b] + n_ * n_, 0.0);
          for (int i = 0; i < n_; ++i) {
            jacobians[b][i * n_ + i] = b == 0 ? -a_ * inv(i) : inv(i);
          }
        }
      }
    }
    return true;
  }

 private:
  double inv(int i) const { return inv_.size() == 1 ? inv_[0] : inv_[static_cast<std::size_t>(i)]; }
  int n_;
  double a_;
  std::vector<double> inv_;
};

/// Relative motion between consecutive epochs: S (x_t - compose(between(m_i', x_{t-1}), m_j')),
/// m' the increments corrected by the slip block (own s, k, peer s, k) when there is one, else
/// m' = m. Blocks: x_{t-1}, x_t[, slip].
class MotionCost : public ceres::CostFunction {
 public:
  MotionCost(const model::Pose2& mi, const model::Pose2& mj, const Eigen::Matrix3d& sqrt_information, bool slip,
             std::optional<Eigen::Vector3d> first_estimate = std::nullopt)
      : mi_(mi), mj_(mj), s_(sqrt_information), slip_(slip), first_estimate_(first_estimate) {
    set_num_residuals(3);
    mutable_parameter_block_sizes()->push_back(3);
    mutable_parameter_block_sizes()->push_back(3);
    if (slip_) {
      mutable_parameter_block_sizes()->push_back(4);
    }
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    Eigen::Matrix<double, 3, 2> ci;
    Eigen::Matrix<double, 3, 2> cj;
    const model::Pose2 mi = slip_ ? corrected_increment(mi_, parameters[2][0], parameters[2][1], &ci) : mi_;
    const model::Pose2 mj = slip_ ? corrected_increment(mj_, parameters[2][2], parameters[2][3], &cj) : mj_;
    const bool slip_jacobian = slip_ && jacobians != nullptr && jacobians[2] != nullptr;
    double predicted[3];
    Eigen::Matrix3d jp;
    Eigen::Matrix3d jmi;
    Eigen::Matrix3d jmj;
    predict_pose(parameters[0], mi, mj, predicted, &jp, slip_jacobian ? &jmi : nullptr, slip_jacobian ? &jmj : nullptr);
    if (first_estimate_ && jacobians != nullptr) {
      // Jacobians at the previous pose's first estimate (the marginalisation prior's point).
      double unused[3];
      predict_pose(first_estimate_->data(), mi, mj, unused, &jp, slip_jacobian ? &jmi : nullptr,
                   slip_jacobian ? &jmj : nullptr);
    }
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
      if (slip_jacobian) {
        Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> j(jacobians[2]);
        j.leftCols<2>() = -s_ * (jmi * ci);
        j.rightCols<2>() = -s_ * (jmj * cj);
      }
    }
    return true;
  }

 private:
  model::Pose2 mi_;
  model::Pose2 mj_;
  Eigen::Matrix3d s_;
  bool slip_;
  std::optional<Eigen::Vector3d> first_estimate_;
};

/// Dense prior on one epoch's states (its blocks of `sizes`, the pose first): S (p - p0) + s0,
/// heading wrapped.
class PriorCost : public ceres::CostFunction {
 public:
  PriorCost(const Eigen::MatrixXd& s, const Eigen::VectorXd& offset, const Eigen::VectorXd& p0, std::vector<int> sizes)
      : s_(s), offset_(offset), p0_(p0), sizes_(std::move(sizes)) {
    set_num_residuals(static_cast<int>(s.rows()));
    for (int size : sizes_) {
      mutable_parameter_block_sizes()->push_back(size);
    }
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int n = static_cast<int>(s_.cols());
    Eigen::VectorXd dp(n);
    int column = 0;
    for (std::size_t b = 0; b < sizes_.size(); ++b) {
      for (int i = 0; i < sizes_[b]; ++i, ++column) {
        dp(column) = parameters[b][i] - p0_(column);
      }
    }
    dp(2) = wrap_angle(dp(2));
    Eigen::Map<Eigen::VectorXd> r(residuals, n);
    r = s_ * dp + offset_;
    if (jacobians != nullptr) {
      column = 0;
      for (std::size_t b = 0; b < sizes_.size(); ++b) {
        if (jacobians[b] != nullptr) {
          Eigen::Map<RowMatrix>(jacobians[b], n, sizes_[b]) = s_.middleCols(column, sizes_[b]);
        }
        column += sizes_[b];
      }
    }
    return true;
  }

 private:
  Eigen::MatrixXd s_;
  Eigen::VectorXd offset_;
  Eigen::VectorXd p0_;
  std::vector<int> sizes_;
};

/// A residual block and the parameter blocks it reads.
using Factor = detail::TcFactor;

/// The factors between consecutive epochs `prev` and `next` (the window's Epoch): the relative
/// motion of both odometries, and the Gauss-Markov transitions of the pair's common mode and of
/// the link biases (exact discretisation over their time step) when they are states. `kl`: links.
template <class Epoch>
void add_transition_factors(std::vector<Factor>& factors, const TightWindowParams& params, int kl, Epoch& prev,
                            Epoch& next, const std::optional<Eigen::Vector3d>& prev_first_estimate) {
  const double dt = next.time_s - prev.time_s;
  const bool slip = params.odometry_slip_states;
  std::vector<double*> motion{prev.pose, next.pose};
  if (slip) {
    motion.push_back(next.slip);  // the slips over the interval that ends at `next`
  }
  factors.push_back(Factor{
      std::make_unique<MotionCost>(next.own_increment, next.peer_increment, next.motion_sqrt_information, slip,
                                   prev_first_estimate),
      motion});
  if (params.common_bias_state) {
    const double a = std::exp(-dt / params.common_time_s);
    const double q = params.common_std_m * std::sqrt(std::max(1.0 - a * a, 1e-12));
    factors.push_back(Factor{std::make_unique<GaussMarkovCost>(1, a, std::vector<double>{1.0 / q}), {&prev.common, &next.common}});
  }
  if (slip) {
    const double a = std::exp(-dt / params.slip_time_s);
    const double unit = std::sqrt(std::max(1.0 - a * a, 1e-12));
    const double is = 1.0 / (params.slip_scale_std * unit);
    const double ik = 1.0 / (params.slip_curvature_std_radpm * unit);
    factors.push_back(Factor{std::make_unique<GaussMarkovCost>(4, a, std::vector<double>{is, ik, is, ik}), {prev.slip, next.slip}});
  }
  if (params.link_bias_states) {
    const double a = std::exp(-dt / params.link_bias_time_s);
    const double q = params.link_bias_std_m * std::sqrt(std::max(1.0 - a * a, 1e-12));
    factors.push_back(Factor{std::make_unique<GaussMarkovCost>(kl, a, std::vector<double>{1.0 / q}), {prev.links.data(), next.links.data()}});
  }
}

/// Adds J^T J and J^T r of `factors` to H and g, for the parameter blocks `offset_of` maps to an
/// index (others ignored). Returns the cost, half the sum of the squared residuals. Row by row over
/// each row's non-zero entries (issue 29): a range row touches 5 of a range factor's 20 columns, a
/// bias transition row 2 of 32, so this is ~1/8 of the flops of the blocks' dense products.
template <class OffsetOf>
double accumulate(const std::vector<Factor>& factors, const OffsetOf& offset_of, Eigen::MatrixXd& h, Eigen::VectorXd& g) {
  double cost_sum = 0.0;
  std::vector<RowMatrix> jac;
  std::vector<double*> jp;
  std::vector<int> offsets;
  std::vector<int> columns;
  std::vector<double> values;
  Eigen::VectorXd r;
  for (const Factor& factor : factors) {
    const ceres::CostFunction& cost = *factor.cost;
    const int m = cost.num_residuals();
    const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
    jac.resize(sizes.size());
    jp.resize(sizes.size());
    offsets.resize(sizes.size());
    for (std::size_t b = 0; b < sizes.size(); ++b) {
      jac[b].resize(m, sizes[b]);
      jp[b] = jac[b].data();
      offsets[b] = offset_of(factor.parameters[b]);
    }
    r.resize(m);
    cost.Evaluate(factor.parameters.data(), r.data(), jp.data());
    cost_sum += 0.5 * r.squaredNorm();
    for (int i = 0; i < m; ++i) {
      columns.clear();
      values.clear();
      for (std::size_t b = 0; b < sizes.size(); ++b) {
        if (offsets[b] < 0) {
          continue;
        }
        for (int k = 0; k < sizes[b]; ++k) {
          const double v = jac[b](i, k);
          if (v != 0.0) {
            columns.push_back(offsets[b] + k);
            values.push_back(v);
          }
        }
      }
      for (std::size_t p = 0; p < columns.size(); ++p) {
        g(columns[p]) += values[p] * r(i);
        for (std::size_t q = 0; q < columns.size(); ++q) {
          h(columns[p], columns[q]) += values[p] * values[q];
        }
      }
    }
  }
  return cost_sum;
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
          .add("odometry_slip_states", &P::odometry_slip_states, "", params::any<bool>(),
               "each robot's odometry slips (scale, curvature) as Gauss-Markov states (false: the white stds cover them)")
          .add("slip_scale_std", &P::slip_scale_std, "", params::positive(),
               "odometry scale error (both wheels' mean slip) per robot: Gauss-Markov std")
          .add("slip_curvature_std_radpm", &P::slip_curvature_std_radpm, "rad/m", params::positive(),
               "odometry curvature error (wheel slip difference / wheel base) per robot: Gauss-Markov std")
          .add("slip_time_s", &P::slip_time_s, "s", params::positive(), "odometry slips: Gauss-Markov time constant")
          .add("noise_window_epochs", &P::noise_window_epochs, "epochs", params::at_least(0),
               "each link's variance: the mean square of its residuals over this many epochs, at least white_std_m^2 (0: off)")
          .add("first_estimates_jacobians", &P::first_estimates_jacobians, "", params::any<bool>(),
               "the oldest epoch's factors linearised at the marginalisation prior's point (false: at the estimate, the ablation)")
          .add("innovation_check", &P::innovation_check, "", params::any<bool>(),
               "the estimator adds to tc's covariance what the eq. (1) fixes' median innovation shows beyond their own (false: the ablation)")
          .add("node_bias_term", &P::node_bias_term, "", params::any<bool>(),
               "the estimator adds to tc's covariance what uncertainty.node_bias_std_m's node biases cause at its pose (false: the ablation)")
          .add("bearing_curvature_term", &P::bearing_curvature_term, "", params::any<bool>(),
               "the estimator adds the second-order term of tc's bearing (with_bearing_curvature) to its covariance (false: the ablation)")
          .add("jump_check_epochs", &P::jump_check_epochs, "epochs", params::at_least(0),
               "the estimator adds to tc's covariance a jump of its estimate beyond those of this many last epochs, dead-reckoned with their covariances (0: off)")
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
  int n = 0;
  for (int size : block_sizes()) {
    n += size;
  }
  return n;
}

std::vector<int> TightlyCoupledWindow::block_sizes() const {
  std::vector<int> sizes{3, 1};
  if (params_.odometry_slip_states) {
    sizes.push_back(4);
  }
  if (params_.link_bias_states) {
    sizes.push_back(static_cast<int>(own_array_.nodes_m.size() * peer_array_.nodes_m.size()));
  }
  return sizes;
}

std::vector<double*> TightlyCoupledWindow::blocks(Epoch& e) const {
  std::vector<double*> p{e.pose, &e.common};
  if (params_.odometry_slip_states) {
    p.push_back(e.slip);
  }
  if (params_.link_bias_states) {
    p.push_back(e.links.data());
  }
  return p;
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
  const int slip = params_.odometry_slip_states ? 4 : 0;
  const int kl = n - 4 - slip;
  e.links.assign(static_cast<std::size_t>(kl), 0.0);
  epochs_.push_back(std::move(e));
  Eigen::VectorXd inv_std(n);
  inv_std.head<4>() << 1.0 / params_.start_xy_std_m, 1.0 / params_.start_xy_std_m, 1.0 / params_.start_theta_std_rad,
      1.0 / params_.common_std_m;
  if (slip > 0) {
    const double is = 1.0 / params_.slip_scale_std;
    const double ik = 1.0 / params_.slip_curvature_std_radpm;
    inv_std.segment<4>(4) << is, ik, is, ik;
  }
  inv_std.tail(kl).setConstant(1.0 / params_.link_bias_std_m);
  prior_.sqrt_information = inv_std.asDiagonal();
  prior_.offset = Eigen::VectorXd::Zero(n);
  prior_.linearization = Eigen::VectorXd::Zero(n);
  prior_.linearization.head<3>() << fix.x, fix.y, fix.theta;
  disagreements_ = 0;
}

void TightlyCoupledWindow::add_excess_noise_term() {
  const Epoch& e = epochs_.back();
  if (!e.ranges || e.range_inv_sigma.size() == 0) {
    return;
  }
  double white = params_.white_std_m;
  if (!params_.link_bias_states) {
    white = std::hypot(params_.white_std_m, params_.link_bias_std_m);
  }
  const Eigen::VectorXd excess = (e.range_inv_sigma.cwiseAbs2().cwiseInverse().array() - white * white).cwiseMax(0.0).matrix();
  if (excess.maxCoeff() <= 0.0) {
    return;
  }
  // A link noisier than the model (or an outlier) is such because something lies in its way, and
  // that lasts as long as the geometry does: the window cannot average it out, nor the link bias
  // state, whose prior does not cover it. What its excess would move a fit by (range_error_map: a
  // persistent error on one range reaches the pose as in one epoch's least squares) is added.
  RangeErrorMap map;
  if (range_error_map(own_array_, peer_array_, pose(), 1.0, 0.0, map)) {
    const Eigen::Matrix3d term = map.independent_map * excess.asDiagonal() * map.independent_map.transpose();
    covariance_ += 0.5 * (term + term.transpose());
  }
}

std::optional<Eigen::Vector3d> TightlyCoupledWindow::first_estimate() const {
  if (!params_.first_estimates_jacobians) {
    return std::nullopt;
  }
  return Eigen::Vector3d(prior_.linearization.head<3>());
}

bool TightlyCoupledWindow::step(double time_s, const model::Pose2& own_increment, const model::Pose2& peer_increment,
                                const std::optional<Eigen::MatrixXd>& ranges_m, const std::optional<model::Pose2>& fix,
                                const Eigen::VectorXd& outlier_variances_m2) {
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
    if (outlier_variances_m2.size() != 0 &&
        (outlier_variances_m2.size() != ranges->size() || !outlier_variances_m2.allFinite() || outlier_variances_m2.minCoeff() < 0.0)) {
      throw std::invalid_argument("TightlyCoupledWindow::step: outlier variances do not fit the ranges or are negative");
    }
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
    const double dt = time_s - prev.time_s;
    if (params_.odometry_slip_states) {
      const double a = std::exp(-dt / params_.slip_time_s);
      for (int i = 0; i < 4; ++i) {
        e.slip[i] = a * prev.slip[i];
      }
      predict_pose(prev.pose, corrected_increment(own_increment, e.slip[0], e.slip[1], nullptr),
                   corrected_increment(peer_increment, e.slip[2], e.slip[3], nullptr), e.pose, nullptr);
    } else {
      predict_pose(prev.pose, own_increment, peer_increment, e.pose, nullptr);
    }
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
    // Each range's variance: the white noise (with the link biases' when they are not states),
    // plus what the caller found beyond the model (a non-line-of-sight range's excess).
    double white = params_.white_std_m;
    if (!params_.link_bias_states) {
      white = std::hypot(params_.white_std_m, params_.link_bias_std_m);
    }
    Eigen::VectorXd variance = Eigen::VectorXd::Constant(ranges->size(), white * white);
    // A link noisier than the model (a board in its way: a changing excess each frame) shows in
    // its residuals at the solutions of the last noise_window_epochs epochs: their mean square,
    // never below the configured variance, is its variance (a residual at a solution is smaller
    // than the error it leaves: a link that holds its model stays at the floor).
    if (params_.noise_window_epochs > 0 && static_cast<int>(residuals_.size()) >= params_.noise_window_epochs / 2 &&
        residual_sum_.size() == variance.size()) {
      variance = variance.cwiseMax(residual_sum_ / static_cast<double>(residuals_.size()));
    }
    if (outlier_variances_m2.size() != 0) {
      variance += outlier_variances_m2;
    }
    epochs_.back().range_inv_sigma = variance.cwiseSqrt().cwiseInverse();
  }
  bool converged = solve();
  if (ranges && params_.noise_window_epochs > 0) {
    const Epoch& e = epochs_.back();
    const Eigen::MatrixXd predicted =
        model::array_ranges(own_array_, model::Pose2{}, peer_array_, model::Pose2{e.pose[0], e.pose[1], e.pose[2]});
    Eigen::VectorXd squared(ranges->size());
    for (Eigen::Index k = 0; k < predicted.rows(); ++k) {
      for (Eigen::Index l = 0; l < predicted.cols(); ++l) {
        const Eigen::Index i = k * predicted.cols() + l;
        const double bias = e.links.empty() ? 0.0 : e.links[static_cast<std::size_t>(i)];
        const double r = (*ranges)(i) - predicted(k, l) - e.common - bias;
        squared(i) = r * r;
      }
    }
    if (residual_sum_.size() != squared.size()) {
      residual_sum_ = Eigen::VectorXd::Zero(squared.size());
    }
    residual_sum_ += squared;
    residuals_.push_back(std::move(squared));
    if (static_cast<int>(residuals_.size()) > params_.noise_window_epochs) {
      residual_sum_ -= residuals_.front();
      residuals_.pop_front();
    }
  }
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
      Eigen::VectorXd inv_sigma = epochs_.back().range_inv_sigma;
      start(time_s, *fix);
      epochs_.back().ranges = ranges;
      epochs_.back().range_inv_sigma = inv_sigma;
      converged = solve();
    }
  }
  add_excess_noise_term();
  const model::Pose2 p = pose();
  return converged && finite(p) && covariance_.allFinite() && last_ranges_s_ &&
         time_s - *last_ranges_s_ <= params_.restart_after_gap_s;
}

bool TightlyCoupledWindow::solve() {
  const bool links = params_.link_bias_states;
  const int n = epoch_size();
  const int kl = static_cast<int>(own_array_.nodes_m.size() * peer_array_.nodes_m.size());
  std::vector<Factor> factors;
  factors.reserve(5 * epochs_.size() + 1);
  auto range_blocks = [&](Epoch& e) {
    std::vector<double*> p{e.pose, &e.common};
    if (links) {
      p.push_back(e.links.data());
    }
    return p;
  };
  factors.push_back(Factor{std::make_unique<PriorCost>(prior_.sqrt_information, prior_.offset, prior_.linearization, block_sizes()),
                           blocks(epochs_.front())});
  for (std::size_t t = 0; t < epochs_.size(); ++t) {
    Epoch& e = epochs_[t];
    if (e.ranges) {
      factors.push_back(Factor{std::make_unique<RangeCost>(own_array_, peer_array_, *e.ranges, e.range_inv_sigma, links,
                                                           t == 0 ? first_estimate() : std::nullopt),
                               range_blocks(e)});
    }
    if (t == 0) {
      continue;
    }
    add_transition_factors(factors, params_, kl, epochs_[t - 1], e, t == 1 ? first_estimate() : std::nullopt);
  }

  // Levenberg-Marquardt as Ceres ran it here until issue 29's session 13 (DENSE_SCHUR, radius 1e6,
  // Ceres' default tolerances: function 1e-6, gradient 1e-10, parameter 1e-8; max_iterations), on
  // the dense normal equations of the whole window (epochs x n unknowns, 60 with 3 epochs of 20):
  // Jacobi scaling fixed at the start point, (J^T J + diag(J^T J) / radius) step = -J^T r in the
  // scaled unknowns, the radius grown after a good step and shrunk after a bad one, as
  // SlidingWindowGraph::optimize does. Ceres' preprocessing, program reordering and Schur
  // machinery were ~70 % of this stage's CPU for a system this small. The steps are the same up to
  // rounding: every figure uwb_tightly_coupled_window_test prints is unchanged, and the tc poses of
  // paper3_exp2 (seeds 1-3) and paper3_8robots moved by at most 1.4e-10 m (docs/performance.md
  // "Single-thread cycle, session 13").
  const int epochs = static_cast<int>(epochs_.size());
  const int size = epochs * n;
  const int link_offset = params_.odometry_slip_states ? 8 : 4;
  const auto offset_of = [&](const double* p) {
    for (int t = 0; t < epochs; ++t) {
      const Epoch& e = epochs_[static_cast<std::size_t>(t)];
      if (p == e.pose) return t * n;
      if (p == &e.common) return t * n + 3;
      if (p == e.slip) return t * n + 4;
      if (links && p == e.links.data()) return t * n + link_offset;
    }
    return -1;
  };
  if (!params_.common_bias_state) {
    for (Epoch& e : epochs_) {
      e.common = 0.0;  // held at zero (the ablation): not an unknown
    }
  }
  if (solve_observer_ != nullptr) {
    std::vector<double*> constant_blocks;
    if (!params_.common_bias_state) {
      for (Epoch& e : epochs_) {
        constant_blocks.push_back(&e.common);
      }
    }
    solve_observer_->before_solve(factors, constant_blocks, params_.max_iterations);
  }
  const std::vector<int> sizes = block_sizes();
  // The unknowns in the epochs' blocks <-> x.
  std::vector<std::vector<double*>> epoch_blocks;
  epoch_blocks.reserve(epochs_.size());
  for (Epoch& e : epochs_) {
    epoch_blocks.push_back(blocks(e));
  }
  const auto load = [&](Eigen::VectorXd& x) {
    for (int t = 0; t < epochs; ++t) {
      const std::vector<double*>& b = epoch_blocks[static_cast<std::size_t>(t)];
      int column = t * n;
      for (std::size_t k = 0; k < b.size(); ++k) {
        x.segment(column, sizes[k]) = Eigen::Map<const Eigen::VectorXd>(b[k], sizes[k]);
        column += sizes[k];
      }
    }
  };
  const auto store = [&](const Eigen::VectorXd& x) {
    for (int t = 0; t < epochs; ++t) {
      const std::vector<double*>& b = epoch_blocks[static_cast<std::size_t>(t)];
      int column = t * n;
      for (std::size_t k = 0; k < b.size(); ++k) {
        Eigen::Map<Eigen::VectorXd>(b[k], sizes[k]) = x.segment(column, sizes[k]);
        column += sizes[k];
      }
    }
  };
  const auto fixed = [&](int k) { return !params_.common_bias_state && k % n == 3; };
  Eigen::VectorXd residual_buffer;
  const auto cost_at_blocks = [&] {
    double cost = 0.0;
    for (const Factor& f : factors) {
      residual_buffer.resize(f.cost->num_residuals());
      f.cost->Evaluate(f.parameters.data(), residual_buffer.data(), nullptr);
      cost += 0.5 * residual_buffer.squaredNorm();
    }
    return cost;
  };
  Eigen::MatrixXd h(size, size);
  Eigen::VectorXd g(size);
  const auto linearize = [&] {
    h.setZero();
    g.setZero();
    return accumulate(factors, offset_of, h, g);
  };
  const auto gradient_converged = [&] {
    double most = 0.0;
    for (int k = 0; k < size; ++k) {
      if (!fixed(k)) {
        most = std::max(most, std::abs(g(k)));
      }
    }
    return most <= 1e-10;
  };
  Eigen::VectorXd x(size);
  load(x);
  double cost = linearize();
  Eigen::VectorXd scale(size);
  for (int k = 0; k < size; ++k) {
    scale(k) = fixed(k) ? 0.0 : 1.0 / (1.0 + std::sqrt(h(k, k)));
  }
  bool converged = true;  // Ceres: CONVERGENCE, or NO_CONVERGENCE after at least one iteration
  if (!gradient_converged()) {
    LmTrustRegion region(1e6);  // warm-started: the first step nearly Gauss-Newton's (Ceres' default 1e4 damps it)
    int invalid_steps = 0;
    Eigen::MatrixXd a(size, size);
    // Block-tridiagonal elimination by epoch (a factor joins one epoch, or two consecutive ones):
    // D_0 = A_00, D_t = A_tt - B_t D_{t-1}^-1 B_t^T (B_t = A_{t,t-1}), then back substitution.
    std::vector<Eigen::LLT<Eigen::MatrixXd>> factor(static_cast<std::size_t>(epochs));
    std::vector<Eigen::MatrixXd> gain(static_cast<std::size_t>(epochs));  // D_{t-1}^-1 B_t^T
    Eigen::VectorXd y(size);
    Eigen::VectorXd step(size);
    Eigen::VectorXd candidate(size);
    for (int iteration = 1; iteration <= params_.max_iterations; ++iteration) {
      // Only the blocks the elimination reads: (t, t) and (t, t - 1).
      for (int t = 0; t < epochs; ++t) {
        a.block(t * n, t * n, n, n) =
            scale.segment(t * n, n).asDiagonal() * h.block(t * n, t * n, n, n) * scale.segment(t * n, n).asDiagonal();
        if (t > 0) {
          a.block(t * n, (t - 1) * n, n, n) = scale.segment(t * n, n).asDiagonal() * h.block(t * n, (t - 1) * n, n, n) *
                                              scale.segment((t - 1) * n, n).asDiagonal();
        }
      }
      Eigen::VectorXd rhs = -(scale.array() * g.array()).matrix();
      for (int k = 0; k < size; ++k) {
        if (fixed(k)) {
          a.row(k).setZero();
          a.col(k).setZero();
          a(k, k) = 1.0;
          rhs(k) = 0.0;
        } else {
          a(k, k) += region.damping(a(k, k));
        }
      }
      y = rhs;
      bool solved = true;
      for (int t = 0; t < epochs && solved; ++t) {
        const auto u = static_cast<std::size_t>(t);
        if (t == 0) {
          factor[u].compute(a.topLeftCorner(n, n));
        } else {
          const auto b = a.block(t * n, (t - 1) * n, n, n);
          gain[u] = factor[u - 1].solve(b.transpose());
          factor[u].compute(a.block(t * n, t * n, n, n) - b * gain[u]);
          y.segment(t * n, n) -= gain[u].transpose() * y.segment((t - 1) * n, n);
        }
        solved = factor[u].info() == Eigen::Success;
      }
      if (!solved) {
        // Ceres: an invalid step shrinks the radius like a rejected one; five in a row fail.
        if (++invalid_steps >= 5) {
          converged = false;
          break;
        }
        region.step_rejected();  // five invalid steps in a row end it long before the minimum radius
        continue;
      }
      invalid_steps = 0;
      for (int t = epochs - 1; t >= 0; --t) {
        const auto u = static_cast<std::size_t>(t);
        if (t + 1 < epochs) {
          y.segment(t * n, n) -= a.block((t + 1) * n, t * n, n, n).transpose() * step.segment((t + 1) * n, n);
        }
        step.segment(t * n, n) = factor[u].solve(y.segment(t * n, n));
      }
      step = (step.array() * scale.array()).matrix();
      if (step.norm() <= 1e-8 * (x.norm() + 1e-8)) {
        break;  // parameter tolerance
      }
      const double model_change = -(g.dot(step) + 0.5 * step.dot(h * step));
      candidate = x + step;
      store(candidate);
      const double candidate_cost = cost_at_blocks();
      if (std::abs(cost - candidate_cost) <= 1e-6 * cost) {
        store(x);  // function tolerance (Ceres keeps the current point)
        break;
      }
      const double relative_decrease = (cost - candidate_cost) / model_change;
      if (LmTrustRegion::accepts(relative_decrease, model_change, candidate_cost)) {
        x.swap(candidate);
        cost = linearize();
        region.step_accepted(relative_decrease);
        if (gradient_converged()) {
          break;
        }
      } else {
        store(x);
        if (region.step_rejected()) {
          break;  // Ceres: minimum trust region radius, a convergence
        }
      }
    }
  }

  // Information of the whole window at the solution (h, as linearised there), then block-tridiagonal
  // elimination from the oldest epoch to the newest: the newest epoch's marginal covariance.
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
  if (solve_observer_ != nullptr) {
    solve_observer_->after_solve(converged);
  }
  return converged;
}

void TightlyCoupledWindow::marginalize_oldest() {
  const bool links = params_.link_bias_states;
  const int n = epoch_size();
  const int slip = params_.odometry_slip_states ? 4 : 0;
  const int kl = n - 4 - slip;
  Epoch& old = epochs_[0];
  Epoch& next = epochs_[1];
  std::vector<double*> range_blocks{old.pose, &old.common};
  if (links) {
    range_blocks.push_back(old.links.data());
  }
  std::vector<Factor> factors;
  factors.push_back(
      Factor{std::make_unique<PriorCost>(prior_.sqrt_information, prior_.offset, prior_.linearization, block_sizes()), blocks(old)});
  if (old.ranges) {
    factors.push_back(Factor{
        std::make_unique<RangeCost>(own_array_, peer_array_, *old.ranges, old.range_inv_sigma, links, first_estimate()),
        range_blocks});
  }
  add_transition_factors(factors, params_, kl, old, next, first_estimate());
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * n);
  const auto offset_of = [&](const double* p) {
    if (p == old.pose) return 0;
    if (p == &old.common) return 3;
    if (p == old.slip) return 4;
    if (links && p == old.links.data()) return 4 + slip;
    if (p == next.pose) return n;
    if (p == &next.common) return n + 3;
    if (p == next.slip) return n + 4;
    if (links && p == next.links.data()) return n + 4 + slip;
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
  prior_.linearization.head<4>() << next.pose[0], next.pose[1], next.pose[2], next.common;
  if (slip > 0) {
    prior_.linearization.segment<4>(4) = Eigen::Map<const Eigen::Vector4d>(next.slip);
  }
  prior_.linearization.tail(kl) = Eigen::Map<const Eigen::VectorXd>(next.links.data(), kl);
  epochs_.pop_front();
}

}  // namespace robodds::uwb_relative_estimator
