#include "sim/evaluator/metrics/relative_pose/relative_pose_metrics.hpp"

#include <cmath>

#include "common/angle.hpp"

namespace robodds::evaluator {

RelativePoseError relative_pose_error(const model::Pose2& world_i, const model::Pose2& world_j,
                                      const model::Pose2& estimate) {
  const model::Pose2 truth = model::between(world_i, world_j);
  return {std::hypot(estimate.x - truth.x, estimate.y - truth.y), wrap_angle(estimate.theta - truth.theta)};
}

void RunningStats::add(double value) {
  ++count_;
  const double delta = value - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * (value - mean_);
}

double RunningStats::stddev() const { return count_ < 2 ? 0.0 : std::sqrt(m2_ / static_cast<double>(count_)); }

void RelativePoseMetrics::add_valid(const std::string& stage, double t_s, const model::Pose2& world_i,
                                    const model::Pose2& world_j, const model::Pose2& estimate) {
  Stage& s = stages_[stage];
  if (!counts(t_s)) {
    return;
  }
  const RelativePoseError e = relative_pose_error(world_i, world_j, estimate);
  s.position_m.add(e.position_m);
  s.heading_rad.add(std::abs(e.heading_rad));
}

void RelativePoseMetrics::add_invalid(const std::string& stage, double t_s) {
  Stage& s = stages_[stage];
  if (counts(t_s)) {
    ++s.invalid;
  }
}

std::map<std::string, RelativeStageStats> RelativePoseMetrics::stages() const {
  constexpr double kDegPerRad = 180.0 / kPi;
  std::map<std::string, RelativeStageStats> out;
  for (const auto& [name, s] : stages_) {
    RelativeStageStats& o = out[name];
    o.epochs = s.position_m.count();
    o.invalid_epochs = s.invalid;
    o.position_error_m_mean = s.position_m.mean();
    o.position_error_m_std = s.position_m.stddev();
    o.heading_error_deg_mean = s.heading_rad.mean() * kDegPerRad;
    o.heading_error_deg_std = s.heading_rad.stddev() * kDegPerRad;
  }
  return out;
}

}  // namespace robodds::evaluator
