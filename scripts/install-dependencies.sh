#!/usr/bin/env bash
# Installs the Debian packages Hex_meshing_3 needs to build, test, run its tools and benchmarks.
# Idempotent: packages already present are skipped by apt. Run as root (or through sudo).
set -euo pipefail

packages=(
  cmake g++ make ccache pkg-config
  libcgal-dev libeigen3-dev libboost-dev libboost-iostreams-dev zlib1g-dev
  libgmp-dev libmpfr-dev libtbb-dev
  libcli11-dev nlohmann-json3-dev
  libtet1.5-dev
  openfoam
  doxygen
  python3-meshio python3-numpy
  clang libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "install-dependencies: installing ${missing[*]}"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-dependencies: done"
