#!/usr/bin/env bash
# Installs every Debian package burst needs, only when something is missing.
# Usage: scripts/install-deps.sh   (as root, or with sudo available)
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  petsc-dev libpetsc-real3.18-dev
  openmpi-bin libopenmpi-dev
  libhdf5-openmpi-dev
  libeigen3-dev
  libsundials-dev
  libgtest-dev libbenchmark-dev
  python3 python3-numpy python3-matplotlib python3-h5py
  python3-paraview # pvpython for tests/check_paraview.py
  clang-format     # tests/check_format.py
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
