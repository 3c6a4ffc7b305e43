#!/usr/bin/env bash
# DDS Security (docs/security.md): `robodds security init` makes the files of plant_smoke; a secure
# lockstep run across processes writes byte-identical results to an unsecured one; a participant
# without credentials sees no topic and no sample of a secure run, one with the tools identity
# does; a host whose group may not publish plant/cmd is refused its writer; missing, tampered,
# foreign and expired files are refused at start-up with one error naming the file and the kind
# of damage, and an edited permissions.xml review copy naming it and the signed permissions;
# `security init` without openssl on PATH names the program and its Debian package.
# Uses DOMAIN and DOMAIN+1.
source "$(dirname "$0")/lib.sh"
SCENARIO="$SRC/sim/scenarios/plant_smoke.yaml"
SEC="$WORK/sec"
"$ROBODDS" security init "$SCENARIO" --out "$SEC" >"$WORK/init.log" 2>&1 || fail "security init: $(cat "$WORK/init.log")"
for id in control sim sensing evaluation coordinator colocated tools; do
  for f in identity_ca.pem cert.pem key.pem governance.p7s permissions.p7s; do
    [[ -s "$SEC/$id/$f" ]] || fail "missing $SEC/$id/$f"
  done
done
[[ $(stat -c %a "$SEC/sim/key.pem") == 600 ]] || fail "private key is not 0600"
mkdir -p "$WORK/no-openssl-bin"
expect_error 1 "security init: the 'openssl' program was not found on PATH \(install the Debian package openssl\)" -- \
  env PATH="$WORK/no-openssl-bin" "$ROBODDS" security init "$SCENARIO" --out "$WORK/no-openssl"
[[ ! -e "$WORK/no-openssl/ca" ]] || fail "security init without openssl wrote $WORK/no-openssl/ca"
grep -q "<topic>plant/cmd</topic>" "$SEC/control/permissions.xml" || fail "control may not publish plant/cmd"
! grep -q "<topic>plant/cmd</topic>" "$SEC/sensing/permissions.xml" || fail "sensing must not name plant/cmd"

# 1. Secure across processes == unsecured (and secure co-located).
run() {  # run NAME ARGS...: a 5 s lockstep run into $WORK/NAME
  local name=$1; shift
  timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --duration 5 --out "$WORK/$name" --domain "$DOMAIN" --no-plots "$@" \
    >"$WORK/$name.log" 2>&1 || fail "run $name failed: $(cat "$WORK/$name.log")"
}
run plain --deploy processes
# One attempt, no retry: with Fast DDS 2.9.1 a secure run across processes used to stall at step 0
# now and then (two participants never authenticated: a race in its SecurityManager), which
# `robodds run` avoids with the participant profile robodds.participant.secure_local (docs/security.md,
# known problem). A stall fails here, named as such.
secure_run() {
  local name=$1
  shift
  timeout -k 5 120 "$ROBODDS" run "$SCENARIO" --duration 5 --out "$WORK/$name" --domain "$DOMAIN" --no-plots \
    --input-timeout 5 --start-timeout 15 --security "$SEC" "$@" >"$WORK/$name.log" 2>&1 && return 0
  grep -qE "waited [0-9.]+ s at step [01] for topic|no tick on sim/clock .* after step [01]|no acknowledgement of step [01] " \
    "$WORK/$name.log" && fail "run $name: secure start-up stall (docs/security.md, known problem): $(cat "$WORK/$name.log")"
  fail "run $name failed: $(cat "$WORK/$name.log")"
}
secure_run secure --deploy processes
grep -q "participant profile robodds.participant.secure_local" "$WORK/secure.log" ||
  fail "the secure run across processes did not use robodds.participant.secure_local: $(cat "$WORK/secure.log")"
same_outputs "$WORK/plain" "$WORK/secure"
secure_run secure_colocated
same_outputs "$WORK/plain" "$WORK/secure_colocated"
echo "ok: secure lockstep runs (processes, co-located) byte-identical to the unsecured one ($N_CSV CSVs)"

# 2. A secure real-time run; outsiders see nothing, the tools identity sees it.
# 14 s: on a busy machine the hosts start late and the tools identity's handshake (PKI-DH) takes
# seconds; its echo runs above the CPU hogs like the run's loops (rt_chrt).
timeout -k 5 60 "$ROBODDS" run "$SCENARIO" --realtime $(rt_priority_flag) --deploy processes --duration 14 --out "$WORK/rt" --domain "$DOMAIN" \
  --security "$SEC" --no-plots >"$WORK/rt.log" 2>&1 &
