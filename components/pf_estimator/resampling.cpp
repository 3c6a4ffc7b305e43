#include "components/pf_estimator/resampling.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace robodds::pf_estimator {
namespace {

// Checks the common preconditions and returns the weight sum.
double checked_weight_sum(const Eigen::ArrayXd& w, const char* caller) {
  if (w.size() == 0) {
    return 0.0;
  }
  // (w >= 0) is false for NaN, so this also rejects NaN.
  if (!(w >= 0.0).all() || !w.isFinite().all()) {
    throw std::invalid_argument(std::string(caller) + ": weights must be finite and >= 0");
  }
  const double total = w.sum();
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw std::invalid_argument(std::string(caller) + ": weights must have a positive finite sum");
  }
  return total;
}

// Index of the last particle with a positive weight: rounding may push the final pointer past
// the end of the cumulative sum, and it must not land on a zero-weight particle.
Eigen::Index last_positive_index(const Eigen::ArrayXd& w) {
  Eigen::Index last = w.size() - 1;
  while (last > 0 && !(w[last] > 0.0)) {
    --last;
  }
  return last;
}

// floor(M w_i), except that an expected count a rounding error below an integer (2 - 4e-16 from
// weights 1/500 with M = 1000) counts as that integer: otherwise its copy would go to the random
// remainder and an exact split would become a noisy one.
double deterministic_copies(double expected_copies) {
  return std::floor(expected_copies + 1e-9);
}

double residual_of(double expected_copies) {
  return std::max(0.0, expected_copies - deterministic_copies(expected_copies));
}

}  // namespace

double effective_sample_size(const Eigen::ArrayXd& normalized_weights) {
  const double sum_sq = normalized_weights.square().sum();
  if (!(sum_sq > 0.0)) {
    return 0.0;
  }
  const double sum = normalized_weights.sum();
  return sum * sum / sum_sq;
}

void systematic_resample_into(const Eigen::ArrayXd& normalized_weights, double u0,
                              std::vector<std::size_t>& indices) {
  const Eigen::ArrayXd& w = normalized_weights;
  const Eigen::Index m = w.size();
  const double total = checked_weight_sum(w, "systematic_resample");
  indices.resize(static_cast<std::size_t>(m));
  if (m == 0) {
    return;
  }
  // [0, 1/M) is the domain; 1/M itself is tolerated because uniform01()/M may round onto it.
  if (!(u0 >= 0.0) || !(u0 <= 1.0 / static_cast<double>(m))) {
    std::ostringstream message;
    message << "systematic_resample: u0 must be in [0, 1/M) (got " << u0 << ", M = " << m << ")";
    throw std::invalid_argument(message.str());
  }
  const double step = total / static_cast<double>(m);
  const double offset = u0 * static_cast<double>(m);  // in [0, 1]
  const Eigen::Index last = last_positive_index(w);
  Eigen::Index i = 0;
  double cumulative = w[0];
  for (Eigen::Index j = 0; j < m; ++j) {
    // Pointer recomputed from j (not accumulated) so rounding does not drift over M steps.
    const double pointer = (offset + static_cast<double>(j)) * step;
    while (pointer >= cumulative && i < last) {
      ++i;
      cumulative += w[i];
    }
    indices[static_cast<std::size_t>(j)] = static_cast<std::size_t>(i);
  }
}

std::vector<std::size_t> systematic_resample(const Eigen::ArrayXd& normalized_weights, double u0) {
  std::vector<std::size_t> indices;
  systematic_resample_into(normalized_weights, u0, indices);
  return indices;
}

void residual_resample_into(const Eigen::ArrayXd& w, RandomEngine& engine,
                            std::vector<std::size_t>& indices) {
  const Eigen::Index m = w.size();
  const double total = checked_weight_sum(w, "residual_resample");
  indices.clear();
  indices.reserve(static_cast<std::size_t>(m));
  if (m == 0) {
    return;
  }
  const double scale = static_cast<double>(m) / total;  // expected copies per unit weight

  // Pass 1: number of deterministic copies and total residual mass.
  Eigen::Index deterministic = 0;
  double residual_total = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double expected = scale * w[i];
    deterministic += static_cast<Eigen::Index>(deterministic_copies(expected));
    residual_total += residual_of(expected);
  }
  Eigen::Index remaining = deterministic < m ? m - deterministic : 0;

  // The remainder is multinomial over the residuals. Its R uniforms are generated already
  // sorted (ascending), so one forward walk over the cumulative residuals assigns them without
  // a sort or a scratch buffer: the maximum of k uniforms on [0, U] is U * u^(1/k), which gives
  // the order statistics in descending order, and 1 - U turns them ascending.
  double upper = 1.0;
  auto next_position = [&]() {
    upper *= std::pow(uniform01(engine), 1.0 / static_cast<double>(remaining));
    return (1.0 - upper) * residual_total;
  };
  double position = remaining > 0 ? next_position() : 0.0;

  // Pass 2: floor copies plus the remainder positions inside particle i's residual interval,
  // emitted in index order.
  double cumulative_residual = 0.0;
  for (Eigen::Index i = 0; i < m && static_cast<Eigen::Index>(indices.size()) < m; ++i) {
    const double expected = scale * w[i];
    cumulative_residual += residual_of(expected);
    auto copies = static_cast<Eigen::Index>(deterministic_copies(expected));
    while (remaining > 0 && position < cumulative_residual) {
      ++copies;
      --remaining;
      if (remaining > 0) {
        position = next_position();
      }
    }
    for (Eigen::Index c = 0; c < copies && static_cast<Eigen::Index>(indices.size()) < m; ++c) {
      indices.push_back(static_cast<std::size_t>(i));
    }
  }
  // Rounding (or a uniform of exactly 0) may leave a position at the very end of the
  // cumulative residual; it belongs to the last particle with weight.
  const auto last = static_cast<std::size_t>(last_positive_index(w));
  while (static_cast<Eigen::Index>(indices.size()) < m) {
    indices.push_back(last);
  }
}

std::vector<std::size_t> residual_resample(const Eigen::ArrayXd& w, RandomEngine& engine) {
  std::vector<std::size_t> indices;
  residual_resample_into(w, engine, indices);
  return indices;
}

}  // namespace robodds::pf_estimator
