#!/usr/bin/env bash
# Installs mechkin's Debian dependencies (apt-get only when one is missing),
# configures and builds it, and installs the Python package for /usr/bin/python3.
# Usage: tools/setup.sh [--with-tests] [build-dir] [extra cmake args...]
#   default: only what the library, the CLI and the Python package need
#            (tests and benchmarks are not configured);
#   --with-tests: also the test, benchmark, browser and sanitizer toolchain
#            (GoogleTest, Google Benchmark, pytest, Chromium, clang, Simbody, emscripten, ...),
#            and the build includes tests and benchmarks (tools/test.sh uses this).
# Default build dir: build (Release). Runs as root on Debian 12; uses sudo otherwise.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
with_tests=0
if [ "${1:-}" = "--with-tests" ]; then with_tests=1; shift; fi
build="${1:-build}"; shift || true
main_pkgs=(g++ cmake ninja-build libeigen3-dev libceres-dev libsuitesparse-dev nlohmann-json3-dev libcli11-dev libfcl-dev
           libtinyxml2-dev libzip-dev libhdf5-dev
           python3 python3-dev pybind11-dev python3-numpy python3-pandas libjs-three)
test_pkgs=(libgtest-dev libgmock-dev libbenchmark-dev python3-jsonschema python3-pytest python3-pil python3-yaml git
           python3-dask python3-distributed python3-h5py chromium clang libclang-rt-14-dev libsimbody-dev
           emscripten)
# --print-packages main|tests: the list only (tools/install_times.sh times them on a fresh system).
if [ "$with_tests" -eq 0 ] && [ "${build}" = "--print-packages" ]; then
  if [ "${1:-main}" = "tests" ]; then echo "${test_pkgs[@]}"; else echo "${main_pkgs[@]}"; fi
  exit 0
fi
pkgs=("${main_pkgs[@]}")
[ "$with_tests" -eq 1 ] && pkgs+=("${test_pkgs[@]}")
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
if [ "$with_tests" -eq 1 ]; then
  # The live page's WebAssembly module too (emscripten, issue 30): its browser test is
  # part of the suite, so a missing em++ stops the configure instead of skipping it.
  suite=(-DMECHKIN_BUILD_TESTS=ON -DMECHKIN_BUILD_BENCHMARKS=ON -DMECHKIN_LIVE=ON)
else
  # Not the live page's module (a build directory the test command configured keeps
  # the option in its cache otherwise); `tools/setup.sh build -DMECHKIN_LIVE=ON` builds it.
  suite=(-DMECHKIN_BUILD_TESTS=OFF -DMECHKIN_BUILD_BENCHMARKS=OFF -DMECHKIN_LIVE=OFF)
fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${suite[@]}" "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
# The Python package into /usr/bin/python3's site-packages
# (/usr/local/lib/python3.11/dist-packages on Debian 12).
if [ -f "$build/python/mechkin/__init__.py" ]; then
  $SUDO cmake --install "$build" --component python >/dev/null
fi
