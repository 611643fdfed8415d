#!/usr/bin/env bash
# Installs every Debian 12 package that avalanche-hazard needs to build, run and test.
# Idempotent: packages already present are left alone. Run as root (or with sudo).
set -euo pipefail
PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libgdal-dev gdal-bin libproj-dev proj-bin
  libeigen3-dev libhdf5-dev hdf5-tools libdeflate-dev libssl-dev
  libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libspdlog-dev nlohmann-json3-dev libtomlplusplus-dev
  openmpi-bin libopenmpi-dev          # batch across machines (mpirun)
  clang libclang-rt-14-dev            # sanitizers and the libFuzzer harnesses
  chromium                            # headless rendering test of the HTML report
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all packages present"
fi
