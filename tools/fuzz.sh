#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for SECONDS
# (default 30). Crashing inputs are written to build-fuzz/crash-*; the corpus
# is seeded with the bundled mechanisms and the invalid-file corpus.
# Usage: tools/fuzz.sh [SECONDS]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
secs="${1:-30}"
out="$here/build-fuzz"
mkdir -p "$out/corpus-loader" "$out/corpus-expression"
cp "$here"/mechanisms/*.json "$here"/tests/invalid/*.json "$out/corpus-loader/" 2>/dev/null || true
printf '360*t' > "$out/corpus-expression/a"; printf 'sin(2*pi*t)^2/(1+t)' > "$out/corpus-expression/b"
printf 'atan2(t, 1-t) + sqrt(exp(-t))' > "$out/corpus-expression/c"
flags=(-std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -I"$here/src" -I/usr/include/eigen3 -DJSON_DIAGNOSTICS=1)
common=("$here"/src/model/*.cpp "$here"/src/math/*.cpp)
clang++ "${flags[@]}" "$here/tools/fuzz/fuzz_loader.cpp" "${common[@]}" -o "$out/fuzz_loader"
clang++ "${flags[@]}" "$here/tools/fuzz/fuzz_expression.cpp" "${common[@]}" -o "$out/fuzz_expression"
cd "$out"
# A crash makes libFuzzer exit non-zero (and write crash-*): the script then fails.
./fuzz_loader -max_total_time="$secs" -max_len=65536 -print_final_stats=1 corpus-loader > loader.log 2>&1 ||
  { tail -40 loader.log; exit 1; }
grep -E "^Done|stat::number_of_executed_units" loader.log
./fuzz_expression -max_total_time="$secs" -max_len=256 -print_final_stats=1 corpus-expression > expression.log 2>&1 ||
  { tail -40 expression.log; exit 1; }
grep -E "^Done|stat::number_of_executed_units" expression.log
