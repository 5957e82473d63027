#!/bin/sh
# Builds the live page's WebAssembly module (issue 30) with Debian's emscripten:
#   tools/build_live.sh [OUTPUT_DIR]     (default: build/live)
# writes OUTPUT_DIR/mechkin_live.js: one file (the wasm inlined as base64,
# -sSINGLE_FILE=1), a factory MechkinLive() (-sMODULARIZE) that `mechkin view --live`
# inlines into the page. Only the sources the live core needs (the list below), -O2;
# Ceres, FCL, SuiteSparse, HDF5 and threads are left out (src/io/live/live_stubs.cpp
# answers their entry points with a clear error). ccache is used when present.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/build/live}
mkdir -p "$out/obj" "$out/include"
# nlohmann_json (Debian nlohmann-json3-dev) alone: /usr/include itself would shadow emscripten's libc.
ln -sfn /usr/include/nlohmann "$out/include/nlohmann"
# emscripten's JS post-pass needs acorn, Debian's nodejs modules have it.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
command -v em++ >/dev/null || { echo "build_live.sh: em++ not found: install Debian's emscripten (apt-get install emscripten)" >&2; exit 1; }
cxx="em++"
command -v ccache >/dev/null && cxx="ccache em++"
flags="-std=c++17 -O2 -fexceptions -DNDEBUG -DJSON_DIAGNOSTICS=1 -I$root/src -isystem /usr/include/eigen3 -isystem $out/include -Wno-deprecated-declarations"

# The live core: spec → model → constraints → kinematics (Newton) → mobility → the run.
sources="
math/rotation.cpp math/taylor.cpp math/convex_hull.cpp math/small_lu.cpp
$(cd "$root/src" && ls joints/*.cpp spec/*.cpp model/*.cpp constraints/*.cpp mobility/*.cpp)
kinematics/block_solver.cpp kinematics/block_structure.cpp kinematics/newton.cpp kinematics/position.cpp
kinematics/workspace.cpp
analysis/assemble_model.cpp analysis/assembly.cpp analysis/branches.cpp analysis/clearance_columns.cpp
analysis/contact_watch.cpp analysis/error_bounds.cpp analysis/forces.cpp analysis/joint_limits.cpp
analysis/kinematic_analysis.cpp analysis/load.cpp analysis/motion.cpp analysis/orientation.cpp
analysis/quadratic_roots.cpp analysis/reduction.cpp analysis/row_error_estimate.cpp analysis/row_selection.cpp
analysis/run_request.cpp analysis/sensitivity.cpp analysis/singular_points.cpp analysis/singularity.cpp
analysis/step_observer.cpp
io/live/live_api.cpp io/live/live_stubs.cpp io/plot_marks.cpp
"
# Unity batches as in the native build (CMakeLists.txt, MECHKIN_UNITY_BUILD): up to 8
# sources of one folder compiled as one translation unit, which parses the headers
# (Eigen, nlohmann_json, the layers below) once for the batch; the step's own layers
# (math, constraints, kinematics) one source per unit, as natively. 39 units instead of
# 96: the module took 6.6 min of CI's Release build beside the native compiles
# (2026-12-06). A batch file is rewritten only when its list changes.
mkdir -p "$out/unity"
batches=""
batch_of() {  # batch_of FOLDER SOURCES...: writes FOLDER's batch files, adds them to $batches
  folder=$1; shift
  k=0; n=0; list=""
  flush() {
    [ -z "$list" ] && return 0
    f="$out/unity/${folder}_$k.cpp"
    printf '%s' "$list" > "$f.new"
    if cmp -s "$f.new" "$f"; then rm "$f.new"; else mv "$f.new" "$f"; fi
    batches="$batches $f"
    k=$((k + 1)); n=0; list=""
  }
  for s in "$@"; do
    list="$list#include \"$root/src/$s\"
"
    n=$((n + 1))
    [ "$n" -eq 8 ] && flush
  done
  flush
}
singles=""
for folder in joints spec model mobility analysis io; do
  # shellcheck disable=SC2046
  batch_of "$folder" $(for s in $sources; do case "$s" in "$folder"/*) echo "$s";; esac; done)
done
for s in $sources; do
  case "$s" in math/*|constraints/*|kinematics/*) singles="$singles $root/src/$s";; esac
done
objects=""
pairs=""  # unit and its object, one pair a line
for u in $batches $singles; do
  o="$out/obj/$(basename "$(dirname "$u")")_$(basename "$u" .cpp).o"
  objects="$objects $o"
  pairs="$pairs$u $o
"
done
# Two compiles at a time (the machines have two cores); make-like: a unit is compiled
# again when it, a source a batch includes or any header is newer than its object.
printf '%s' "$pairs" | xargs -P 2 -n 2 sh -c 'stale=0; [ -f "$2" ] && [ ! "$1" -nt "$2" ] || stale=1
  for s in $(sed -n "s/^#include \"\(.*\)\"$/\1/p" "$1"); do [ "$s" -nt "$2" ] && stale=1; done
  [ -n "$(find '"$root"'/src -name "*.hpp" -newer "$2" 2>/dev/null | head -1)" ] && stale=1
  if [ "$stale" -eq 1 ]; then '"$cxx $flags"' -c "$1" -o "$2" || exit 255; fi' sh
exports='_mk_live_load,_mk_live_set,_mk_live_clear,_mk_live_run,_mk_live_rows,_mk_live_cols,_mk_live_columns,_mk_live_status,_mk_live_error,_mk_live_mobility,_malloc,_free'
em++ -O2 -fexceptions $objects -o "$out/mechkin_live.js" \
  -sMODULARIZE=1 -sEXPORT_NAME=MechkinLive -sSINGLE_FILE=1 -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web,node \
  -sEXPORTED_FUNCTIONS="[$exports]" -sEXPORTED_RUNTIME_METHODS='[ccall,cwrap,UTF8ToString,stringToUTF8,lengthBytesUTF8]' \
  -sERROR_ON_UNDEFINED_SYMBOLS=1
echo "build_live.sh: $out/mechkin_live.js ($(wc -c < "$out/mechkin_live.js") bytes)"
