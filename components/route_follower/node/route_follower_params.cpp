#include "components/route_follower/node/route_follower_params.hpp"

namespace robodds::route_follower {

const params::ParamTable<RouteFollowerNodeParams>& route_follower_param_table() {
  using N = RouteFollowerNodeParams;
  static const params::ParamTable<RouteFollowerNodeParams> table =
      params::ParamTable<RouteFollowerNodeParams>(
          "Route follower (issue 11, paper 3's robots): drives a closed or open polygon of world points,\n"
          "turning in place at each vertex, then driving the segment with a bounded line-following\n"
          "correction. Every robot it serves drives the same route: one instance per robot for different\n"
          "routes (robots: [N]). Zero command while the pose estimate is missing, not valid or stale.")
          .add("rate_hz", &N::rate_hz, "Hz", params::positive(), "control rate; must divide the simulation rate")
          .include(&N::route, route_param_table())
          .add("estimate_timeout_s", &N::estimate_timeout_s, "s", params::positive(),
               "real time only: an estimate received longer ago than this stops the robot; > the control period");
  return table;
}

}  // namespace robodds::route_follower
