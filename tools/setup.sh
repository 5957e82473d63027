#!/usr/bin/env bash
# Installs mechkin's Debian dependencies (idempotent) and configures + builds it.
# Usage: tools/setup.sh [build-dir] [extra cmake args...]
# Default build dir: build (Release). Runs as root on Debian 12; uses sudo otherwise.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"; shift || true
pkgs=(g++ cmake make libeigen3-dev libceres-dev nlohmann-json3-dev libcli11-dev
      libgtest-dev libgmock-dev libbenchmark-dev python3 python3-jsonschema
      clang libclang-rt-14-dev valgrind)
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${pkgs[@]}" >/dev/null
cd "$here"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
