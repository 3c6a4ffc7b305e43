#pragma once
// Every parameter of the route_follower component: the route and its law (RouteParams) plus the
// node's own. config/route_follower.params.yaml is generated from the table.

#include "common/param_table.hpp"
#include "components/route_follower/route_params.hpp"

namespace robodds::route_follower {

// Units, ranges and one-line descriptions of these fields: route_follower_param_table() in
// route_follower_params.cpp (the one source; `robodds components --params route_follower` prints
// it). Defaults: the member initialisers.
struct RouteFollowerNodeParams {
  double rate_hz = 50.0;
  RouteParams route;
  double estimate_timeout_s = 0.5;
};

const params::ParamTable<RouteFollowerNodeParams>& route_follower_param_table();

}  // namespace robodds::route_follower
