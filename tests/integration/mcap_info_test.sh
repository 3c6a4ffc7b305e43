#!/usr/bin/env bash
# `robodds info` on files written by our MCAP writer (robodds-mcap-sample-writer, $4): a whole file,
# a truncated one (prints what was recovered, warning, exit 0), a CRC-corrupted one (prints the
# problem, exit 1), not an MCAP file and a missing file (one error line, exit 2). No DDS.
source "$(dirname "$0")/lib.sh"
SAMPLE_WRITER="$4"
"$SAMPLE_WRITER" "$WORK"
F="$WORK/sample_zstd.mcap"

out="$("$ROBODDS" info "$F")" || fail "info on a whole file failed: $out"
for pattern in "summary: +present, CRCs valid" "chunks: +10 \(zstd\)" "messages: +403" "duration: +3\.990 s" \
  " 1  test/sample +robodds_test::Sample +omgidl +cdr +3 +1\.00" " 2  test/bytes .* 400 +100\.00"; do
  grep -qE -- "$pattern" <<<"$out" || fail "expected /$pattern/ in: $out"
done
echo "ok: whole file"

out="$("$ROBODDS" info "$WORK/sample_empty.mcap")" || fail "info on a file without messages failed: $out"
grep -qE "^messages: +0$" <<<"$out" && grep -qE "^chunks: +0$" <<<"$out" && grep -qE " 1  test/sample .* 0 +-$" <<<"$out" ||
  fail "file without messages: $out"
echo "ok: no messages"

# Cut inside the 7th chunk: the 6 before it are recovered.
head -c 9000 "$F" >"$WORK/cut.mcap"
rc=0
out="$("$ROBODDS" info "$WORK/cut.mcap" 2>"$WORK/cut.err")" || rc=$?
[[ $rc -eq 0 ]] || fail "truncated file: exit $rc, expected 0: $out $(cat "$WORK/cut.err")"
grep -qE "^recovered: +truncated at byte [0-9]+: 6 complete chunks, 250 messages recovered; summary missing$" <<<"$out" ||
  fail "truncated file: no recovery line in: $out"
grep -qE "^robodds info: warning: .*cut\.mcap: truncated at byte" "$WORK/cut.err" || fail "no warning line: $(cat "$WORK/cut.err")"
echo "ok: truncated"

# One bit flipped inside the first chunk's records (uncompressed file, so the chunk still parses).
python3 - "$WORK/sample_none.mcap" "$WORK/flipped.mcap" <<'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read())
b[3000] ^= 1
open(sys.argv[2], "wb").write(b)
PY
rc=0
out="$("$ROBODDS" info "$WORK/flipped.mcap" 2>&1)" || rc=$?
[[ $rc -eq 1 ]] || fail "corrupted file: exit $rc, expected 1: $out"
grep -qE "problem: +.*flipped\.mcap: byte 32: Chunk CRC mismatch" <<<"$out" || fail "corrupted file: CRC problem not named: $out"
echo "ok: CRC mismatch"

printf 'not an mcap file at all' >"$WORK/text.mcap"
expect_error 2 "robodds: error: $WORK/text\.mcap: byte 0: not an MCAP file \(bad magic\)" -- "$ROBODDS" info "$WORK/text.mcap"
expect_error 2 "robodds: error: $WORK/missing\.mcap: cannot open: No such file or directory" -- "$ROBODDS" info "$WORK/missing.mcap"
: >"$WORK/empty.mcap"
expect_error 2 "empty\.mcap: byte 0: not an MCAP file" -- "$ROBODDS" info "$WORK/empty.mcap"
echo "PASS"
