#!/usr/bin/env bash
# The project's two entry points (see README.md):
#   tools/dev.sh demo   install what is missing, build Release, run the main job on the
#                       bundled default scene, outputs under out/
#   tools/dev.sh test   install what is missing, build Release, run every test (ctest)
# Both are idempotent: packages already installed are not touched, the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

# Debian 12 package names (build tools and every library the CMake project finds).
PACKAGES=(
  ca-certificates cmake ninja-build g++ pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libepoxy-dev libpng-dev libglm-dev libgl1-mesa-dri libegl-mesa0
)

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "== installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

BUILD_DIR=${SHADOWCERT_BUILD_DIR:-build}
JOBS=${SHADOWCERT_JOBS:-$(nproc)}

build() {
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j "$JOBS"
}

demo() {
  mkdir -p out
  local scene=data/scenes/default.json
  echo "== shadowcert inspect $scene"
  "$BUILD_DIR/cli/shadowcert" inspect "$scene" --json out/inspect.json
  echo "== shadowcert certify $scene"
  "$BUILD_DIR/cli/shadowcert" certify "$scene" --method all --json out/certify.json --volume-out out/volume.off
  echo "== shadowcert render $scene --method cpu"
  "$BUILD_DIR/cli/shadowcert" render "$scene" --method cpu --out out/render.png --counts out/counts.png \
    --mask out/mask.png --json out/render.json
  echo "== outputs under out/: inspect.json certify.json volume_<method>.off render.png counts.png mask.png render.json"
}

case "${1:-}" in
  demo) install_missing; build; demo ;;
  test) install_missing; build; ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$JOBS" ;;
  *) echo "usage: tools/dev.sh demo|test" >&2; exit 2 ;;
esac
