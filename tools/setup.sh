#!/usr/bin/env bash
# Installs mechkin's Debian dependencies (apt-get only when one is missing),
# configures and builds it, and installs the Python package for /usr/bin/python3.
# Usage: tools/setup.sh [build-dir] [extra cmake args...]
# Default build dir: build (Release). Runs as root on Debian 12; uses sudo otherwise.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"; shift || true
pkgs=(g++ cmake ninja-build libeigen3-dev libceres-dev libsuitesparse-dev nlohmann-json3-dev libcli11-dev
      libgtest-dev libgmock-dev libbenchmark-dev python3 python3-dev python3-jsonschema
      pybind11-dev python3-numpy python3-pandas python3-pytest python3-pil python3-dask python3-distributed libjs-three chromium
      clang libclang-rt-14-dev valgrind libsimbody-dev)
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
cd "$here"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
# The Python package into /usr/bin/python3's site-packages
# (/usr/local/lib/python3.11/dist-packages on Debian 12).
if [ -f "$build/python/mechkin/__init__.py" ]; then
  $SUDO cmake --install "$build" --component python >/dev/null
fi
