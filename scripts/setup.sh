#!/usr/bin/env bash
# Installs the Debian 12 packages robodds needs (only the missing ones). Run as root.
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build pkg-config python3
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  libeigen3-dev libceres-dev libyaml-cpp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libssl-dev openssl
  libzstd-dev liblz4-dev  # MCAP chunk compression (runtime/mcap/)
  libwebsocketpp-dev libasio-dev nlohmann-json3-dev  # robodds bridge: WebSocket server on standalone asio, JSON (tools/bridge/)
  iproute2 tcpdump procps bc docker-compose python3-matplotlib python3-yaml file time
  stress-ng  # CPU hogs beside real-time runs (docs/deployment.md, Real-time priority)
  cyclonedds-dev cyclonedds-tools libcycloneddsidl0
  slurmctld slurmd slurm-client munge  # integration.slurm_sweep: a one-node cluster runs an emitted sweep (docs/scale.md)
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Node.js for the official MCAP and Foxglove readers the tests use (tests/npm/, scripts/npm_setup.sh):
# Debian's nodejs and npm, each only when its command is missing (a nodesource nodejs bundles npm,
# and Debian's npm package would conflict with it).
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi
