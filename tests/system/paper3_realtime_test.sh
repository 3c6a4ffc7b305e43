#!/usr/bin/env bash
# Paper 3 beyond the paper: every robot's estimator in its own process, in REAL time (wall-clock
# timers, latest-sample inputs), UWB at the full 50 Hz with 30 % of the frames lost (the top of issue
# 11's 10-30 %); the position and heading errors of the estimator's stages (uwb, window, pf) stay
# within 20 % of the same deployment's lockstep figures, and valid estimates keep coming. The
# baseline [22] is printed, not bounded: it weighs the newest frame's ranges directly, and its
# heading in real time ran 8-24 % above lockstep in three runs (a frame up to 20 ms old while the
# robot turns at 0.5 rad/s).
# Argument after the domain: duration (s).
source "$(dirname "$0")/../integration/lib.sh"
python3 "$(dirname "$0")/paper3_per_robot.py" "$SRC/sim/scenarios/paper3_exp2.yaml" "$WORK/per_robot.yaml" "$4" 0.3 \
  || fail "could not write the per-robot scenario"
timeout -k 5 300 "$ROBODDS" run "$WORK/per_robot.yaml" --out "$WORK/lockstep" --domain "$DOMAIN" --no-plots >"$WORK/lockstep.log" 2>&1 \
  || fail "lockstep run failed: $(tail -5 "$WORK/lockstep.log")"
timeout -k 5 $(( ${4%.*} + 120 )) "$ROBODDS" run "$WORK/per_robot.yaml" --realtime $(rt_priority_flag) --deploy processes --out "$WORK/realtime" \
  --domain "$DOMAIN" --no-plots >"$WORK/realtime.log" 2>&1 || fail "real-time run failed: $(tail -5 "$WORK/realtime.log")"
python3 - "$WORK/lockstep/summary.json" "$WORK/realtime/summary.json" <<'PY' || fail "real-time errors out of bounds"
import json, sys
lockstep, realtime = (json.load(open(p))["metrics"]["stages"] for p in sys.argv[1:])
failed = []
for stage in ("uwb", "window", "pf", "pf_baseline"):
    a, b = lockstep[stage], realtime[stage]
    print(f"{stage:12s} lockstep {a['position_error_m_mean']:.3f} m / {a['heading_error_deg_mean']:.2f} deg ({a['epochs']} epochs), "
          f"real time {b['position_error_m_mean']:.3f} m / {b['heading_error_deg_mean']:.2f} deg ({b['epochs']} epochs)")
    if b["epochs"] < 0.5 * a["epochs"]:
        failed.append(f"{stage}: {b['epochs']} valid epochs in real time against {a['epochs']} in lockstep")
    for key in ("position_error_m_mean", "heading_error_deg_mean"):
        if stage != "pf_baseline" and b[key] > 1.2 * a[key]:
            failed.append(f"{stage}.{key}: real time {b[key]:.3f} > 1.2 x lockstep {a[key]:.3f}")
if failed:
    sys.exit("FAIL: " + "; ".join(failed))
PY
echo "ok: paper 3 in real time, one process per robot, 30 % UWB frames lost: uwb, window and pf within 20 % of lockstep"
