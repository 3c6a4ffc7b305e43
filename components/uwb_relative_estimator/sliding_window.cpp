#include "components/uwb_relative_estimator/sliding_window.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "common/angle.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_estimator/lm_trust_region.hpp"
#include "components/uwb_relative_estimator/window_edge.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

model::Pose2 inverse(const model::Pose2& a_b) { return model::between(a_b, model::Pose2{}); }

}  // namespace

const params::ParamTable<WindowWeights>& window_weights_param_table() {
  using W = WindowWeights;
  static const params::ParamTable<W> table =
      params::ParamTable<W>("Sliding-window pose graph of paper 3, eq. (2): constant information matrices.")
          .add("odometry_xy_std_m", &W::odometry_xy_std_m, "m", params::positive(), "odometry increment position std per epoch")
          .add("odometry_theta_std_rad", &W::odometry_theta_std_rad, "rad", params::positive(),
               "odometry increment heading std per epoch")
          .add("uwb_xy_std_m", &W::uwb_xy_std_m, "m", params::positive(), "single-epoch UWB relative position std")
          .add("uwb_theta_std_rad", &W::uwb_theta_std_rad, "rad", params::positive(),
               "single-epoch UWB relative heading std");
  return table;
}

void WindowWeights::validate() const { window_weights_param_table().check_ranges(*this); }

SlidingWindowGraph::SlidingWindowGraph(std::size_t num_robots, std::size_t window, WindowWeights weights)
    : num_robots_(num_robots), window_(window), weights_(weights) {
  if (num_robots_ < 2) {
    param_checks::reject("num_robots", "must be >= 2", static_cast<double>(num_robots_));
  }
  if (window_ < 2) {
    param_checks::reject("window", "must be >= 2 epochs", static_cast<double>(window_));
  }
  weights_.validate();
}

void SlidingWindowGraph::add_epoch(const std::vector<model::Pose2>& odometry, const std::vector<PairMeasurement>& uwb) {
  if (odometry.size() != num_robots_) {
    throw std::invalid_argument("add_epoch: " + std::to_string(odometry.size()) + " odometry increments for " +
                                std::to_string(num_robots_) + " robots");
  }
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    if (!finite(odometry[i])) {
      throw std::invalid_argument("add_epoch: odometry of robot " + std::to_string(i) + " is not finite (got " +
                                  model::to_text(odometry[i]) + ")");
    }
  }
  for (const PairMeasurement& m : uwb) {
    if (m.own >= num_robots_ || m.other >= num_robots_ || m.own == m.other) {
      throw std::invalid_argument("add_epoch: UWB pair (" + std::to_string(m.own) + ", " + std::to_string(m.other) +
                                  ") is not two different robots of " + std::to_string(num_robots_));
    }
    if (!finite(m.pose)) {
      throw std::invalid_argument("add_epoch: UWB pose of pair (" + std::to_string(m.own) + ", " +
                                  std::to_string(m.other) + ") is not finite (got " + model::to_text(m.pose) + ")");
    }
  }
  Epoch epoch;
  epoch.odometry = odometry;
  epoch.uwb = uwb;
  epoch.poses.resize(num_robots_);
  if (epochs_.empty()) {
    // Robot 0 defines the frame; the others start where a UWB measurement to robot 0 puts them.
    for (std::size_t i = 1; i < num_robots_; ++i) {
      epoch.poses[i] = model::Pose2{static_cast<double>(i), 0.0, 0.0};
      for (const PairMeasurement& m : uwb) {
        if (m.own == 0 && m.other == i) {
          epoch.poses[i] = m.pose;
        } else if (m.own == i && m.other == 0) {
          epoch.poses[i] = inverse(m.pose);
        }
      }
    }
  } else {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      epoch.poses[i] = model::compose(epochs_.back().poses[i], odometry[i]);
    }
  }
  epochs_.push_back(std::move(epoch));
  if (epochs_.size() > window_) {
    epochs_.pop_front();
  }
}

