"""Drives the page of cga-demo --web in headless Chromium and checks its self-test (tests/web, ctest):
check_page.py CHROMIUM API PAGE_DIR OUT_PREFIX [--expect-fail] [--hash EXTRA].

Loads PAGE_DIR/index.html#selftest through tests/targets/browser_run.py (DevTools pipe: it waits for the
page's window.cgagenResult, with a timeout), with API's flags (webgpu: Dawn on SwiftShader; webgl2: WebGPU
off, ANGLE on SwiftShader). The first line of the result must be "API ok MAXDEV" with MAXDEV <= 1e-4 (the
page compares the GPU's skinned vertices of every method with the CPU jobs' vertices embedded by the
exporter), and the page must load nothing from elsewhere (no URL, fetch, script src, link or import); with
--expect-fail it must be "API fail MAXDEV" with MAXDEV > 1e-4 (the mismatch check). Saves
OUT_PREFIX.png (a screenshot) and OUT_PREFIX.txt; the result's detail line must give a deviation for every method
of the page's data (CGA_DATA.methods, the runtime's method table) on the character and on the strip; prints the
page's frame time, labelled as what it is: a CPU emulation. Exit status 0 when the check holds, else 1 with the reason.
"""
import os
import re
import subprocess
import sys
import time

from screenshot_page import method_names

HERE = os.path.dirname(os.path.abspath(__file__))
RUNNER = os.path.join(HERE, "..", "targets", "browser_run.py")


def main():
    args = sys.argv[1:]
    expect_fail = "--expect-fail" in args
    extra = ""
    if "--hash" in args:
        extra = "&" + args[args.index("--hash") + 1]
    chromium, api, page_dir, prefix = args[0], args[1], args[2], args[3]
    page = os.path.join(os.path.abspath(page_dir), "index.html")
    if not os.path.isfile(page):
        print("FAIL no page %s (cga-demo --web did not write it)" % page)
        return 1
    # Self-contained: nothing the browser would load from elsewhere (file:// forbids fetch(); no network).
    with open(page, encoding="utf-8") as f:
        html = f.read()
    outside = re.findall(r"https?://|fetch\(|<script[^>]*\bsrc=|<link\b|import\(|\bimport\s", html)
    if outside:
        print("FAIL the page refers to outside resources: %s" % sorted(set(outside)))
        return 1
    for stale in (prefix + ".txt", prefix + ".png"):
        if os.path.exists(stale):
            os.remove(stale)
    start = time.monotonic()
    rc = subprocess.call([sys.executable, RUNNER, chromium, api, page + "#selftest" + extra, prefix + ".txt", "45",
                          prefix + ".png"])
    seconds = time.monotonic() - start
    if rc == 2:
        print("FAIL chromium-headless-shell not found (%r): install Debian's chromium-headless-shell "
              "(scripts/setup.sh does) and configure again" % chromium)
        return 1
    if rc != 0:
        print("FAIL browser_run.py exited with %d" % rc)
        return 1
    with open(prefix + ".txt") as f:
        text = f.read()
    print(text)
    first = text.splitlines()[0] if text else ""
    m = re.fullmatch(r"(webgpu|webgl2) (ok|fail) ([0-9.e+-]+|NaN|Infinity)", first)
    if not m:
        print("FAIL the page wrote no result line (PATH ok|fail MAXDEV): %r" % first)
        return 1
    path, verdict, dev = m.group(1), m.group(2), float(m.group(3))
    if path != api:
        print("FAIL the page ran the %s path, expected %s" % (path, api))
        return 1
    methods = method_names(html)
    detail = re.search(r"^detail (.*)$", text, re.M)
    tested = set(re.findall(r"(character|twist)/([a-z0-9-]+) ", detail.group(1) + " ")) if detail else set()
    missing = [w + "/" + m for m in methods for w in ("character", "twist") if (w, m) not in tested]
    if not methods or missing:
        print("FAIL the self-test did not compare every method of the data (%s): missing %s"
              % (", ".join(methods) or "no methods found", ", ".join(missing)))
        return 1
    frame = re.search(r"^frame_ms ([0-9.]+)", text, re.M)
    if frame:
        print("frame time %s ms on SwiftShader (CPU emulation of the GPU, not a GPU speed figure), %s path"
              % (frame.group(1), api))
    if not os.path.isfile(prefix + ".png") or os.path.getsize(prefix + ".png") < 10000:
        print("FAIL no screenshot (or an empty one) at %s.png" % prefix)
        return 1
    print("screenshot %s.png; %.1f s in Chromium" % (prefix, seconds))
    if expect_fail:
        if verdict == "fail" and not dev <= 1e-4:
            print("PASS the self-test detects mismatched vertices (%s fail %g)" % (api, dev))
            return 0
        print("FAIL the self-test accepted mismatched vertices: %s" % first)
        return 1
    if verdict == "ok" and dev <= 1e-4:
        print("PASS %s: max deviation %g of the character's size (bound 1e-4)" % (api, dev))
        return 0
    print("FAIL %s: %s" % (api, first))
    return 1


if __name__ == "__main__":
    sys.exit(main())
