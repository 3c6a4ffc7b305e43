#!/usr/bin/env bash
# Makes the DDS Security files of `latency_bench runtime ... --security DIR` (docs/security.md,
# "Cost"): `robodds security init` of plant_smoke (CA, signed governance: every topic encrypted)
# and DIR/bench/, the `tools` identity's certificate and key with permissions that allow
# publishing and subscribing to bench/ping and bench/pong only, signed by the CA with openssl.
#
#   bench/security_dir.sh ROBODDS DIR
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ROBODDS=${1:?usage: bench/security_dir.sh ROBODDS DIR}
DIR=${2:?usage: bench/security_dir.sh ROBODDS DIR}
mkdir -p "$DIR"
"$ROBODDS" security init "$ROOT/sim/scenarios/plant_smoke.yaml" --out "$DIR" >"$DIR/init.log" 2>&1 ||
  { cat "$DIR/init.log" >&2; exit 1; }
mkdir -p "$DIR/bench"
cp -p "$DIR/tools/identity_ca.pem" "$DIR/tools/cert.pem" "$DIR/tools/key.pem" "$DIR/tools/governance.p7s" "$DIR/bench/"
python3 - "$DIR/tools/permissions.xml" "$DIR/bench/permissions.xml" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
topics = "".join("            <topic>%s</topic>\n" % t for t in ("bench/ping", "bench/pong"))
rule = ("      <allow_rule>\n        <domains><id_range><min>0</min><max>232</max></id_range></domains>\n"
        "        <publish>\n          <topics>\n" + topics + "          </topics>\n        </publish>\n"
        "        <subscribe>\n          <topics>\n" + topics + "          </topics>\n        </subscribe>\n"
        "      </allow_rule>\n")
new, n = re.subn(r"      <allow_rule>.*</allow_rule>\n", lambda _: rule, text, flags=re.S)
if n != 1:
    sys.exit("no allow_rule in " + sys.argv[1])
open(sys.argv[2], "w").write(new)
PY
openssl smime -sign -in "$DIR/bench/permissions.xml" -text -out "$DIR/bench/permissions.p7s" \
  -signer "$DIR/ca/ca_cert.pem" -inkey "$DIR/ca/ca_key.pem" 2>"$DIR/init.log" || { cat "$DIR/init.log" >&2; exit 1; }
echo "$DIR/bench"
