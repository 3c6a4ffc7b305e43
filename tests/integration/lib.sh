# Helpers for integration tests: real robodds processes over real DDS.
# Each test gets ROBODDS (binary), SRC (repo root) and DOMAIN (its own domain id).
set -euo pipefail
ROBODDS="$1"
SRC="$2"
DOMAIN="$3"
WORK="$(mktemp -d /tmp/robodds-test.XXXXXX)"
cleanup_pids=()
cleanup() {
  for pid in "${cleanup_pids[@]:-}"; do
    [[ -n "$pid" ]] && kill "$pid" 2>/dev/null || true
  done
  rm -rf "$WORK"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# expect_error EXPECTED_EXIT PATTERN -- command...: runs command, checks exit code and stderr.
expect_error() {
  local code="$1" pattern="$2"; shift 3
  local out rc=0
  out="$(timeout -k 5 60 "$@" 2>&1)" || rc=$?
  [[ $rc -eq $code ]] || fail "expected exit $code, got $rc from: $* -- output: $out"
  grep -qE -- "$pattern" <<<"$out" || fail "expected /$pattern/ in: $out"
  [[ $(grep -c "error:" <<<"$out") -eq 1 ]] || fail "expected exactly one error line in: $out"
  echo "ok: $pattern"
}
