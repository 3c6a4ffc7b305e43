#pragma once
// The route follower: drives a route (route_params.hpp) vertex by vertex. At each vertex the robot
// stops and turns in place at +-turn_rate towards the next one until the heading error is below
// heading_tolerance_rad, then drives at speed_mps with a bounded line-following correction
// (route_law.hpp) until it is within position_tolerance_m of that vertex. Pure: SI units, world
// frame, time in s.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/model/twist.hpp"
#include "components/route_follower/route_params.hpp"

namespace robodds::route_follower {

enum class Phase {
  kTurning,  // v = 0, turning in place towards the target vertex
  kDriving,  // v = speed, on the segment to the target vertex
  kDone,     // loop: false and the last vertex reached: zero command from now on
};

/// What the follower did on one step, for telemetry and tests.
struct FollowerStatus {
  Phase phase = Phase::kTurning;      // after this step
  std::size_t target_index = 0;       // vertex the command heads for (0-based)
  std::size_t reached_count = 0;      // vertices reached so far, over all laps
  bool reached_this_step = false;     // a vertex was reached at this step (target_index advanced)
  double distance_to_target_m = 0.0;
  double cross_track_m = 0.0;         // from the line of the current segment, > 0 left of it
  double heading_error_rad = 0.0;     // bearing of the target vertex - heading, wrapped
};

struct FollowerOutput {
  model::Twist twist;
  FollowerStatus status;
};

/// The current segment runs from the vertex last reached to the target vertex; before the first
/// vertex is reached it starts at the robot's position at the first step (a robot that starts on
/// vertex 0 reaches it at once). One vertex is reached per step at most; the command of that
/// step already heads for the next one. |v| <= speed_mps and |omega| <= turn_rate_radps always.
class RouteFollower {
 public:
  /// Validates params (std::invalid_argument naming the key, see RouteParams::validate).
  explicit RouteFollower(const RouteParams& params);

  /// One control step from the pose (any finite heading); dt_s > 0 is the time the command will
  /// be applied (the control period). Throws std::invalid_argument for a non-finite pose or a
  /// dt_s that is not > 0; the state is then unchanged.
  FollowerOutput step(const model::Pose2& pose, double dt_s);

  const RouteParams& params() const { return params_; }
  const std::vector<Eigen::Vector2d>& vertices() const { return vertices_; }
  Phase phase() const { return phase_; }
  std::size_t target_index() const { return target_; }
  std::size_t reached_count() const { return reached_; }
  bool done() const { return phase_ == Phase::kDone; }

 private:
  /// Advances the target after it was reached; kDone at the end of an open route.
  void advance();
  model::Twist drive(const model::Pose2& pose, const Eigen::Vector2d& position, double distance_m, double dt_s,
                     FollowerStatus& status) const;

  RouteParams params_;
  std::vector<Eigen::Vector2d> vertices_;
  std::size_t target_ = 0;
  std::size_t reached_ = 0;
  Phase phase_ = Phase::kTurning;
  bool started_ = false;
  Eigen::Vector2d segment_start_ = Eigen::Vector2d::Zero();
};

}  // namespace robodds::route_follower
