#!/usr/bin/env bash
# tools/device_check.sh DIR: the GPU check of docs/gpu.md, one script, every result under DIR.
#
# On a machine with an NVIDIA GPU (EGL_EXT_platform_device; the code picks the hardware device
# over llvmpipe by itself): builds Release in build-device/ (no benchmarks but render_bench, no
# sanitizers), runs the GL test label, bench/render_bench at 1920x1080 up to 4M triangles and
# `shadowcert bench --suite default`, and writes
#   DIR/environment.txt     GPU, driver, GL renderer, commit, date, nproc
#   DIR/build.log           the configure and build
#   DIR/gl_tests.log        ctest -L gl (SHADOWCERT_REQUIRE_GL=1: a missing GL is a failure)
#   DIR/render_bench.json   Google Benchmark JSON (+ .txt, the console table)
#   DIR/bench/              shadowcert bench's outputs (bench.json, .csv, .md, plots, report.html)
#   DIR/summary.txt         one line per step: its exit code and seconds
# Target: under 8 minutes on a 16-core machine. Each step has its own time limit (below), so a
# slow step cannot eat the others' time; a step that fails or times out is recorded in
# summary.txt and the script goes on, exiting 1 at the end if any step failed.
#
# Environment: SHADOWCERT_DEVICE_TRIANGLES (render_bench's list, default 1M,2M,4M),
# SHADOWCERT_DEVICE_RESOLUTION (default 1920x1080), SHADOWCERT_DEVICE_BUILD_DIR (build-device),
# SHADOWCERT_JOBS (nproc). On llvmpipe the same script runs (use a small triangle list there:
# a 4M-triangle frame takes minutes in software).
#
# SHADOWCERT_DEVICE_STEPS: the steps to run, comma-separated (default all: gl_tests,
# render_bench, lamp_in_room, real_meshes, bench_default; on demand: lamp_diag), to fit a
# short device lease.
#
# SHADOWCERT_DEVICE_PREBUILT=BUNDLE: no build; the programs and libraries tools/device_bundle.sh
# put in BUNDLE (for a GPU machine that cannot install Debian's packages). The GL tests are then
# the bundle's test programs, run one by one (gtest JSON in DIR/gtest/), and the source tree's
# path they were built with is linked to this tree.
#
# Besides the tests and render_bench, the GPU paths of wave 3 each get a step: the cube-map
# shadow maps (a lamp at the very centre of a room: every method of render against the exact
# image) and the real meshes at 1920x1080 (the robust methods: 0 hard errors on the GPU too).
set -uo pipefail
cd "$(dirname "$0")/.."

