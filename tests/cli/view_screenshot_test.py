#!/usr/bin/env python3
"""`shadowcert view` under Xvfb (cli/view_command.cpp, docs/engine-integration.md#shadowcert-view):
the window's screenshot of every robust volume method on bundled scenes must equal
`shadowcert render --out` of the same scene and size pixel for pixel (0 differing pixels); an
unknown method and a missing display exit 2 with a clear message.

Usage: view_screenshot_test.py SHADOWCERT SOURCE_DIR WORK_DIR
Needs xvfb-run (Debian's xvfb); without it the test says so and skips (exit 77), unless
SHADOWCERT_REQUIRE_GL=1, which turns that into a failure."""
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib

ROBUST_VOLUME_METHODS = ["cpu", "cs", "gs", "ts", "pertri"]  # pipeline/method_registry.h's robust ones that draw a volume
SCENES = ["default.json", "sphere_over_floor.json", "closed_casters.json"]
SIZE = "160x120"


def read_png(path):
    """(width, height, rows of RGBA bytes) of an 8-bit RGBA, non-interlaced PNG (gpu/png_image.h writes those)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path + ": not a PNG"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 6 and interlace == 0, path + ": not 8-bit RGBA"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, prev = zlib.decompress(idat), 4 * width, [], bytearray(4 * width)
    for r in range(height):
        f, line = raw[r * (stride + 1)], bytearray(raw[r * (stride + 1) + 1:(r + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 4] if i >= 4 else 0
            b = prev[i]
            c = prev[i - 4] if i >= 4 else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, rows


def differing_pixels(a, b):
    assert a[:2] == b[:2], "sizes differ: %s vs %s" % (a[:2], b[:2])
    n = 0
    for ra, rb in zip(a[2], b[2]):
        for x in range(0, len(ra), 4):
            n += ra[x:x + 4] != rb[x:x + 4]
    return n


def main():
    shadowcert, source, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    required = os.environ.get("SHADOWCERT_REQUIRE_GL") == "1"
    if shutil.which("xvfb-run") is None:
        print("xvfb-run not found (Debian's xvfb)")
        return 1 if required else 77
    failures = 0
    for scene in SCENES:
        path = os.path.join(source, "data", "scenes", scene)
        for method in ROBUST_VOLUME_METHODS:
            shot = os.path.join(work, "view_%s_%s.png" % (scene, method))
            out = os.path.join(work, "render_%s_%s.png" % (scene, method))
            v = subprocess.run(["xvfb-run", "-a", shadowcert, "view", path, "--method", method, "--size", SIZE,
                                "--screenshot", shot, "--frames", "3"], capture_output=True, text=True, timeout=600)
            r = subprocess.run([shadowcert, "render", path, "--method", method, "--size", SIZE, "--out", out],
                               capture_output=True, text=True, timeout=600)
            if v.returncode != 0 or r.returncode != 0:
                print("FAILED %s %s: view exit %d (%s), render exit %d (%s)" % (
                    scene, method, v.returncode, v.stderr.strip(), r.returncode, r.stderr.strip()))
                failures += 1
                continue
            n = differing_pixels(read_png(shot), read_png(out))
            print("%s %s %s: %d differing pixels" % ("ok" if n == 0 else "FAILED", scene, method, n))
            failures += n != 0
    default = os.path.join(source, "data", "scenes", "default.json")
    # The overlay: no hard error (red) on a robust method; the pixels it marks ambiguous (grey)
    # are the only ones that differ from render's frame. --frames 1: the frame written is then the
    # one that computes the overlay, whose offscreen comparison once left another framebuffer
    # bound and lost the overlay (CI, a loaded machine, 2026-12-05).
    shot = os.path.join(work, "view_overlay.png")
    out = os.path.join(work, "render_default.json_cs.png")
    v = subprocess.run(["xvfb-run", "-a", shadowcert, "view", default, "--method", "cs", "--size", SIZE, "--overlay",
                        "--screenshot", shot, "--frames", "1"], capture_output=True, text=True, timeout=600)
    counts = re.search(r"(\d+) hard errors, (\d+) ambiguous pixels", v.stdout)
    if v.returncode != 0 or counts is None:
        print("FAILED overlay: exit %d, %s %s" % (v.returncode, v.stdout.strip(), v.stderr.strip()))
        failures += 1
    else:
        hard, ambiguous = int(counts.group(1)), int(counts.group(2))
        a, b = read_png(shot), read_png(out)
        red = sum(1 for ra, rb in zip(a[2], b[2]) for x in range(0, len(ra), 4)
                  if ra[x:x + 4] != rb[x:x + 4] and ra[x] > ra[x + 1] + 100)
        n = differing_pixels(a, b)
        ok = hard == 0 and red == 0 and ambiguous > 0 and 0 < n <= ambiguous
        print("%s overlay: %d hard, %d ambiguous, %d pixels differ from render, %d red" % (
            "ok" if ok else "FAILED", hard, ambiguous, n, red))
        failures += not ok
    # An unknown method: exit 2, naming it.
    bad = subprocess.run(["xvfb-run", "-a", shadowcert, "view", default, "--method", "nosuch", "--frames", "1"],
                         capture_output=True, text=True, timeout=120)
    ok = bad.returncode == 2 and "nosuch" in bad.stderr
    print("%s unknown method: exit %d, %s" % ("ok" if ok else "FAILED", bad.returncode, bad.stderr.strip()[:200]))
    failures += not ok
    # No display: exit 2, saying what is missing.
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    nodisplay = subprocess.run([shadowcert, "view", default, "--frames", "1"], capture_output=True, text=True,
                               timeout=120, env=env)
    ok = nodisplay.returncode == 2 and "display" in nodisplay.stderr.lower()
    print("%s no display: exit %d, %s" % ("ok" if ok else "FAILED", nodisplay.returncode, nodisplay.stderr.strip()))
    failures += not ok
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
