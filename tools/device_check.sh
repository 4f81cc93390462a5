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
set -uo pipefail
cd "$(dirname "$0")/.."

[ $# -eq 1 ] || { echo "usage: tools/device_check.sh DIR" >&2; exit 2; }
OUT_DIR=$(mkdir -p "$1" && cd "$1" && pwd) || { echo "tools/device_check.sh: cannot create $1" >&2; exit 2; }
BUILD=${SHADOWCERT_DEVICE_BUILD_DIR:-build-device}
JOBS=${SHADOWCERT_JOBS:-$(nproc)}
TRIANGLES=${SHADOWCERT_DEVICE_TRIANGLES:-1000000,2000000,4000000}
RESOLUTION=${SHADOWCERT_DEVICE_RESOLUTION:-1920x1080}
export SHADOWCERT_REQUIRE_GL=1

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

step build 210 "$OUT_DIR/build.log" bash -c "
  cmake -S . -B '$BUILD' -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHADOWCERT_BUILD_BENCH=ON &&
  cmake --build '$BUILD' -j '$JOBS' --target shadowcert render_bench &&
  cmake --build '$BUILD' -j '$JOBS'" || { echo "build failed: $OUT_DIR/build.log" >&2; exit 1; }

# The renderer the GL tests and the benches see, as `shadowcert render` reports it.
"$BUILD/cli/shadowcert" render data/scenes/default.json --size 64x48 --method cpu --json "$OUT_DIR/renderer.json" \
  >/dev/null 2>&1 && python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print('renderer:', d.get('renderer')); print('device:', d.get('device'))" \
  "$OUT_DIR/renderer.json" >>"$OUT_DIR/environment.txt" 2>&1

step gl_tests 90 "$OUT_DIR/gl_tests.log" ctest --test-dir "$BUILD" -L gl --output-on-failure -j "$JOBS"
step render_bench 120 "$OUT_DIR/render_bench.txt" "$BUILD/bench/render_bench" --triangles="$TRIANGLES" \
  --resolution="$RESOLUTION" --benchmark_counters_tabular=true \
  --benchmark_out="$OUT_DIR/render_bench.json" --benchmark_out_format=json
step bench_default 60 "$OUT_DIR/bench.log" "$BUILD/cli/shadowcert" bench --suite default --out "$OUT_DIR/bench"

echo "== results under $OUT_DIR (summary.txt)"
cat "$OUT_DIR/environment.txt"
exit "$failed"
