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

With "heat" in the fragment it checks the heat map too (check_heat): the legend lies inside the 1280x760
window (body[data-legend] against body[data-window]) and says what the colours compare (each panel's own
method against the reference), every panel's label compares its own method with one reference
(data-heat-a, data-heat-b), and the screenshot agrees: the reference's panel has no red, and on the twist
strip ("twist" in the fragment, turned 180 degrees) a panel whose method pinches the strip has some.
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


def box(dom, attribute):
    """body[ATTRIBUTE] as numbers ("left top width height", "width height"); None when absent or empty."""
    m = re.search(r'<body[^>]*\b%s="([0-9. -]+)"' % attribute, dom)
    return [float(v) for v in m.group(1).split()] if m else None


def check_heat(dom, pixels, x0, y0, w, h, methods, twist):
    """The heat map's checks (see the module's text): None when they hold, else why not."""
    window, legend = box(dom, "data-window"), box(dom, "data-legend")
    if window != [1280, 760]:
        return "the window is %s, not the 1280x760 the check is for" % window
    if not legend or len(legend) != 4:
        return "the heat map is on but the page gives no legend position"
    left, top, width, height = legend
    if left < 0 or top < 0 or left + width > window[0] or top + height > window[1]:
        return "the legend (%g %g %g %g) is not inside the %gx%g window" % (left, top, width, height, *window)
    text = re.search(r'<div id="legend"[^>]*>(.*?)</div>', dom, re.S)
    text = re.sub(r"\s+", " ", re.sub(r"<[^>]*>", " ", text.group(1))) if text else ""
    labels = re.findall(r'<div class="panel-label"([^>]*)>', dom)
    pairs = [(re.search(r'data-heat-a="([^"]*)"', a), re.search(r'data-heat-b="([^"]*)"', a)) for a in labels]
    pairs = [(a.group(1), b.group(1)) if a and b else None for a, b in pairs]
    print("heat map pairs: %s" % ", ".join("%s vs %s" % p if p else "none" for p in pairs))
    print("legend at %g %g %g %g: %s" % (left, top, width, height, text))
    if len(pairs) != len(methods) or None in pairs:
        return "not every panel says what its heat map compares (data-heat-a, data-heat-b)"
    refs = {b for _, b in pairs}
    if [a for a, _ in pairs] != methods or len(refs) != 1:
        return "the panels do not each compare their own method with one reference: %s" % pairs
    ref = refs.pop()
    if "own method" not in text or ref not in text or "reference" not in text:
        return "the legend does not say that each panel's own method is compared with %s: %r" % (ref, text)
    # Red (heat near 1) against blue: a pixel whose red beats green and blue by a margin; the legend's own
    # colour bar is left out.
    def hot(panel):
        xs = range(int(x0 + panel * w / len(methods)) + 2, int(x0 + (panel + 1) * w / len(methods)) - 2)
        ys = range(int(y0) + 24, min(len(pixels), int(y0 + h) - 2))
        return sum(1 for y in ys for x in xs
                   if not (top <= y <= top + height) and pixels[y][x][0] > max(pixels[y][x][1:]) + 60)
    counts = [hot(p) for p in range(len(methods))]
    print("red pixels per panel: %s" % ", ".join("%s %d" % (m, c) for m, c in zip(methods, counts)))
    if counts[methods.index(ref)] > 0:
        return "the reference %s's own panel has red pixels: it is not compared with itself" % ref
    pinching = [m for m in ("lbs", "cga-points") if m in methods]
    if twist and pinching and not any(counts[methods.index(m)] > 0 for m in pinching):
        return "no red in the %s panel(s) on the twisted strip: the heat map shows no difference" % ", ".join(pinching)
    return None


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
    heat = ""
    if "heat" in fragment.lstrip("#").split("&"):
        why = check_heat(dom, pixels, x0, y0, w, h, methods, "twist" in fragment.lstrip("#").split("&"))
        if why:
            print("FAIL heat map: " + why)
            return 1
        heat = "; the heat map compares each panel's own method with the reference, legend in view"
    if copy_to:
        shutil.copyfile(out_png, copy_to)
        print("copied to %s" % copy_to)
    print("PASS the page came up (%s) and draws all %d panels%s" % (status, panels, heat))
    return 0


if __name__ == "__main__":
    sys.exit(main())
