#!/usr/bin/env bash
# tools/device_bundle.sh DIR: the programs of an existing Release build (build/, or
# $SHADOWCERT_BUILD_DIR) and the shared libraries they need that a bare GPU machine lacks, in DIR
# (default .device-bundle/), for tools/device_check.sh with SHADOWCERT_DEVICE_PREBUILT=DIR on a
# machine that cannot install Debian's packages (docs/gpu.md#nvidia-figures).
#
#   DIR/bin/   shadowcert, render_bench and the GL test programs (tests/*_test that render)
#   DIR/lib/   libepoxy, libpng, libgmp, libmpfr, libtbb, libfmt, OpenMesh, and GLVND's libEGL,
#              libOpenGL and libGLdispatch (the GPU's driver brings its own EGL vendor library)
#
# The test programs name the source tree by its absolute path here (their data files):
# device_check.sh links that path to the tree it runs in.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-.device-bundle}
BUILD=${SHADOWCERT_BUILD_DIR:-build}
# The GL tests the device check runs: each GL method against the exact image, the shadow maps
# (their cube maps), the GPU-built volumes, the real meshes at 1024x768 and the GL campaign's kept
# reproducers.
TESTS=(shadow_method_renderer_test shadow_map_renderer_test per_triangle_volume_test compute_volume_test
       stencil_shadow_renderer_test hard_case_render_test scene_comparison_test gl_campaign_test regressions_test)
cmake --build "$BUILD" --target shadowcert render_bench "${TESTS[@]}"
rm -rf "$OUT"
mkdir -p "$OUT/bin" "$OUT/lib"
cp "$BUILD/cli/shadowcert" "$BUILD/bench/render_bench" "$OUT/bin/"
for t in "${TESTS[@]}"; do cp "$BUILD/tests/$t" "$OUT/bin/"; done
# Every library the programs load but the C/C++ runtime (the machine's own libc, libm,
# libstdc++ and libgcc are newer than Debian 12's and must be the ones used).
for lib in $(ldd "$OUT"/bin/* | awk '/=> \//{print $3}' | sort -u); do
  case "$(basename "$lib")" in
    libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libstdc++.so.*|libgcc_s.so.*|ld-linux*) ;;
    *) cp -L "$lib" "$OUT/lib/" ;;
  esac
done
# Loaded at run time, so ldd does not list it: libepoxy opens GLVND's libOpenGL for the GL entry
# points (it fails without "libGL.so.1 or libOpenGL.so.0").
cp -L /usr/lib/x86_64-linux-gnu/libOpenGL.so.0 "$OUT/lib/"
echo "$(git rev-parse HEAD)$(git diff --quiet || echo ' (dirty)') $(pwd)" >"$OUT/source.txt"
du -sh "$OUT"
