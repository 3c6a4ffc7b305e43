#include "components/circumnavigation_controller/formation_gaps.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angle.hpp"

namespace robodds::circumnavigation_controller {
namespace {

constexpr double kTwoPi = 2.0 * kPi;

/// The bearing in [0, 2 pi).
double normalised(double bearing_rad) {
  if (!std::isfinite(bearing_rad)) {
    throw std::invalid_argument("formation_gaps: bearing must be finite");
  }
  double b = std::fmod(bearing_rad, kTwoPi);
  if (b < 0.0) {
    b += kTwoPi;
  }
  return b >= kTwoPi ? 0.0 : b;  // -tiny + 2 pi can round to 2 pi
}

/// Counter-clockwise distance in [0, 2 pi) from `from` to `to` (both in [0, 2 pi)); a robot
/// with an identical bearing is at 0 when it is ordered ahead (`to_is_ahead`), at 2 pi when behind.
double ccw_gap(double from, double to, bool to_is_ahead_on_tie) {
  if (to > from) {
    return to - from;
  }
  if (to < from) {
    return to - from + kTwoPi;
  }
  return to_is_ahead_on_tie ? 0.0 : kTwoPi;
}

}  // namespace

double bearing_from_target(double x, double y, double target_x, double target_y) {
  return std::atan2(y - target_y, x - target_x);
}

Gaps formation_gaps(const TeamBearing& own, const std::vector<TeamBearing>& peers) {
  const double own_b = normalised(own.bearing_rad);
  Gaps gaps{kTwoPi, kTwoPi, 1};
  for (const TeamBearing& peer : peers) {
    if (peer.robot_id == own.robot_id) {
      continue;
    }
    const double peer_b = normalised(peer.bearing_rad);
    const bool peer_ahead_on_tie = peer.robot_id > own.robot_id;
    gaps.ahead_rad = std::min(gaps.ahead_rad, ccw_gap(own_b, peer_b, peer_ahead_on_tie));
    gaps.behind_rad = std::min(gaps.behind_rad, ccw_gap(peer_b, own_b, !peer_ahead_on_tie));
    ++gaps.team_count;
  }
  return gaps;
}

}  // namespace robodds::circumnavigation_controller
