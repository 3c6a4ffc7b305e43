#pragma once
// Parameters of the route follower (issue 11: the robots of paper 3 drive rectangles and a
// T-shaped path at 0.2 m/s, turning in place at 0.5 rad/s).
//
// A route is a list of world points (vertices) driven in order, one straight segment from each
// to the next:
//   - loop: true  a closed walk: after the last point the robot drives back to the first and
//                 starts the next lap (do not repeat the first point at the end). A rectangle is
//                 its 4 corners; a path driven back and forth is written out as the closed walk
//                 that does it, e.g. the T of paper 3's experiment 2 (stem (6,0.5)-(6,5.5), bar
//                 (3,5.5)-(9,5.5)) is [[6,0.5], [6,5.5], [3,5.5], [9,5.5], [6,5.5]]: up the stem,
//                 to the bar's left end, across to its right end, back to the middle, and (the
//                 closing segment) down the stem.
//   - loop: false an open path, driven once; the robot stops at its last point.
// Points may repeat (the T passes (6,5.5) twice); consecutive ones (and, with loop, the last and
// the first) must be at least position_tolerance_m apart.

#include <vector>

#include "common/param_table.hpp"

namespace robodds::route_follower {

// Units, ranges and one-line descriptions of these fields: route_param_table() in
// route_params.cpp (the one source; `robodds components --params route_follower` prints it).
// Defaults: the member initialisers.
struct RouteParams {
  /// Paper 3, experiment 1-a: the 7 m x 6 m rectangle with corners (+-3.5, +-3), counter-clockwise.
  std::vector<params::Point2> route{{-3.5, -3.0}, {3.5, -3.0}, {3.5, 3.0}, {-3.5, 3.0}};
  bool loop = true;
  /// Paper 3: 0.2 m/s; the turn rate (0.5 rad/s) is issue 11's, the paper gives none.
  double speed_mps = 0.2;
  double turn_rate_radps = 0.5;
  /// A vertex counts as reached within this distance; the robot then turns in place towards the
  /// next one.
  double position_tolerance_m = 0.05;
  /// The turn in place ends (and driving starts) once the heading error is below this.
  double heading_tolerance_rad = 0.02;
  /// Line following while driving: desired heading = segment heading - atan(cross_track /
  /// lookahead_m), omega = heading_gain * (desired - heading), clamped to +-max_correction_radps
  /// (<= turn_rate_radps).
  double lookahead_m = 0.5;
  double heading_gain = 2.0;
  double max_correction_radps = 0.1;
  /// A heading error above this while driving (the estimate jumped, the robot was pushed or
  /// passed the vertex beside the tolerance circle) stops the robot and turns it in place again.
  double realign_threshold_rad = 0.5;

  /// Throws std::invalid_argument "key: reason (got ...)" for the first bad field: the table's
  /// ranges, then at least 2 finite points, consecutive points >= position_tolerance_m apart
  /// (key `route`), max_correction_radps <= turn_rate_radps, realign_threshold_rad >
  /// heading_tolerance_rad.
  void validate() const;
};

const params::ParamTable<RouteParams>& route_param_table();

}  // namespace robodds::route_follower