bool SlidingWindowGraph::optimize() {
  if (epochs_.empty()) {
    return true;
  }
  // Levenberg-Marquardt as Ceres runs it (issue 29; until then this was a ceres::Problem solved with
  // SPARSE_NORMAL_CHOLESKY): Jacobi scaling fixed at the start point, the damped normal equations
  // (J^T J + diag(J^T J) / radius) step = -J^T r in the scaled variables, the radius grown after a
  // good step and shrunk after a bad one, and Ceres' default tolerances (function 1e-6, gradient
  // 1e-10, parameter 1e-8; at most 50 iterations). What Ceres' general sparse Cholesky could not use
  // is the structure: ordered by epoch, J^T J is block tridiagonal (an odometry edge joins one robot
  // at two consecutive epochs, a UWB edge two robots at one epoch), so each step is one block
  // elimination along the window, 3 N unknowns per epoch, with no symbolic analysis.
  const std::size_t epochs = epochs_.size();
  const auto n = static_cast<Eigen::Index>(3 * num_robots_);
  std::vector<double> x(epochs * num_robots_ * 3);
  for (std::size_t e = 0; e < epochs; ++e) {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      const model::Pose2& p = epochs_[e].poses[i];
      double* xi = &x[(e * num_robots_ + i) * 3];
      xi[0] = p.x;
      xi[1] = p.y;
      xi[2] = p.theta;
    }
  }
  struct Edge {
    Edge(const model::Pose2& measured, double xy_std, double theta_std, std::size_t a_index, std::size_t b_index)
        : residual(measured, xy_std, theta_std), a(a_index), b(b_index) {}
    WindowEdge residual;
    std::size_t a;  // index of pose a (epoch * num_robots + robot)
    std::size_t b;
  };
  std::vector<Edge> edges;
  std::size_t edge_count = 0;
  for (std::size_t e = 0; e < epochs; ++e) {
    edge_count += (e > 0 ? num_robots_ : 0) + epochs_[e].uwb.size();
  }
  edges.reserve(edge_count);
  for (std::size_t e = 0; e < epochs; ++e) {
    for (std::size_t i = 0; i < num_robots_ && e > 0; ++i) {
      edges.emplace_back(epochs_[e].odometry[i], weights_.odometry_xy_std_m, weights_.odometry_theta_std_rad,
                         (e - 1) * num_robots_ + i, e * num_robots_ + i);
    }
    for (const PairMeasurement& m : epochs_[e].uwb) {
      edges.emplace_back(m.pose, weights_.uwb_xy_std_m, weights_.uwb_theta_std_rad, e * num_robots_ + m.own,
                         e * num_robots_ + m.other);
    }
  }
  if (edges.empty()) {
    return true;  // one epoch without a measurement: nothing to solve
  }
  // Unknowns: every pose but robot 0's oldest (the gauge, unknowns 0-2), whose rows and columns are
  // the identity in the system solved.
  // J^T J and J^T r by epoch: diagonal blocks (3N x 3N) and, between epochs e - 1 and e, one 3 x 3
  // block per robot (its odometry edge).
  diagonal_.resize(epochs);
  inverse_.resize(epochs);
  factor_.resize(epochs);
  for (std::size_t e = 0; e < epochs; ++e) {
    diagonal_[e].resize(n, n);
    inverse_[e].resize(n, n);
  }
  std::vector<Eigen::MatrixXd>& diagonal = diagonal_;
  std::vector<Eigen::Matrix3d> coupling(epochs * num_robots_);
  Eigen::VectorXd gradient(static_cast<Eigen::Index>(x.size()));
  const auto cost_at = [&](const std::vector<double>& at) {
    double cost = 0.0;
    for (const Edge& edge : edges) {
      const double* parameters[2] = {&at[edge.a * 3], &at[edge.b * 3]};
      double r[3];
      edge.residual.Evaluate(parameters, r, nullptr);
      cost += r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    }
    return 0.5 * cost;
  };
  // The normal equations at `at` (unscaled), and the cost.
  const auto linearize = [&](const std::vector<double>& at) {
    for (Eigen::MatrixXd& d : diagonal) {
      d.setZero();
    }
    for (Eigen::Matrix3d& c : coupling) {
      c.setZero();
    }
    gradient.setZero();
    double cost = 0.0;
    for (const Edge& edge : edges) {
      const double* parameters[2] = {&at[edge.a * 3], &at[edge.b * 3]};
      Eigen::Vector3d r;
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> ja;
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> jb;
      double* jacobians[2] = {ja.data(), jb.data()};
      edge.residual.Evaluate(parameters, r.data(), jacobians);
      cost += r.squaredNorm();
      const std::size_t ea = edge.a / num_robots_;
      const std::size_t eb = edge.b / num_robots_;
      const auto ia = static_cast<Eigen::Index>(3 * (edge.a % num_robots_));
      const auto ib = static_cast<Eigen::Index>(3 * (edge.b % num_robots_));
      diagonal[ea].block<3, 3>(ia, ia) += ja.transpose() * ja;
      diagonal[eb].block<3, 3>(ib, ib) += jb.transpose() * jb;
      if (ea == eb) {
        diagonal[ea].block<3, 3>(ia, ib) += ja.transpose() * jb;
        diagonal[ea].block<3, 3>(ib, ia) += jb.transpose() * ja;
      } else {
        coupling[edge.b] += ja.transpose() * jb;  // rows: robot at epoch e - 1, columns: at e
      }
      gradient.segment<3>(static_cast<Eigen::Index>(3 * edge.a)) += ja.transpose() * r;
      gradient.segment<3>(static_cast<Eigen::Index>(3 * edge.b)) += jb.transpose() * r;
    }
    return 0.5 * cost;
  };
  double cost = linearize(x);
  // Jacobi scaling from the start point: column k of J times 1 / (1 + |J_k|).
  Eigen::VectorXd scale(gradient.size());
  for (std::size_t e = 0; e < epochs; ++e) {
    for (Eigen::Index k = 0; k < n; ++k) {
      scale(static_cast<Eigen::Index>(e) * n + k) = 1.0 / (1.0 + std::sqrt(diagonal[e](k, k)));
    }
  }
  const auto gradient_converged = [&] {
    double most = 0.0;
    for (Eigen::Index k = 3; k < gradient.size(); ++k) {
      most = std::max(most, std::abs(gradient(k)));
    }
    return most <= 1e-10;
  };
  if (gradient_converged()) {
    return true;
  }
  LmTrustRegion region(1e6);  // as the Ceres solve had: a warm start, the first step nearly Gauss-Newton's
  std::vector<double> candidate(x.size());
  std::vector<Eigen::LLT<Eigen::MatrixXd>>& factor = factor_;
  std::vector<Eigen::MatrixXd>& inverse = inverse_;
  std::vector<Eigen::Matrix3d> scaled_coupling(epochs * num_robots_);  // C of the scaled system
  Eigen::VectorXd step(gradient.size());
  // Scratch of every iteration, allocated once (issue 29, session 13: malloc and page faults were
  // a quarter of this function's time).
  Eigen::VectorXd rhs(gradient.size());
  Eigen::MatrixXd a(n, n);
  Eigen::MatrixXd ct_inverse(n, n);  // C^T A_{e-1}^-1
  Eigen::VectorXd y(n);
  Eigen::VectorXd d(n);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  bool converged = false;
  for (int iteration = 1; iteration <= 50; ++iteration) {
    // Scaled, damped system A s = -g_s; A block tridiagonal: eliminate epoch by epoch.
    bool solved = true;
    rhs = -(scale.array() * gradient.array()).matrix();
    rhs.head<3>().setZero();
    for (std::size_t e = 0; e < epochs && solved; ++e) {
      const auto offset = static_cast<Eigen::Index>(e) * n;
      a = scale.segment(offset, n).asDiagonal() * diagonal[e] * scale.segment(offset, n).asDiagonal();
      for (Eigen::Index k = 0; k < n; ++k) {
        a(k, k) += region.damping(a(k, k));
      }
      if (e == 0) {
        a.topRows<3>().setZero();
        a.leftCols<3>().setZero();
        a.topLeftCorner<3, 3>().setIdentity();
      } else {
        // A_e -= C^T A_{e-1}^-1 C, rhs_e -= C^T A_{e-1}^-1 rhs_{e-1}, C block diagonal (3 x 3 per robot).
        const auto previous = offset - n;
        for (std::size_t i = 0; i < num_robots_; ++i) {
          const auto r = static_cast<Eigen::Index>(3 * i);
          Eigen::Matrix3d c = scale.segment<3>(previous + r).asDiagonal() * coupling[e * num_robots_ + i] *
                              scale.segment<3>(offset + r).asDiagonal();
          if (e == 1 && i == 0) {
            c.setZero();  // the gauge pose is not an unknown
          }
          ct_inverse.middleRows<3>(r) = c.transpose() * inverse[e - 1].middleRows<3>(r);
          scaled_coupling[e * num_robots_ + i] = c;
        }
        for (std::size_t j = 0; j < num_robots_; ++j) {
          const auto col = static_cast<Eigen::Index>(3 * j);
          a.middleCols<3>(col) -= ct_inverse.middleCols<3>(col) * scaled_coupling[e * num_robots_ + j];
        }
        rhs.segment(offset, n) -= ct_inverse * rhs.segment(previous, n);
      }
      factor[e].compute(a);
      if (factor[e].info() != Eigen::Success) {
        solved = false;
        break;
      }
      inverse[e] = factor[e].solve(identity);
    }
    if (!solved) {
      // Ceres: a failed linear solve shrinks the radius like a rejected step.
      if (region.step_rejected()) {
        break;
      }
      continue;
    }
    for (std::size_t e = epochs; e-- > 0;) {
      const auto offset = static_cast<Eigen::Index>(e) * n;
      y = rhs.segment(offset, n);
      if (e + 1 < epochs) {
        for (std::size_t i = 0; i < num_robots_; ++i) {
          const auto r = static_cast<Eigen::Index>(3 * i);
          y.segment<3>(r) -= scaled_coupling[(e + 1) * num_robots_ + i] * step.segment<3>(offset + n + r);
        }
      }
      step.segment(offset, n) = inverse[e] * y;
    }
    step = (step.array() * scale.array()).matrix();  // back to the unknowns' own units
    step.head<3>().setZero();
    double x_norm = 0.0;
    for (double v : x) {
      x_norm += v * v;
    }
    if (step.norm() <= 1e-8 * (std::sqrt(x_norm) + 1e-8)) {
      converged = true;  // parameter tolerance
      break;
    }
    // Linear model: cost change = -(g^T d + d^T J^T J d / 2).
    double quadratic = 0.0;
    for (std::size_t e = 0; e < epochs; ++e) {
      const auto offset = static_cast<Eigen::Index>(e) * n;
      d = step.segment(offset, n);
      quadratic += d.dot(diagonal[e] * d);
      if (e > 0) {
        for (std::size_t i = 0; i < num_robots_; ++i) {
          const auto r = static_cast<Eigen::Index>(3 * i);
          quadratic += 2.0 * step.segment<3>(offset - n + r).dot(coupling[e * num_robots_ + i] * d.segment<3>(r));
        }
      }
    }
    const double model_change = -(gradient.dot(step) + 0.5 * quadratic);
    for (std::size_t k = 0; k < x.size(); ++k) {
      candidate[k] = x[k] + step(static_cast<Eigen::Index>(k));
    }
    const double candidate_cost = cost_at(candidate);
    if (std::abs(cost - candidate_cost) <= 1e-6 * cost) {
      converged = true;  // function tolerance (Ceres keeps the current point)
      break;
    }
    const double relative_decrease = (cost - candidate_cost) / model_change;
    if (LmTrustRegion::accepts(relative_decrease, model_change, candidate_cost)) {
      x.swap(candidate);
      cost = linearize(x);
      region.step_accepted(relative_decrease);
      if (gradient_converged()) {
        converged = true;
        break;
      }
    } else if (region.step_rejected()) {
      break;
    }
  }
  for (std::size_t e = 0; e < epochs; ++e) {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      const double* p = &x[(e * num_robots_ + i) * 3];
      epochs_[e].poses[i] = {p[0], p[1], wrap_angle(p[2])};
    }
  }
  return converged;
}

