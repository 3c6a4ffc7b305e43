#!/usr/bin/env bash
# The Debian package works: `cpack -G DEB` from the build tree gives robodds_<version>_<arch>.deb
# with bin/robodds, every component executable bin/robodds-<type> and share/robodds under /usr,
# Depends on the Fast DDS runtime packages and on openssl (`robodds security init` runs it);
# unpacked into a temporary root (dpkg -x, no install on this machine) its robodds, run outside
# the source tree without ROBODDS_SHARE_DIR, gives the build-tree binary's results byte for
# byte, and a component executable lists its parameters.
# Extra argument: the build directory.
source "$(dirname "$0")/lib.sh"
BUILD="$4"
S="$SRC/sim/scenarios/plant_smoke.yaml"
unset ROBODDS_SHARE_DIR

timeout -k 5 300 cpack -G DEB --config "$BUILD/CPackConfig.cmake" -B "$WORK/pkg" >"$WORK/cpack.log" 2>&1 ||
  fail "cpack failed: $(tail -n 20 "$WORK/cpack.log")"
debs=("$WORK"/pkg/robodds_*.deb)
[[ ${#debs[@]} -eq 1 && -f ${debs[0]} ]] || fail "expected one robodds_*.deb in $WORK/pkg: $(ls "$WORK/pkg")"
DEB="${debs[0]}"
contents="$(dpkg-deb -c "$DEB")"
for f in ./usr/bin/robodds ./usr/share/robodds/deploy/qos/robodds_qos.xml ./usr/share/robodds/sim/report/report.py \
         ./usr/share/robodds/sim/scenarios/plant_smoke.yaml ./usr/share/robodds/components/pf_estimator/config/pf_estimator.params.yaml; do
  grep -qE " $f\$" <<<"$contents" || fail "$(basename "$DEB") lacks $f"
done
types=$("$ROBODDS" components | grep -oE '^[a-z][a-z0-9_]*') || fail "robodds components listed no type"
for t in $types; do
  grep -qE " ./usr/bin/robodds-${t//_/-}\$" <<<"$contents" || fail "$(basename "$DEB") lacks ./usr/bin/robodds-${t//_/-}"
done
if grep -qE "(test|bench)" <<<"$(grep ' ./usr/bin/' <<<"$contents")"; then
  fail "test or benchmark executables in the package: $(grep ' ./usr/bin/' <<<"$contents")"
fi
depends="$(dpkg-deb -f "$DEB" Depends)"
grep -q "libfastrtps" <<<"$depends" || fail "Depends does not name the Fast DDS library package: $depends"
grep -q "libssl" <<<"$depends" || fail "Depends does not name libssl (the security start-up checks link libcrypto): $depends"
grep -qE "(^|, )openssl(,|$)" <<<"$depends" || fail "Depends does not name openssl (robodds security init runs it): $depends"
recommends="$(dpkg-deb -f "$DEB" Recommends)"
grep -qE "(^|, )python3-matplotlib(,|$)" <<<"$recommends" || fail "Recommends does not name python3-matplotlib: $recommends"
! grep -qE "(^|, )openssl(,|$)" <<<"$recommends" || fail "openssl is a Depends, not a Recommends: $recommends"
echo "ok: $(basename "$DEB"): robodds, $(wc -w <<<"$types") component executables, share/robodds; Depends: $depends; Recommends: $recommends"

# Unpacked, not installed: the binaries find /usr/share/robodds next to them (../share/robodds).
dpkg -x "$DEB" "$WORK/root"
"$ROBODDS" --log warn run "$S" --domain "$DOMAIN" --duration 2 --out "$WORK/reference" --no-plots >"$WORK/reference.log" 2>&1 ||
  fail "build-tree run failed: $(cat "$WORK/reference.log")"
mkdir -p "$WORK/elsewhere"
(cd "$WORK/elsewhere" && "$WORK/root/usr/bin/robodds" --log warn run "$WORK/root/usr/share/robodds/sim/scenarios/plant_smoke.yaml" \
  --domain "$DOMAIN" --duration 2 --out out --no-plots) >"$WORK/packaged.log" 2>&1 ||
  fail "packaged robodds failed: $(cat "$WORK/packaged.log")"
same_outputs "$WORK/reference" "$WORK/elsewhere/out"
# The help is read whole first: `grep -q` leaves at its match and, under pipefail, a writer still
# printing (the help passed one pipe buffer with the actuator limits) would fail the line on SIGPIPE.
plant_help="$("$WORK/root/usr/bin/robodds-plant" --help)" || fail "packaged robodds-plant --help failed"
grep -q "command_timeout_s" <<<"$plant_help" || fail "packaged robodds-plant --help lists no parameters"
echo "ok: the packaged robodds gives the build-tree results ($N_CSV CSVs); robodds-plant --help lists its parameters"
