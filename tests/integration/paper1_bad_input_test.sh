#!/usr/bin/env bash
# Paper 1 components reject bad parameters with one line naming the file, the key and the
# reason (a gain set violating eq. 11/16, bad particle-filter settings, a non-finite way-point).
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/paper1_waypoints.yaml"
with_params() {  # with_params NAME COMPONENT TYPE PARAMS: a copy of paper1_waypoints with params on one component
  # (added to the component's own params when it has some, e.g. the controller's actuator limits)
  local inner="${4:1:${#4}-2}"
  # (t: a line the first expression rewrote is not rewritten again by the second)
  sed -e "s/{name: $2, type: $3}/{name: $2, type: $3, params: $4}/" -e t \
    -e "s/{name: $2, type: $3, params: {/&$inner, /" "$S" >"$WORK/$1.yaml"
  grep -qF "$inner" "$WORK/$1.yaml" || fail "rewrite of $1 did not apply"
  echo "$WORK/$1.yaml"
}
R=("$ROBODDS" run --domain "$DOMAIN" --out "$WORK/out" --no-plots)

expect_error 2 "g1\.yaml: forward_gains: .*eq\. \(11\) sgn\*·ksigma \+ ka - kd > 0" -- \
  "${R[@]}" "$(with_params g1 controller waypoint_controller '{forward_gains: {kd: 30.0, ka: 20.0, ksigma: -2.5}}')"
expect_error 2 "g2\.yaml: forward_gains: .*eq\. \(11\) kd > 0" -- \
  "${R[@]}" "$(with_params g2 controller waypoint_controller '{forward_gains: {kd: -1.0, ka: 20.0, ksigma: -2.5}}')"
expect_error 2 "g3\.yaml: epsilon_m: must be > 0" -- \
  "${R[@]}" "$(with_params g3 controller waypoint_controller '{epsilon_m: 0}')"
expect_error 2 "p1\.yaml: num_particles: must be >= 1" -- \
  "${R[@]}" "$(with_params p1 estimator pf_estimator '{num_particles: 0}')"
expect_error 2 "p2\.yaml: resample_threshold: " -- \
  "${R[@]}" "$(with_params p2 estimator pf_estimator '{num_particles: 100, resample_threshold: 500}')"
expect_error 2 "p3\.yaml: resampling: .*multinomialish" -- \
  "${R[@]}" "$(with_params p3 estimator pf_estimator '{resampling: multinomialish}')"
expect_error 2 "p4\.yaml: measurement_std_m: " -- \
  "${R[@]}" "$(with_params p4 estimator pf_estimator '{measurement_std_m: .nan}')"
expect_error 2 "m1\.yaml: waypoints" -- \
  "${R[@]}" "$(with_params m1 mission mission_source '{waypoints: [[60, 20], [.nan, 15]]}')"
expect_error 2 "m2\.yaml: waypoints" -- \
  "${R[@]}" "$(with_params m2 mission mission_source '{waypoints: []}')"
echo "ok: paper 1 bad parameters rejected with a clear one-line error"