void SlidingWindowGraph::place_robot(std::size_t robot, std::size_t own, const model::Pose2& relative) {
  if (epochs_.empty()) {
    throw std::invalid_argument("place_robot: no epoch added yet");
  }
  if (robot >= num_robots_ || own >= num_robots_ || robot == own) {
    throw std::invalid_argument("place_robot: robots (" + std::to_string(robot) + ", " + std::to_string(own) +
                                ") are not two different robots of " + std::to_string(num_robots_));
  }
  if (!finite(relative)) {
    throw std::invalid_argument("place_robot: pose is not finite (got " + model::to_text(relative) + ")");
  }
  epochs_.back().poses[robot] = model::compose(epochs_.back().poses[own], relative);
  for (std::size_t e = epochs_.size() - 1; e > 0; --e) {
    // The odometry of epoch e leads from e - 1 to e: undo it.
    epochs_[e - 1].poses[robot] = model::compose(epochs_[e].poses[robot], inverse(epochs_[e].odometry[robot]));
  }
}

model::Pose2 SlidingWindowGraph::latest_relative(std::size_t own, std::size_t other) const {
  if (epochs_.empty()) {
    throw std::invalid_argument("latest_relative: no epoch added yet");
  }
  if (own >= num_robots_ || other >= num_robots_) {
    throw std::invalid_argument("latest_relative: robots (" + std::to_string(own) + ", " + std::to_string(other) +
                                ") are not both among the " + std::to_string(num_robots_));
  }
  return model::between(epochs_.back().poses[own], epochs_.back().poses[other]);
}

}  // namespace robodds::uwb_relative_estimator
