#include "components/route_follower/route_params.hpp"

#include <cmath>
#include <string>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::route_follower {
namespace {

std::string point_text(std::size_t index, const params::Point2& p) {
  return "point " + std::to_string(index) + " (" + shortest_text(p[0]) + ", " + shortest_text(p[1]) + ")";
}

/// At least 2 points, each finite (the table's range of `route`).
params::Check<std::vector<params::Point2>> two_or_more_finite_points() {
  return {"at least 2 points", [](std::string_view key, const std::vector<params::Point2>& points) {
            if (points.size() < 2) {
              param_checks::reject(key, "a route needs at least 2 points", std::to_string(points.size()) + " point(s)");
            }
            for (std::size_t i = 0; i < points.size(); ++i) {
              if (!std::isfinite(points[i][0]) || !std::isfinite(points[i][1])) {
                param_checks::reject(key, "every coordinate must be finite", point_text(i, points[i]));
              }
            }
          }};
}

/// Consecutive points (with loop also the last and the first) at least `tolerance` apart.
void check_spacing(const RouteParams& p) {
  const std::size_t n = p.route.size();
  const std::size_t segments = p.loop ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const params::Point2& a = p.route[i];
    const params::Point2& b = p.route[(i + 1) % n];
    const double distance = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!(distance >= p.position_tolerance_m)) {
      param_checks::reject("route",
                           "consecutive points must be at least position_tolerance_m " +
                               shortest_text(p.position_tolerance_m) + " m apart" +
                               (i + 1 == n ? " (loop: true joins the last point to the first; do not repeat it)" : ""),
                           point_text(i, a) + " and " + point_text((i + 1) % n, b) + ", " + shortest_text(distance) +
                               " m apart");
    }
  }
}

}  // namespace

const params::ParamTable<RouteParams>& route_param_table() {
  using R = RouteParams;
  static const params::ParamTable<RouteParams> table =
      params::ParamTable<RouteParams>()
          .add("route", &R::route, "m", two_or_more_finite_points(),
               "world [x, y] of each vertex, in driving order (see loop)")
          .add("loop", &R::loop, "", params::any<bool>(),
               "true: closed, the last point joins the first and laps repeat; false: stop at the last point")
          .add("speed_mps", &R::speed_mps, "m/s", params::positive(), "forward speed on the segments (paper 3: 0.2)")
          .add("turn_rate_radps", &R::turn_rate_radps, "rad/s", params::positive(), "turn rate of the turns in place")
          .add("position_tolerance_m", &R::position_tolerance_m, "m", params::positive(),
               "a vertex is reached within this distance")
          .add("heading_tolerance_rad", &R::heading_tolerance_rad, "rad",
               params::shown_as(params::in_open_interval(0.0, kPi), "(0, pi)"),
               "the turn in place ends below this heading error")
          .add("lookahead_m", &R::lookahead_m, "m", params::positive(),
               "line following: desired heading = segment heading - atan(cross-track / lookahead)")
          .add("heading_gain", &R::heading_gain, "1/s", params::positive(),
               "line following: omega = gain * heading error, clamped to max_correction_radps")
          .add("max_correction_radps", &R::max_correction_radps, "rad/s",
               params::shown_as(params::positive(), "(0, turn_rate_radps]"), "|omega| bound while driving")
          .add("realign_threshold_rad", &R::realign_threshold_rad, "rad",
               params::shown_as(params::in_open_interval(0.0, kPi), "(heading_tolerance_rad, pi)"),
               "a larger heading error while driving stops the robot and turns it in place again");
  return table;
}

void RouteParams::validate() const {
  route_param_table().check_ranges(*this);
  check_spacing(*this);
  if (!(max_correction_radps <= turn_rate_radps)) {
    param_checks::reject("max_correction_radps", "must be <= turn_rate_radps " + shortest_text(turn_rate_radps),
                         max_correction_radps);
  }
  if (!(realign_threshold_rad > heading_tolerance_rad)) {
    param_checks::reject("realign_threshold_rad",
                         "must be > heading_tolerance_rad " + shortest_text(heading_tolerance_rad) +
                             " (else the robot turns again as soon as it drives)",
                         realign_threshold_rad);
  }
}

}  // namespace robodds::route_follower
