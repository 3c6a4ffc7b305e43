#!/usr/bin/env bash
# The end of `robodds run` (issue 26, findings 1 and 2), piped as in a CI log (paper 1, 20 s):
# 1. stdout and stderr in one pipe: the header is the first line and the report comes after the
#    progress; progress is one line per 10 % on stderr (not a terminal); the report is at most 15
#    lines, has the way-point and PF headline lines, and no robot's figure twice (robots.1).
# 2. --quiet prints only the output directory, --json summary.json byte for byte and nothing else
#    on stdout, --verbose every figure (metrics.robots.1.pf_rmse_m).
# 3. Bad input found after the header: header first, the error line last.
# 4. A NaN estimate: the report's rejected-inputs and warnings lines.
# 5. A sweep: paced progress, the headline rows on stdout. 6. A replay --fast: progress lines.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/paper1_waypoints.yaml"
RUN=(timeout -k 5 60 "$ROBODDS" run "$S" --duration 20 --no-plots --domain "$DOMAIN")

"${RUN[@]}" --out "$WORK/a" >"$WORK/both.log" 2>&1 || fail "run failed: $(tail -5 "$WORK/both.log")"
head -1 "$WORK/both.log" | grep -q "^robodds run paper1_waypoints: colocated, lockstep, 2001 steps" ||
  fail "the header is not the first line: $(head -3 "$WORK/both.log")"
progress=$(grep -c "^  step [0-9]* / 2000 ([0-9]* %), .* s simulated, .*x real time, ETA" "$WORK/both.log" || true)
[[ $progress -eq 10 ]] || fail "expected 10 progress lines (one per 10 %) when piped, got $progress: $(cat "$WORK/both.log")"
last_progress=$(grep -n "^  step 2000 / 2000" "$WORK/both.log" | cut -d: -f1)
status_line=$(grep -n "^completed: 20 s simulated in .* s (.*x real time)$" "$WORK/both.log" | cut -d: -f1)
[[ -n $status_line && $status_line -gt $last_progress ]] || fail "the report is not after the progress: $(cat "$WORK/both.log")"
report_lines=$(( $(wc -l <"$WORK/both.log") - status_line + 1 ))
[[ $report_lines -le 15 ]] || fail "the report has $report_lines lines (at most 15): $(cat "$WORK/both.log")"
grep -qE "^  way-points +[0-9]+ of 18 reached" "$WORK/both.log" || fail "no way-point line: $(cat "$WORK/both.log")"
grep -qE "^  estimate RMSE +[0-9.]+ m position, [0-9.]+ deg heading$" "$WORK/both.log" || fail "no estimate RMSE line: $(cat "$WORK/both.log")"
grep -q "robots" "$WORK/both.log" && fail "a robot's figures printed apart: $(cat "$WORK/both.log")"
tail -1 "$WORK/both.log" | grep -q "^results: $WORK/a (summary.json, 7 CSV files; --verbose prints every figure)$" ||
  fail "the last line does not say where the outputs are: $(tail -2 "$WORK/both.log")"
echo "ok: header first, 10 progress lines, a report of $report_lines lines"

"${RUN[@]}" --out "$WORK/q" --quiet >"$WORK/q.out" 2>"$WORK/q.err" || fail "--quiet run failed: $(cat "$WORK/q.err")"
[[ $(cat "$WORK/q.out") == "$WORK/q" && ! -s "$WORK/q.err" ]] ||
  fail "--quiet: expected only the output directory, got stdout: $(cat "$WORK/q.out") stderr: $(cat "$WORK/q.err")"
"${RUN[@]}" --out "$WORK/j" --json >"$WORK/j.out" 2>"$WORK/j.err" || fail "--json run failed: $(cat "$WORK/j.err")"
cmp -s "$WORK/j.out" "$WORK/j/summary.json" || fail "--json: stdout is not summary.json: $(head -5 "$WORK/j.out")"
python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$WORK/j.out" || fail "--json: stdout does not parse as JSON"
"${RUN[@]}" --out "$WORK/v" --verbose >"$WORK/v.out" 2>&1 || fail "--verbose run failed: $(tail -3 "$WORK/v.out")"
grep -qE "^  metrics.robots.1.pf_rmse_m +[0-9.]+$" "$WORK/v.out" || fail "--verbose: no full dump: $(head -20 "$WORK/v.out")"
echo "ok: --quiet, --json, --verbose"