[ $# -eq 1 ] || { echo "usage: tools/device_check.sh DIR" >&2; exit 2; }
OUT_DIR=$(mkdir -p "$1" && cd "$1" && pwd) || { echo "tools/device_check.sh: cannot create $1" >&2; exit 2; }
BUILD=${SHADOWCERT_DEVICE_BUILD_DIR:-build-device}
JOBS=${SHADOWCERT_JOBS:-$(nproc)}
TRIANGLES=${SHADOWCERT_DEVICE_TRIANGLES:-1000000,2000000,4000000}
RESOLUTION=${SHADOWCERT_DEVICE_RESOLUTION:-1920x1080}
export SHADOWCERT_REQUIRE_GL=1

STEPS=${SHADOWCERT_DEVICE_STEPS:-gl_tests,render_bench,lamp_in_room,real_meshes,bench_default}
# want STEP: whether STEP is among SHADOWCERT_DEVICE_STEPS.
want() { case ",$STEPS," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }

failed=0
: >"$OUT_DIR/summary.txt"
# step NAME LIMIT_SECONDS LOG COMMAND...: runs COMMAND under `timeout`, its output to LOG.
step() {
  local name=$1 limit=$2 log=$3
  shift 3
  local start=$SECONDS
  echo "== $name (at most $limit s; log: $log)"
  timeout --kill-after=10 "$limit" "$@" >"$log" 2>&1
  local rc=$?
  local line
  line=$(printf '%-14s exit %3d  %4d s' "$name" "$rc" $((SECONDS - start)))
  [ "$rc" -eq 124 ] && line+="  (timed out)"
  echo "$line" | tee -a "$OUT_DIR/summary.txt"
  [ "$rc" -eq 0 ] || failed=1
  return "$rc"
}

{
  echo "date: $(date -u +%FT%TZ)"
  echo "commit: $(git rev-parse HEAD 2>/dev/null || echo none)$(git diff --quiet 2>/dev/null || echo ' (dirty)')"
  echo "nproc: $(nproc)"
  command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
} >"$OUT_DIR/environment.txt" 2>&1

PREBUILT=${SHADOWCERT_DEVICE_PREBUILT:-}
if [ -n "$PREBUILT" ]; then
  PREBUILT=$(cd "$PREBUILT" && pwd)
  export LD_LIBRARY_PATH="$PREBUILT/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  # GLVND finds the NVIDIA EGL vendor library where the driver's container layout puts it.
  for vendor in /usr/share/glvnd/egl_vendor.d/10_nvidia.json /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json; do
    [ -f "$vendor" ] && { export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor; break; }
  done
  built_in=$(awk '{print $NF}' "$PREBUILT/source.txt")
  if [ "$built_in" != "$(pwd)" ]; then mkdir -p "$(dirname "$built_in")" && ln -sfn "$(pwd)" "$built_in"; fi
  SHADOWCERT="$PREBUILT/bin/shadowcert"
  RENDER_BENCH="$PREBUILT/bin/render_bench"
  echo "prebuilt: $(cat "$PREBUILT/source.txt")" >>"$OUT_DIR/environment.txt"
else
  step build 210 "$OUT_DIR/build.log" bash -c "
    cmake -S . -B '$BUILD' -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHADOWCERT_BUILD_BENCH=ON &&
    cmake --build '$BUILD' -j '$JOBS' --target shadowcert render_bench &&
    cmake --build '$BUILD' -j '$JOBS'" || { echo "build failed: $OUT_DIR/build.log" >&2; exit 1; }
  SHADOWCERT="$BUILD/cli/shadowcert"
  RENDER_BENCH="$BUILD/bench/render_bench"
fi

# The renderer the GL tests and the benches see, as `shadowcert render` reports it.
"$SHADOWCERT" render data/scenes/default.json --size 64x48 --method cpu --json "$OUT_DIR/renderer.json" \
  >/dev/null 2>&1 && python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print('renderer:', d.get('renderer')); print('device:', d.get('device'))" \
  "$OUT_DIR/renderer.json" >>"$OUT_DIR/environment.txt" 2>&1

if ! want gl_tests; then
  :
elif [ -n "$PREBUILT" ]; then
  mkdir -p "$OUT_DIR/gtest"
  step gl_tests 300 "$OUT_DIR/gl_tests.log" bash -c '
    failed=0
    for t in "$1"/bin/*_test; do
      name=$(basename "$t")
      echo "== $name"
      "$t" --gtest_brief=1 --gtest_output="json:$2/gtest/$name.json" || failed=1
    done
    exit $failed' _ "$PREBUILT" "$OUT_DIR"
else
  step gl_tests 90 "$OUT_DIR/gl_tests.log" ctest --test-dir "$BUILD" -L gl --output-on-failure -j "$JOBS"
fi
want render_bench && step render_bench 120 "$OUT_DIR/render_bench.txt" "$RENDER_BENCH" --triangles="$TRIANGLES" \
  --resolution="$RESOLUTION" --benchmark_counters_tabular=true \
  --benchmark_out="$OUT_DIR/render_bench.json" --benchmark_out_format=json
# The cube-map shadow maps: a point light at the exact centre of a room's bounds, every method.
want lamp_in_room && step lamp_in_room 60 "$OUT_DIR/lamp_in_room.log" "$SHADOWCERT" diff data/scenes/lamp_in_room.json --size "$RESOLUTION" \
  --methods all,pcf,pcss,smoothie --json "$OUT_DIR/lamp_in_room.json"
# Where lamp_in_room fails on NVIDIA (docs/gpu.md#nvidia-figures: 155,677 hard errors for every
# volume method on an H200, 0 on llvmpipe): cpu's overlay and masks at full size under z-fail and
# z-pass, and at the scene's own 320x240, to see which surfaces and which part of the volume.
want lamp_diag && step lamp_diag 120 "$OUT_DIR/lamp_diag.log" bash -c '
  for mode in zfail zpass; do
    "$1" diff data/scenes/lamp_in_room.json --size "$2" --methods cpu --stencil "$mode" \
      --out "$3/lamp_diag_$mode" --json "$3/lamp_diag_$mode.json"
  done
  "$1" diff data/scenes/lamp_in_room.json --methods cpu,pertri --out "$3/lamp_diag_320x240" \
    --json "$3/lamp_diag_320x240.json"
  exit 0' _ "$SHADOWCERT" "$RESOLUTION" "$OUT_DIR"
# The bundled real meshes at full size: the robust methods must show 0 hard errors on the GPU too.
want real_meshes && step real_meshes 120 "$OUT_DIR/real_meshes.log" bash -c '
  failed=0
  for m in data/meshes/*/*.*; do
    case "$m" in *.md|*.txt) continue ;; esac
    echo "== $m"
    "$1" diff "$m" --size "$2" --methods cpu,cs,gs,ts,pertri --json "$3/real_$(basename "$m").json" || failed=1
  done
  exit $failed' _ "$SHADOWCERT" "$RESOLUTION" "$OUT_DIR"
want bench_default && step bench_default 60 "$OUT_DIR/bench.log" "$SHADOWCERT" bench --suite default --out "$OUT_DIR/bench"

echo "== results under $OUT_DIR (summary.txt)"
cat "$OUT_DIR/environment.txt"
exit "$failed"