cleanup_pids+=("$!")
sleep 3
topics="$(timeout -k 2 20 "$ROBODDS" topics --duration 2 --domain "$DOMAIN")" || fail "robodds topics failed: $topics"
grep -q "(no topics seen" <<<"$topics" || fail "an unauthenticated participant discovered topics: $topics"
expect_error 1 "no sample on plant/state within 2" -- "$ROBODDS" echo plant/state --count 1 --timeout 2 --domain "$DOMAIN"
out="$(timeout -k 2 20 $(rt_chrt 10) "$ROBODDS" echo plant/state --count 2 --timeout 9 --domain "$DOMAIN" --security "$SEC")" ||
  fail "the tools identity received nothing: $out"
[[ $(grep -c "^--- plant/state (robot_id=" <<<"$out") -eq 2 ]] || fail "expected 2 samples with credentials: $out"
wait "${cleanup_pids[-1]}" || fail "the secure real-time run failed: $(cat "$WORK/rt.log")"
echo "ok: no credentials, no topics and no samples; the tools identity receives"

# 3. A group with a valid identity but no permission to publish plant/cmd: its writer is refused.
sed 's/^  sensing: \[position_sensor\]/  sensing: [position_sensor, commander]/; /^  control: \[commander\]/d' \
  "$SCENARIO" >"$WORK/hostile.yaml"
grep -q "sensing: \[position_sensor, commander\]" "$WORK/hostile.yaml" || fail "hostile scenario not rewritten"
expect_error 2 "cannot create a writer on plant/cmd .*plant/cmd topic not found in allow rule" -- "$ROBODDS" host --scenario "$WORK/hostile.yaml" --group sensing --realtime --duration 3 \
  --domain $((DOMAIN + 1)) --security "$SEC"
echo "ok: a group without permission to publish plant/cmd is refused its writer"

# 4. Bad files: one error naming the file and the problem, before anything starts.
bad() { rm -rf "$WORK/bad"; cp -r "$SEC" "$WORK/bad"; }
host_sim=("$ROBODDS" host --scenario "$SCENARIO" --group sim --domain $((DOMAIN + 1)) --security "$WORK/bad" --start-timeout 1)
bad; rm "$WORK/bad/sim/permissions.p7s"
expect_error 2 "bad/sim/permissions.p7s: DDS Security: permissions not found" -- "${host_sim[@]}"
bad; sed -i 's|<topic>plant/state</topic>|<topic>plant/cmd</topic>|' "$WORK/bad/sim/permissions.p7s"
cmp -s "$SEC/sim/permissions.p7s" "$WORK/bad/sim/permissions.p7s" && fail "permissions not tampered"
expect_error 2 "bad/sim/permissions.p7s: DDS Security: permissions content was changed after signing" -- "${host_sim[@]}"
bad; cp "$WORK/bad/sim/permissions.xml" "$WORK/bad/sim/permissions.p7s"
expect_error 2 "bad/sim/permissions.p7s: DDS Security: permissions is not an S/MIME signed document" -- "${host_sim[@]}"
bad; sed -i '0,/^MII/s//*II/' "$WORK/bad/sim/permissions.p7s"  # the first base64 line of the signature block
cmp -s "$SEC/sim/permissions.p7s" "$WORK/bad/sim/permissions.p7s" && fail "signature block not tampered"
expect_error 2 "bad/sim/permissions.p7s: DDS Security: permissions signature block is corrupted" -- "${host_sim[@]}"
bad; sed -i 's|<topic>plant/state</topic>|<topic>plant/cmd</topic>|' "$WORK/bad/sim/permissions.xml"
expect_error 2 "bad/sim/permissions.xml: DDS Security: differs from the signed permissions .*bad/sim/permissions.p7s" -- "${host_sim[@]}"
"$ROBODDS" security init "$SCENARIO" --out "$WORK/other" >/dev/null 2>&1 || fail "second security init"
bad; cp "$WORK/other/sim/permissions.p7s" "$WORK/bad/sim/"
expect_error 2 "bad/sim/permissions.p7s: DDS Security: permissions is signed by another CA" -- "${host_sim[@]}"
bad; cp "$WORK/other/sim/cert.pem" "$WORK/other/sim/key.pem" "$WORK/bad/sim/"
expect_error 2 "bad/sim/cert.pem: DDS Security: identity certificate is not signed by the CA" -- "${host_sim[@]}"
bad; openssl req -new -key "$SEC/sim/key.pem" -subj "/CN=sim@plant_smoke" -out "$WORK/x.csr" 2>/dev/null
openssl x509 -req -in "$WORK/x.csr" -CA "$SEC/ca/ca_cert.pem" -CAkey "$SEC/ca/ca_key.pem" -days 0 -set_serial 7 \
  -out "$WORK/bad/sim/cert.pem" 2>/dev/null
sleep 1
expect_error 2 "bad/sim/cert.pem: DDS Security: identity certificate has expired" -- "${host_sim[@]}"
expect_error 2 "security directory not found" -- "$ROBODDS" run "$SCENARIO" --domain "$DOMAIN" --security "$WORK/nowhere" --no-plots --out "$WORK/x"
echo "ok: security files checked at start-up"
