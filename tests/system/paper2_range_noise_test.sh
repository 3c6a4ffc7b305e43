#!/usr/bin/env bash
# Issue 27, finding 1: paper 2 with the range sensor 4x noisier (sigma 2 m) than the observer's
# configured 0.5 m (sim/scenarios/degraded/paper2_range_noise_2m.yaml), one seed. With the fixed
# 5 m restart threshold noise alone restarted each observer ~30,000 times and the formation never
# settled (phase settle -1, radius RMSE > 1,000 m); with the threshold on the estimated noise both
# phases settle within 600 s, the radius RMSE stays <= 1.2 m and the observers restart exactly at
# the target switch (3 robots switch: 3); each observer's reported rate std holds (issue 27). ~2-5 s.
source "$(dirname "$0")/../integration/lib.sh"
timeout -k 5 120 "$ROBODDS" --log info run "$SRC/sim/scenarios/degraded/paper2_range_noise_2m.yaml" --seed 3 \
  --domain "$DOMAIN" --out "$WORK/run" --no-plots >"$WORK/run.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/run.log")"
python3 - "$WORK/run/summary.json" <<'PY' || fail "paper 2 at 2 m of range noise: $(cat "$WORK/run.log" | tail -8)"
import json, sys
m = json.load(open(sys.argv[1]))["metrics"]
bad = []
for phase in ("phase1", "phase2"):
    settle, radius = m[phase]["settle_time_s"], m[phase]["radius_rmse_m"]
    if not 0 <= settle <= 600:
        bad.append(f"{phase}.settle_time_s {settle} (bound 0-600 s)")
    if radius is None:  # not settled: no tail figure (issue 27)
        bad.append(f"{phase}.radius_rmse_m null: {m[phase].get('not_settled')}")
    elif radius > 1.2:
        bad.append(f"{phase}.radius_rmse_m {radius} (bound 1.2 m)")
for observer in ("sta", "linear"):
    o = m["observer"][observer]
    if o["restarts"] != 3:
        bad.append(f"observer.{observer}.restarts {o['restarts']} (the mission's 3 target switches)")
    # The estimated range noise is reported (issue 27): the robots' mean near the true 2 m.
    if not 1.6 <= o.get("range_noise_std_m", 0) <= 2.4:
        bad.append(f"observer.{observer}.range_noise_std_m {o.get('range_noise_std_m')} (the sensor's sigma is 2 m)")
    # The rate std each estimate reports holds against the truth (issue 27): <= 1 % of the valid
    # estimates outside 3 stds (measured 0.01-0.02 %; reporting the 0.5 m floor's check-line spread instead of
    # measuring it, 0.087 m/s: 42-45 %).
    c = o["consistency"]
    if c["valid_samples"] < 300000 or c["overconfident_fraction"] > 0.01:
        bad.append(f"observer.{observer}.consistency: {c['overconfident_fraction']:.4f} of {c['valid_samples']} valid over-confident (bound 0.01)")
if bad:
    sys.exit("FAIL: " + "; ".join(bad))
PY
grep -qE "observer: robot 1: range noise estimated sigma (1\.[6-9]|2\.[0-4])[0-9]* m \(floor 0\.5 m\)" "$WORK/run.log" \
  || fail "no estimated range noise near 2 m logged for robot 1: $(grep 'range noise' "$WORK/run.log")"

# Issue 27, finding 6 (two more runs, ~3 s each, noise-free). (1) A start formation never tuned on
# (degraded/paper2_start_random_3.yaml): the observer converges in 2.86 s; the convergence read
# 96.1 s before excursions where the truth |r''| broke the bound b were excused. (2) 10 % of the
# ranges lost (seed 1): with each gap integrated as one Euler step the sliding mode's chattering
# grew (seed 2: steady RMSE 0.043 m/s, 0.95 % over-confident, convergence 367 s); integrated period
# by period: 0.032 m/s, 0.02 %, but a lost step republished the last estimate, its rate held while
# the truth moved, and seed 1's 200 s hold broke at 221.5 s; each lost step carrying the observer's
# prediction (RangeRateObserver::predict): 2.48 s. Both mission verdicts "complete".
timeout -k 5 120 "$ROBODDS" run "$SRC/sim/scenarios/degraded/paper2_start_random_3.yaml" --seed 1 \
  --domain "$DOMAIN" --out "$WORK/start" --no-plots >"$WORK/start.log" 2>&1 || fail "start formation run failed: $(tail -5 "$WORK/start.log")"
timeout -k 5 120 "$ROBODDS" run "$SRC/sim/scenarios/paper2_circumnavigation.yaml" --seed 1 --set range_sensor.dropout_probability=0.1 \
  --domain "$DOMAIN" --out "$WORK/dropouts" --no-plots >"$WORK/dropouts.log" 2>&1 || fail "dropout run failed: $(tail -5 "$WORK/dropouts.log")"
python3 - "$WORK/start/summary.json" "$WORK/dropouts/summary.json" <<'PY' || fail "paper 2 convergence from an unseen start or with dropouts"
import json, sys
bad = []
for path, name in zip(sys.argv[1:], ("random_3 start", "10 % dropouts")):
    s = json.load(open(path))
    o = s["metrics"]["observer"]["sta"]
    if s.get("mission") != "complete":
        bad.append(f"{name}: mission {s.get('mission')}")
    if not 0 <= o["convergence_s"] <= 5:
        bad.append(f"{name}: observer.sta.convergence_s {o['convergence_s']} (bound 5 s)")
    if o["steady_rmse_mps"] > 0.036:
        bad.append(f"{name}: observer.sta.steady_rmse_mps {o['steady_rmse_mps']} (bound 0.036; 0.043 with one Euler step per gap)")
    if o["consistency"]["overconfident_fraction"] > 0.001:
        bad.append(f"{name}: observer.sta over-confident {o['consistency']['overconfident_fraction']} (bound 0.001)")
    if o["restarts"] != 2 + (name != "random_3 start"):
        bad.append(f"{name}: observer.sta.restarts {o['restarts']} (the mission's target switches)")
if bad:
    sys.exit("FAIL: " + "; ".join(bad))
PY
echo "ok: paper 2 at 2 m of range noise settles, restarts only at the target switch, estimates the noise; converges from an unseen start and with 10 % dropouts"
