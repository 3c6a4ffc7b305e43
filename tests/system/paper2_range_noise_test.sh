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
echo "ok: paper 2 at 2 m of range noise settles, restarts only at the target switch, estimates the noise"
