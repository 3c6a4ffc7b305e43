#!/usr/bin/env bash
# A QoS file missing any one profile fails cleanly, co-located and across processes: exit 2 with
# exactly one error line naming the file and the profile, no crash, no child left running, no
# Fast DDS shared-memory segment left behind. The profiles come from the file's own
# profile_name attributes (every data_writer, data_reader and participant), not from a list here.
#
# Shared memory: every run gets a private, empty /dev/shm (a mount namespace with its own tmpfs;
# the runner and its children share it), listed right after the runner exits. So a segment seen
# there is this run's, whatever other tests (ctest -j) create or leak in the real /dev/shm at the
# same time. Needs root for unshare/mount: skips (77) without it.
source "$(dirname "$0")/lib.sh"
unshare --mount --propagation private true 2>/dev/null || { echo "SKIP: needs unshare --mount (root)"; exit 77; }

QOS="$SRC/deploy/qos/robodds_qos.xml"
S="$SRC/sim/scenarios/plant_smoke.yaml"

# One copy of the QoS file per profile element, without it: "ELEMENT NAME FILE" lines.
python3 - "$QOS" "$WORK" >"$WORK/cases" <<'PY'
import re, sys
qos, work = sys.argv[1], sys.argv[2]
text = open(qos).read()
live = re.sub(r"<!--.*?-->", lambda m: " " * len(m.group(0)), text, flags=re.S)  # keep offsets
for m in re.finditer(r'<(participant|data_writer|data_reader)\s[^>]*profile_name="([^"]+)"', live):
    element, name = m.group(1), m.group(2)
    end = live.index("</%s>" % element, m.end()) + len("</%s>" % element)
    path = "%s/no_%s_%s.xml" % (work, element, name)
    open(path, "w").write(text[:m.start()] + text[end:])
    print(element, name, path)
PY
[[ $(wc -l <"$WORK/cases") -ge 10 ]] || fail "found only $(wc -l <"$WORK/cases") profiles in $QOS"

# "${PRIVATE_SHM[@]}" LEFT command...: runs command with a private /dev/shm; lists what is left in
# it (Fast DDS segments, their lock files and semaphores) into LEFT after the command exits.
PRIVATE_SHM=(unshare --mount --propagation private bash -c
  'mount -t tmpfs -o size=256m tmpfs /dev/shm || exit 97; left="$1"; shift; rc=0; "$@" || rc=$?; ls /dev/shm >"$left"; exit $rc' _)

n=0
while read -r element name file; do
  profile_args=()
  [[ $element == participant ]] && profile_args=(--participant-profile "$name")
  pattern="$(basename "$file" | sed 's/\./\\./g'): $element profile '${name//./\\.}': not found"
  for deploy in colocated processes; do
    left="$WORK/left_${deploy}_$(basename "$file")"
    expect_error 2 "$pattern" -- "${PRIVATE_SHM[@]}" "$left" "$ROBODDS" run "$S" --deploy "$deploy" --qos "$file" \
      "${profile_args[@]}" --domain "$DOMAIN" --duration 0.2 --no-plots --out "$WORK/out"
    [[ ! -s "$left" ]] || fail "$deploy without $element '$name': left in /dev/shm: $(tr '\n' ' ' <"$left")"
    ! pgrep -f -- "--domain $DOMAIN( |$)" >/dev/null || fail "$deploy without $element '$name': still running: $(pgrep -af -- "--domain $DOMAIN( |$)")"
    n=$((n + 1))
  done
done <"$WORK/cases"
echo "ok: $n runs, each without one profile of $(basename "$QOS")"
