"""The page as a new user's first look at it takes it (tests/web, ctest web/screenshot):
screenshot_page.py CHROMIUM PAGE_DIR OUT.png [--fragment F] [--copy-to FILE].

Runs Chromium's own one-shot screenshot with the flags of a WebGPU try on SwiftShader:
  chromium-headless-shell --headless --use-angle=swiftshader --enable-unsafe-swiftshader --enable-unsafe-webgpu
    --use-webgpu-adapter=swiftshader --virtual-time-budget=15000 --screenshot=OUT.png PAGE_DIR/index.html
with --dump-dom in the same run for what the page says about itself. Passes when, within the budget, the
page reports body[data-status] "ready" (it draws: WebGPU, or WebGL 2) or "fallback" with the reason in its
status line, and every panel in the screenshot (one per skinning method: body[data-panels], the length of
the runtime's method table) shows a coloured character. Fails (exit 1,
a line saying why) on "loading" (nothing came up in time: the blank page), "error", no status, or an empty
panel. --fragment adds #F to the address; --copy-to copies the screenshot there when the check passes (the
web-page-picture target refreshes docs/img/web-page.png this way).
"""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

FLAGS = ["--headless", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--enable-unsafe-webgpu",
         "--use-webgpu-adapter=swiftshader", "--virtual-time-budget=15000"]
# Not part of the try above, but needed here: root in a container (no sandbox), a throwaway profile, a
# small /dev/shm, and a window wide enough for the controls and the captions.
HOUSEKEEPING = ["--no-sandbox", "--no-first-run", "--disable-extensions", "--disable-dev-shm-usage",
                "--hide-scrollbars", "--window-size=1280,760"]


def read_png(path, max_rows=None):
    """(width, height, rows of RGB tuples) of an 8-bit RGB or RGBA PNG, as Chromium writes them; only the
    first max_rows rows when given."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    at, idat, width = 8, b"", 0
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                raise ValueError("PNG of depth %d, colour type %d, interlace %d" % (depth, colour, interlace))
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(min(height, max_rows or height)):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, [[tuple(r[x * bpp:x * bpp + 3]) for x in range(width)] for r in rows]


def method_names(html):
    """The names of CGA_DATA.methods (the exporter writes the runtime's method table there, one
    {name: "...", colour: [...], vec4s: N} per method) in the page's text."""
    m = re.search(r"^\s*methods: \[(.*)\],$", html, re.M)
    return re.findall(r'\{name: "([^"]*)"', m.group(1)) if m else []


def run(chromium, what, url, profile):
    cmd = [chromium, *FLAGS, *HOUSEKEEPING, "--user-data-dir=" + profile, *what, url]
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=90, text=True)


def main():
    args = sys.argv[1:]
    fragment, copy_to = "", None
    if "--fragment" in args:
        fragment = "#" + args.pop(args.index("--fragment") + 1)
        args.remove("--fragment")
    if "--copy-to" in args:
        copy_to = args.pop(args.index("--copy-to") + 1)
        args.remove("--copy-to")
    chromium, page_dir, out_png = args
    if not os.access(chromium, os.X_OK):
        print("FAIL chromium-headless-shell not found (%r): install Debian's chromium-headless-shell" % chromium)
        return 1
    url = "file://" + os.path.join(os.path.abspath(page_dir), "index.html") + fragment
    profile = tempfile.mkdtemp(prefix="cgagen-shot-")
    try:
        start = time.monotonic()
        if os.path.exists(out_png):
            os.remove(out_png)
        dom = run(chromium, ["--screenshot=" + os.path.abspath(out_png), "--dump-dom"], url, profile).stdout
        shot_s = time.monotonic() - start
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    m = re.search(r'<body[^>]*\bdata-status="([a-z]*)"', dom)
    status = m.group(1) if m else None
    line = re.search(r'<div id="status">(.*?)</div>', dom, re.S)
    line = re.sub(r"\s+", " ", line.group(1)).strip() if line else ""
    print("status %s: %s" % (status, line))
    print("screenshot %s (%.1f s in Chromium)" % (out_png, shot_s))
    if status not in ("ready", "fallback"):
        print("FAIL the page did not come up within the budget (status %s): %s" % (status, line))
        return 1
    if status == "fallback" and "fell back from WebGPU: " not in line:
        print("FAIL the page fell back without saying why: %s" % line)
        return 1
    rect = re.search(r'<body[^>]*\bdata-canvas="([0-9.]+) ([0-9.]+) ([0-9.]+) ([0-9.]+)"', dom)
    panels = re.search(r'<body[^>]*\bdata-panels="([0-9]+)"', dom)
    if not os.path.isfile(out_png) or not rect or not panels:
        print("FAIL no screenshot, or the page gave no canvas position or panel count")
        return 1
    panels = int(panels.group(1))
    methods = method_names(dom)
    if panels != len(methods):
        print("FAIL the page draws %d panels for the %d methods of its data (%s)" % (panels, len(methods),
                                                                                      ", ".join(methods)))
        return 1
    x0, y0, w, h = (float(v) for v in rect.groups())
    width, height, pixels = read_png(out_png, int(y0 + h) + 1)
    height = min(height, len(pixels))
    # A character's pixels are coloured (the methods' colours, shaded); the page around them is grey.
    for panel in range(panels):
        xs = range(max(0, int(x0 + panel * w / panels) + 2), min(width, int(x0 + (panel + 1) * w / panels) - 2))
        ys = range(max(0, int(y0) + 24), min(height, int(y0 + h) - 2))  # below the panel's name
        coloured = sum(1 for y in ys for x in xs if max(pixels[y][x]) - min(pixels[y][x]) > 50)
        share = coloured / max(1, len(xs) * len(ys))
        print("panel %d: %.1f%% coloured pixels" % (panel + 1, 100 * share))
        if share < 0.01:
            print("FAIL panel %d of the screenshot shows no character" % (panel + 1))
            return 1
    if copy_to:
        shutil.copyfile(out_png, copy_to)
        print("copied to %s" % copy_to)
    print("PASS the page came up (%s) and draws all %d panels" % (status, panels))
    return 0


if __name__ == "__main__":
    sys.exit(main())
