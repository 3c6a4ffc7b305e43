#!/usr/bin/env bash
# Deployment inputs that must fail at start-up with one line naming the file and element:
# a discovery-server client profile with a malformed locator, a QoS file that does not exist
# given to a host (flag or environment, as compose files pass it). No network namespaces.
source "$(dirname "$0")/lib.sh"
S="$SRC/sim/scenarios/plant_smoke.yaml"
QOS="$SRC/deploy/qos/robodds_qos.xml"
H=("$ROBODDS" host --scenario "$S" --group sim --domain "$DOMAIN" --start-timeout 2)
DS=(--participant-profile robodds.participant.discovery_client)
ds_client_with() {  # ds_client_with NAME SED-EXPR: a copy of discovery_client.xml edited by sed
  sed "$2" "$SRC/deploy/qos/discovery_client.xml" >"$WORK/$1.xml"
  cmp -s "$SRC/deploy/qos/discovery_client.xml" "$WORK/$1.xml" && fail "sed '$2' changed nothing"
  echo "$WORK/$1.xml"
}

# Malformed server locators: rejected by Fast DDS's parser (address) or by the runtime's check
# (values the 2.9 parser accepts but that can never reach a server).
f="$(ds_client_with bad_ip 's#<address>127.0.0.1</address>#<address>10.0.0.999</address>#')"
expect_error 2 "bad_ip\.xml: rejected by Fast DDS .*'10\.0\.0\.999'.*Name: address" -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with no_ip 's#<address>127.0.0.1</address>#<address></address>#')"
expect_error 2 "no_ip\.xml: rejected by Fast DDS .*<address>" -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with bad_port_text 's#<port>11811</port>#<port>eleven</port>#')"
expect_error 2 "bad_port_text\.xml: rejected by Fast DDS .*<port>" -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with big_port 's#<port>11811</port>#<port>99999</port>#')"
expect_error 2 "big_port\.xml: participant profile 'robodds\.participant\.discovery_client': discoveryServersList: RemoteServer 44\.53\.00\.5f\.45\.50\.52\.4f\.53\.49\.4d\.41: locator 127\.0\.0\.1: port 99999 is not a valid port" \
  -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with zero_port 's#<port>11811</port>#<port>0</port>#')"
expect_error 2 "zero_port\.xml: .*RemoteServer .*: port 0 is not a valid port" -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with any_ip 's#<address>127.0.0.1</address>#<address>0.0.0.0</address>#')"
expect_error 2 "any_ip\.xml: .*RemoteServer .*locator 0\.0\.0\.0:11811: address 0\.0\.0\.0 is not a server address" \
  -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
f="$(ds_client_with bad_prefix 's#prefix="44.53.00.5f.45.50.52.4f.53.49.4d.41"#prefix="44.53.00.5f"#')"
expect_error 2 "bad_prefix\.xml: rejected by Fast DDS .*invalid server's guidPrefix" -- "${H[@]}" "${DS[@]}" --qos "$QOS" --qos "$f"
# The same check protects `robodds topics` (it builds its own participant).
f="$(ds_client_with big_port2 's#<port>11811</port>#<port>70000</port>#')"
expect_error 2 "big_port2\.xml: .*port 70000 is not a valid port" -- \
  "$ROBODDS" topics --duration 0.1 --domain "$DOMAIN" "${DS[@]}" --qos "$QOS" --qos "$f"

# A host given a QoS file that does not exist: by flag, and by $ROBODDS_QOS_FILE.
expect_error 2 "$WORK/missing\.xml: QoS profile file not found" -- "${H[@]}" --qos "$WORK/missing.xml"
expect_error 2 "$WORK/missing_ds\.xml: QoS profile file not found" -- "${H[@]}" --qos "$QOS" --qos "$WORK/missing_ds.xml"
expect_error 2 "$WORK/from_env\.xml: QoS profile file not found" -- env ROBODDS_QOS_FILE="$WORK/from_env.xml" "${H[@]}"
echo "ok: every malformed deployment input rejected with one line naming file and element"