# Bad input found once the run has started (7 Hz does not divide the 100 Hz steps): the header
# first, then the one error line (a pipe's buffering used to print the header after it).
rc=0
"${RUN[@]}" --out "$WORK/f" --set position_sensor.rate_hz=7 >"$WORK/f.log" 2>&1 || rc=$?
[[ $rc -eq 2 ]] || fail "expected exit 2 from bad input, got $rc: $(cat "$WORK/f.log")"
head -1 "$WORK/f.log" | grep -q "^robodds run paper1_waypoints:" || fail "bad input: the header is not first: $(cat "$WORK/f.log")"
tail -1 "$WORK/f.log" | grep -q "^robodds: error: --set: rate_hz: " || fail "bad input: the error line is not last: $(cat "$WORK/f.log")"
echo "ok: bad input: header first, error line last"

# A NaN estimate (rejected by the controller, logged): the report names the rejected input and the warning.
sed 's/{name: estimator, type: truth_estimator}/{name: estimator, type: truth_estimator, params: {inject_nan_at_step: 100}}/' \
  "$SRC/sim/scenarios/paper1_ideal.yaml" >"$WORK/nan.yaml"
timeout -k 5 60 "$ROBODDS" run "$WORK/nan.yaml" --duration 5 --no-plots --domain "$DOMAIN" --out "$WORK/n" >"$WORK/n.out" 2>"$WORK/n.err" ||
  fail "NaN run failed: $(cat "$WORK/n.err")"
grep -qE "^  rejected inputs +controller estimate/pose: 1 [a-z_]+" "$WORK/n.out" || fail "no rejected input line: $(cat "$WORK/n.out")"
grep -qE "^  warnings +[0-9]+ warnings? logged above$" "$WORK/n.out" || fail "no warnings line: $(cat "$WORK/n.out")"
echo "ok: rejected inputs and warnings in the report"

# A sweep piped (domains DOMAIN and DOMAIN + 1): progress paced (a line per 10 % of the runs at most, the last
# always), stdout's table has the headline figures' rows only (summary.md every metric).
timeout -k 5 120 "$ROBODDS" sweep "$SRC/sim/scenarios/constant_twist.yaml" --seeds 1-20 --duration 1 --jobs 2 --domain "$DOMAIN" \
  --out "$WORK/s" >"$WORK/s.out" 2>"$WORK/s.err" || fail "sweep failed: $(tail -5 "$WORK/s.err")"
lines=$(grep -c "^sweep: [0-9]*/20 runs done" "$WORK/s.err" || true)
[[ $lines -ge 1 && $lines -le 10 ]] && grep -q "^sweep: 20/20 runs done, 0 failed" "$WORK/s.err" ||
  fail "sweep progress: expected at most one line per 10 % of the runs (10) and the last: $(cat "$WORK/s.err")"
grep -q "^| max_abs_v_applied_mps | 20 |" "$WORK/s.out" && ! grep -q "max_abs_v_commanded_mps" "$WORK/s.out" &&
  grep -q "^| max_abs_v_commanded_mps | 20 |" "$WORK/s/summary.md" ||
  fail "sweep stdout: expected the headline rows only: $(cat "$WORK/s.out")"
echo "ok: sweep: $lines progress lines for 20 runs, the headline rows on stdout"

# `robodds replay --fast` piped: a progress line per 10 % of the messages.
timeout -k 5 60 "$ROBODDS" run "$SRC/sim/scenarios/constant_twist.yaml" --duration 5 --no-plots --domain "$DOMAIN" --out "$WORK/r" \
  --record "$WORK/r.mcap" --quiet >/dev/null || fail "recording run failed"
timeout -k 5 60 "$ROBODDS" replay "$WORK/r.mcap" --fast --wait-readers 0 --domain "$DOMAIN" >"$WORK/replay.out" 2>"$WORK/replay.err" ||
  fail "replay failed: $(cat "$WORK/replay.err")"
lines=$(grep -cE "^  message [0-9]+ / [0-9]+ \([0-9]+ %\), .* s of the recording, .*ETA" "$WORK/replay.err" || true)
[[ $lines -eq 10 ]] || fail "replay: expected 10 progress lines, got $lines: $(cat "$WORK/replay.err")"
echo "ok: replay: 10 progress lines"
