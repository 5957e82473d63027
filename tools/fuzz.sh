#!/usr/bin/env bash
# Builds the libFuzzer targets from CMake (clang, ASan + UBSan, MECHKIN_FUZZ=ON)
# and runs each for SECONDS (default 30). Crashing inputs are written to
# build-fuzz/crash-*; the corpora are seeded with the bundled mechanisms and the
# invalid-file corpus. A crash makes libFuzzer exit non-zero: the script fails.
# Usage: tools/fuzz.sh [SECONDS] [BUILD_DIR]
# BUILD_DIR: an existing clang build configured with -DMECHKIN_FUZZ=ON (tools/test.sh
# passes its sanitizer build, so the library is compiled once for both).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
secs="${1:-30}"
out="${2:-$here/build-fuzz}"
case "$out" in /*) ;; *) out="$here/$out" ;; esac
if [ -z "${2:-}" ]; then
  cmake -S "$here" -B "$out" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DMECHKIN_FUZZ=ON -DMECHKIN_SANITIZE=ON -DMECHKIN_BUILD_TESTS=OFF -DMECHKIN_BUILD_BENCHMARKS=OFF \
    -DMECHKIN_BUILD_PYTHON=OFF >/dev/null
fi
cmake --build "$out" -j"$(nproc)" --target fuzz_loader fuzz_expression fuzz_check >/dev/null
mkdir -p "$out/corpus-loader" "$out/corpus-check" "$out/corpus-expression"
cp "$here"/mechanisms/*.json "$here"/tests/invalid/*.json "$out/corpus-loader/" 2>/dev/null || true
cp "$here"/mechanisms/*.json "$here"/tests/invalid/*.json "$out/corpus-check/" 2>/dev/null || true
printf '360*t' > "$out/corpus-expression/a"; printf 'sin(2*pi*t)^2/(1+t)' > "$out/corpus-expression/b"
printf 'atan2(t, 1-t) + sqrt(exp(-t))' > "$out/corpus-expression/c"
cd "$out"
run() {  # target corpus max_len
  ./tools/fuzz/"$1" -max_total_time="$secs" -max_len="$3" -timeout=20 -print_final_stats=1 "$2" > "$1.log" 2>&1 ||
    { tail -40 "$1.log"; exit 1; }
  echo "$1: $(grep -E 'stat::number_of_executed_units' "$1.log" | awk '{print $2}') executions, no crash"
}
run fuzz_loader corpus-loader 65536
run fuzz_check corpus-check 65536
run fuzz_expression corpus-expression 4096
