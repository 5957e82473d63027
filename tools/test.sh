#!/usr/bin/env bash
# Builds and runs the whole test suite: C++ (GoogleTest), the Python package
# (pytest, through ctest), then the C++ suite again under AddressSanitizer +
# UndefinedBehaviorSanitizer with clang (build-asan/, which also builds the
# libFuzzer targets), and a short libFuzzer run of each target.
# Installs the Debian dependencies first (tools/setup.sh).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"
bash tools/setup.sh build
ctest --test-dir build --output-on-failure -j"$(nproc)"
echo "== sanitizer build (clang, ASan + UBSan; also the libFuzzer targets) =="
cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMECHKIN_SANITIZE=ON -DMECHKIN_FUZZ=ON -DMECHKIN_BUILD_BENCHMARKS=OFF -DMECHKIN_BUILD_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)"
echo "== short fuzz run (libFuzzer, 20 s per target) =="
bash tools/fuzz.sh 20 build-asan
