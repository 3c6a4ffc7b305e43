#!/usr/bin/env bash
# Our MCAP files read by the official reader (@mcap/core, tests/npm/check_mcap.mjs): files written
# by our writer (robodds-mcap-sample-writer, $4) with each compression pass with CRC validation,
# their statistics and indexes agree with the messages, and the hand-encoded XCDR1 samples decode
# with Foxglove's omgidl decoder to the values written. A damaged and a truncated copy must fail.
# Needs node and tests/npm/node_modules (scripts/npm_setup.sh). No DDS.
source "$(dirname "$0")/lib.sh"
SAMPLE_WRITER="$4"
CHECK="$SRC/tests/npm/check_mcap.mjs"
command -v node >/dev/null || fail "node not found (scripts/setup.sh installs nodejs)"
[[ -d $SRC/tests/npm/node_modules/@mcap/core ]] || fail "tests/npm/node_modules missing: run scripts/npm_setup.sh"
"$SAMPLE_WRITER" "$WORK"

for compression in none zstd lz4; do
  out="$(timeout -k 5 60 node "$CHECK" "$WORK/sample_$compression.mcap" --expect-json "$WORK/sample_expect.json" --counts-only 2>&1)" ||
    fail "$compression: $out"
  grep -q '"messages":403,"chunks":10,"topics":{"test/bytes":400,"test/sample":3},"decoded":3' <<<"$out" || fail "$compression: $out"
  echo "ok: $compression: $out"
done
out="$(timeout -k 5 60 node "$CHECK" "$WORK/sample_empty.mcap" --counts-only 2>&1)" || fail "empty: $out"
grep -q '"messages":0,"chunks":0,"topics":{},"decoded":0' <<<"$out" || fail "empty: $out"
echo "ok: no messages: $out"
# The decoded values, one JSON line per omgidl message (what a user sees).
out="$(timeout -k 5 60 node "$CHECK" "$WORK/sample_lz4.mcap")" || fail "lz4 listing: $out"
[[ $(wc -l <<<"$out") -eq 3 ]] || fail "expected 3 decoded messages: $out"
grep -q '"name":"robot_1","position":{"x":1.5,"y":-2.25},"ranges":\[0.5,1,2.5\],"mode":1' <<<"$out" || fail "values: $out"

# Must fail: a flipped bit in a chunk, a wrong expectation, a cut file.
python3 - "$WORK/sample_none.mcap" "$WORK/flipped.mcap" <<'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read())
b[3000] ^= 1
open(sys.argv[2], "wb").write(b)
PY
rc=0
out="$(timeout -k 5 60 node "$CHECK" "$WORK/flipped.mcap" --counts-only 2>&1)" || rc=$?
[[ $rc -eq 1 ]] && grep -q "check_mcap: .*flipped.mcap: .*CRC" <<<"$out" || fail "flipped bit not caught (exit $rc): $out"
echo "ok: flipped bit: $out"
sed 's/"stamp":12.5/"stamp":12.25/' "$WORK/sample_expect.json" >"$WORK/wrong_expect.json"
rc=0
out="$(timeout -k 5 60 node "$CHECK" "$WORK/sample_zstd.mcap" --expect-json "$WORK/wrong_expect.json" --counts-only 2>&1)" || rc=$?
[[ $rc -eq 1 ]] && grep -q "omgidl message 0 decodes to" <<<"$out" || fail "wrong expectation not caught (exit $rc): $out"
echo "ok: wrong value caught"
head -c 9000 "$WORK/sample_zstd.mcap" >"$WORK/cut.mcap"
rc=0
out="$(timeout -k 5 60 node "$CHECK" "$WORK/cut.mcap" --counts-only 2>&1)" || rc=$?
[[ $rc -eq 1 ]] || fail "cut file not refused (exit $rc): $out"
echo "ok: cut file refused: $out"
echo "PASS"
