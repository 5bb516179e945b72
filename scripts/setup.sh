#!/usr/bin/env bash
# Idempotent install of every Debian 12 package wavebake needs (README.md says
# why each is here). Runs apt-get only when something is missing.
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config git
  libabsl-dev libzstd-dev nlohmann-json3-dev libembree-dev libassimp-dev
  libopenexr-dev libstb-dev libcli11-dev libspdlog-dev libsqlite3-dev
  libprotobuf-dev protobuf-compiler libgrpc++-dev protobuf-compiler-grpc libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  clang-14 libclang-rt-14-dev clang
  python3-zarr python3-numpy python3-matplotlib python3-grpcio python3-grpc-tools
  slurmctld slurmd slurm-client munge python3-kubernetes iproute2
  libcpp-httplib-dev pybind11-dev python3-dev python3-pytest
  python3-venv python3-pip python3-setuptools python3-wheel mypy
  chromium chromium-driver python3-selenium python3-prometheus-client glslang-tools prometheus
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  # munge and the Slurm daemons are started by the tests that need them, with
  # their own configuration: keep the packages from starting system services.
  if [ ! -e /usr/sbin/policy-rc.d ]; then
    printf '#!/bin/sh\nexit 101\n' | $SUDO tee /usr/sbin/policy-rc.d >/dev/null
    $SUDO chmod 755 /usr/sbin/policy-rc.d
    trap '$SUDO rm -f /usr/sbin/policy-rc.d' EXIT
  fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
