#!/usr/bin/env bash
# Smoke test of robodds-observer-study: a short run writes the CSV with the expected header, row
# count and field count, and a bad --duration is refused with one error line.
# Usage: observer_study_smoke.sh PATH_TO_robodds-observer-study
set -euo pipefail
study=${1:?usage: observer_study_smoke.sh STUDY_EXECUTABLE}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "observer_study_smoke: $*" >&2; exit 1; }

"$study" --seeds 2 --duration short --out "$dir/study.csv" 2>"$dir/stderr" || fail "exit $?: $(cat "$dir/stderr")"
header="signal,rate_hz,sigma_m,observer,w_radps,k1,k2,q_m2ps5,seeds,lag_rms_mps,lag_ci95_mps,noise_rms_mps,noise_ci95_mps,total_rms_mps,total_ci95_mps,total_bias_mps,restarts_per_run"
[[ $(head -n 1 "$dir/study.csv") == "$header" ]] || fail "header: $(head -n 1 "$dir/study.csv")"
rows=$(($(wc -l <"$dir/study.csv") - 1))
((rows == 288)) || fail "expected 288 rows (2 signals x 3 rates x 4 sigmas x 12 observers), got $rows"
awk -F, 'NR > 1 && NF != 17 { print "line " NR ": " NF " fields"; bad = 1 } END { exit bad }' "$dir/study.csv" ||
  fail "field count"
# Every (signal, rate, sigma) has one super-twisting row, seven linear ones and four Kalman ones (q set).
sta=$(grep -c ',sta,' "$dir/study.csv")
((sta == 24)) || fail "expected 24 super-twisting rows, got $sta"
kf=$(awk -F, '$4 == "kf" && $8 > 0' "$dir/study.csv" | wc -l)
((kf == 96)) || fail "expected 96 Kalman rows with q > 0, got $kf"
# Noise-free constant range: a zero noise floor; with noise: a positive one.
awk -F, 'NR > 1 && $3 == 0 && $12 != 0 { print "sigma 0 noise floor " $12 " on line " NR; bad = 1 }
         NR > 1 && $3 > 0 && !($12 > 0) { print "sigma " $3 " noise floor " $12 " on line " NR; bad = 1 }
         END { exit bad }' "$dir/study.csv" || fail "noise floor column"

if "$study" --duration soon >/dev/null 2>"$dir/stderr"; then fail "--duration soon accepted"; fi
grep -q "^robodds-observer-study: error: --duration" "$dir/stderr" || fail "bad --duration message: $(cat "$dir/stderr")"
echo "observer_study_smoke: ok ($rows rows)"
