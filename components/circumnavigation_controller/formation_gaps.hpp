#pragma once
// Angular gaps between the robots of a team around their target, for the spacing term of the
// guidance law (README.md). Pure: std only, angles in rad, counter-clockwise positive.

#include <cstdint>
#include <vector>

namespace robodds::circumnavigation_controller {

/// A team robot's bearing seen from the target, atan2(y - Ty, x - Tx).
struct TeamBearing {
  std::uint32_t robot_id = 0;
  double bearing_rad = 0.0;
};

/// The gaps of one robot: counter-clockwise (the orbit's direction) to the next team robot, and
/// from the previous one back to this robot. With team_count 1 both are 2 pi.
struct Gaps {
  double ahead_rad = 0.0;   // g+
  double behind_rad = 0.0;  // g-
  int team_count = 1;       // n, this robot included
};

/// atan2(y - target_y, x - target_x): the bearing of a point seen from the target.
double bearing_from_target(double x, double y, double target_x, double target_y);

/// The gaps of robot `own` among `peers` (its team mates with a known pose; an entry with own's
/// id is ignored). Robots are ordered counter-clockwise by bearing, identical bearings by robot
/// id (the lower id is behind; peers have distinct ids), so the gaps are in [0, 2 pi], 0 only for identical bearings,
/// and the forward gaps of a team add up to 2 pi. Throws std::invalid_argument for a
/// non-finite bearing.
Gaps formation_gaps(const TeamBearing& own, const std::vector<TeamBearing>& peers);

}  // namespace robodds::circumnavigation_controller
