#!/usr/bin/env python3
"""The bench report in a real browser (docs/bench.md#the-report): `shadowcert bench` on a tiny
scene writes report.html; Debian's chromium, headless, loads it offline from a file:// URL and
the test checks that it loaded, that every <img> (the images and the plots) decoded
(naturalWidth > 0), that no error event fired and that nothing reached the console.

    report_browser_test.py SHADOWCERT_BINARY SOURCE_DIR

How: a copy of the page gets a small script at the top of <head> that records error events
(a resource that fails, an uncaught exception) and, on load, writes {images, undecoded, errors}
into an attribute of <html>; `chromium --headless --dump-dom --virtual-time-budget` prints the
DOM after the load, and `--enable-logging=stderr --v=0` prints every console message as
INFO:CONSOLE, which must not appear (the report has no script of its own). The page itself is
also checked to name nothing outside it (no http:, https: or file: URL).

Exit 0 pass, 1 fail, 77 skip (ctest's SKIP_RETURN_CODE): no EGL device (as the GL tests skip;
SHADOWCERT_REQUIRE_GL=1 fails instead), or no chromium or no matplotlib outside CI
(SHADOWCERT_REQUIRE_BROWSER=1, set by `tools/dev.sh test`, fails instead).
"""
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
CHECKER = """<script>
window.__shadowcertErrors = [];
window.addEventListener('error', function (e) {
  var t = e.target;
  window.__shadowcertErrors.push(e.message ? 'error: ' + e.message
                                           : 'resource failed: ' + (t && t.tagName) + ' ' + (t && t.alt || ''));
}, true);
window.addEventListener('unhandledrejection', function (e) { window.__shadowcertErrors.push('rejection: ' + e.reason); });
window.addEventListener('load', function () {
  var images = document.images, undecoded = [], plots = 0;
  for (var i = 0; i < images.length; ++i) {
    if (!images[i].complete || images[i].naturalWidth === 0) undecoded.push(images[i].alt);
    if (images[i].closest('figure.plot')) ++plots;
  }
  document.documentElement.setAttribute('data-shadowcert-check', JSON.stringify(
      {images: images.length, plots: plots, undecoded: undecoded, errors: window.__shadowcertErrors,
       title: document.title}));
});
</script>
"""


def flag(name):
    return os.environ.get(name, "") not in ("", "0")


def skip_or_fail(required, message):
    if required:
        print("FAIL: " + message)
        return 1
    print("SKIP: " + message)
    return SKIP


def find_chromium():
    for name in ("/usr/bin/chromium", "chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def main(argv):
    if len(argv) != 3:
        print("usage: report_browser_test.py SHADOWCERT_BINARY SOURCE_DIR")
        return 2
    binary, source = argv[1], argv[2]
    require_browser = flag("SHADOWCERT_REQUIRE_BROWSER")
    chromium = find_chromium()
    if chromium is None:
        return skip_or_fail(require_browser, "no chromium (Debian: apt install chromium; tools/dev.sh installs it)")

    work = tempfile.mkdtemp(prefix="shadowcert_report_browser_")
    try:
        out = os.path.join(work, "bench")
        scene = os.path.join(source, "data", "scenes", "default.json")
        run = subprocess.run([binary, "bench", scene, "--size", "48x36", "--frames", "1", "--methods",
                              "cpu,cs/exact,shadowmap/512,pcf/3,smooth/0.01,edges/diagonal", "--out", out],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False)
        if run.returncode == 2 and "EGL" in run.stdout:
            return skip_or_fail(flag("SHADOWCERT_REQUIRE_GL"), "no EGL device: " + run.stdout.strip())
        if run.returncode != 0:
            print("FAIL: shadowcert bench exited %d:\n%s" % (run.returncode, run.stdout))
            return 1
        if "plots not drawn" in run.stdout:
            status = skip_or_fail(require_browser, "the plots were not drawn: " + run.stdout.strip())
            if status != SKIP:
                return status
        report = os.path.join(out, "report.html")
        with open(report, encoding="utf-8") as f:
            page = f.read()
        outside = re.findall(r"""(?:src|href)\s*=\s*["']?\s*(?:https?:|file:|//)|url\(\s*["']?(?:https?:|file:|//)""",
                             page, re.IGNORECASE)
        if outside:
            print("FAIL: report.html names something outside it: %s" % outside[:3])
            return 1
        if "<script" in page.lower():
            print("FAIL: report.html has a script of its own (it must render without one)")
            return 1
        checked = os.path.join(work, "checked.html")
        with open(checked, "w", encoding="utf-8") as f:
            f.write(page.replace("<head>", "<head>\n" + CHECKER, 1))

        env = {k: v for k, v in os.environ.items() if k not in ("LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS")}
        profile = os.path.join(work, "profile")
        browser = subprocess.run(
            [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             "--user-data-dir=" + profile, "--enable-logging=stderr", "--v=0", "--virtual-time-budget=10000",
             "--dump-dom", "file://" + checked],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, timeout=240, check=False)
        if browser.returncode != 0:
            print("FAIL: chromium exited %d:\n%s" % (browser.returncode, browser.stderr[-4000:]))
            return 1
        match = re.search(r'data-shadowcert-check="([^"]*)"', browser.stdout)
        if match is None:
            print("FAIL: the page did not finish loading (no check result in the DOM):\n%s" % browser.stderr[-4000:])
            return 1
        result = json.loads(html.unescape(match.group(1)))
        console = [line for line in browser.stderr.splitlines() if ":CONSOLE" in line]
        failures = []
        if result["images"] == 0:
            failures.append("no image in the page")
        if result["undecoded"]:
            failures.append("images that did not decode: %s" % result["undecoded"])
        if result["errors"]:
            failures.append("error events: %s" % result["errors"])
        if console:
            failures.append("console messages: %s" % console)
        if require_browser and result["plots"] == 0:
            failures.append("no plot in the page")
        if not result["title"].startswith("shadowcert bench"):
            failures.append("unexpected title %r" % result["title"])
        if failures:
            print("FAIL: " + "; ".join(failures))
            return 1
        print("PASS: report.html loaded offline in %s: %d images (%d plots) decoded, no error, no console message"
              % (os.path.basename(chromium), result["images"], result["plots"]))
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
