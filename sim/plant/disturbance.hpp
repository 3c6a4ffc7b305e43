#pragma once
// A one-off jump of the true pose (a "kidnapped robot"), for testing how an estimator recovers.
// Pure: world frame, SI units.

#include "common/model/pose2.hpp"

namespace robodds::plant {

/// At simulated time at_s the true pose of every robot of the plant jumps once by (dx, dy) in
/// the world frame and dtheta in heading. at_s < 0: off (the default).
/// Units, ranges, descriptions: the disturbance_* entries of plant_model_param_table().
struct PoseDisturbance {
  double at_s = -1.0;
  double dx_m = 0.0;
  double dy_m = 0.0;
  double dtheta_rad = 0.0;

  bool enabled() const { return at_s >= 0.0; }
  /// True at the first step whose time (s) reaches at_s: `time_s` >= at_s - 1 ns (so that
  /// 3000 * 0.01 s counts as 30 s), and the jump was not applied yet.
  bool due(double time_s, bool already_applied) const;
};

/// `pose` moved by the disturbance: (x + dx, y + dy), heading wrapped to (-pi, pi].
model::Pose2 apply_disturbance(const model::Pose2& pose, const PoseDisturbance& disturbance);

}  // namespace robodds::plant
