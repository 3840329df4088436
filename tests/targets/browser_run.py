"""Opens a page in headless Chromium and writes what it computed: browser_run.py CHROMIUM API PAGE OUT TIMEOUT_S
[SCREENSHOT.png] (the page as drawn once its result is in; tests/web uses it).

API is webgpu or webgl2 (the flags that put it on SwiftShader, Chromium's CPU implementation of Vulkan and
GL ES). The page (tests/targets/browser_harness.js inlined by targets_check) sets window.cgagenResult to a
promise of a text; this waits for it and writes it to OUT.

Why not --dump-dom: it dumps at the load event, before WebGPU's asynchronous work ends, and
--virtual-time-budget only waits while the renderer has timers, and then in virtual time (page timings
became fiction). Here Chromium is driven through the DevTools protocol on a pipe (--remote-debugging-pipe:
JSON messages ending in NUL, read on fd 3, written on fd 4): no network, no port, real time.

Exit status 0 with OUT written; else a message on stderr and status 1 (2: Chromium missing, 3: timed out).
"""
import fcntl
import json
import os
import select
import signal
import subprocess
import sys
import tempfile
import time

FLAGS = {
    "webgpu": ["--enable-unsafe-webgpu", "--enable-features=Vulkan", "--use-angle=swiftshader",
               "--use-webgpu-adapter=swiftshader"],
    "webgl2": ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
}


def main():
    chromium, api, page, out_path, timeout = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5])
    if not chromium or not os.access(chromium, os.X_OK):
        sys.stderr.write("browser_run: Chromium not found (%r). Install Debian's chromium-headless-shell "
                         "(scripts/setup.sh does) and configure again.\n" % chromium)
        return 2
    deadline = time.monotonic() + timeout
    to_chrome_r, to_chrome_w = os.pipe()
    from_chrome_r, from_chrome_w = os.pipe()

    def child_fds():  # Chromium reads commands on fd 3 and writes replies on fd 4
        r = fcntl.fcntl(to_chrome_r, fcntl.F_DUPFD_CLOEXEC, 10)
        w = fcntl.fcntl(from_chrome_w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.dup2(r, 3)  # via fds >= 10: the pipe's own fds may be 3 or 4; dup2 makes 3 and 4 inheritable
        os.dup2(w, 4)  # (os.pipe's fds and the copies >= 10 close on exec)

    profile = tempfile.mkdtemp(prefix="cgagen-chromium-")
    log = open(out_path + ".chromium.log", "w")
    proc = subprocess.Popen(
        [chromium, "--headless", "--no-sandbox", "--no-first-run", "--disable-extensions",
         "--user-data-dir=" + profile,
         "--disable-dev-shm-usage",  # containers often have a small /dev/shm
         "--remote-debugging-pipe", *FLAGS[api], "about:blank"],
        stdin=subprocess.DEVNULL, stdout=log, stderr=log, close_fds=False,  # close_fds would close 3 and 4
        preexec_fn=child_fds, start_new_session=True)
    os.close(to_chrome_r)
    os.close(from_chrome_w)
    buf = b""
    next_id = 0

    def send(method, params=None, session=None):
        nonlocal next_id
        next_id += 1
        msg = {"id": next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(to_chrome_w, json.dumps(msg).encode() + b"\0")
        return next_id

    def receive(match):  # the first message for which match(msg) holds; raises TimeoutError past the deadline
        nonlocal buf
        while True:
            while b"\0" in buf:
                raw, buf = buf.split(b"\0", 1)
                msg = json.loads(raw)
                if match(msg):
                    return msg
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError
            ready, _, _ = select.select([from_chrome_r], [], [], left)
            if ready:
                chunk = os.read(from_chrome_r, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed the pipe (exit status %s); see %s.chromium.log"
                                       % (proc.poll(), out_path))
                buf += chunk

    def call(method, params=None, session=None):
        i = send(method, params, session)
        reply = receive(lambda m: m.get("id") == i)
        if "error" in reply:
            raise RuntimeError("%s: %s" % (method, reply["error"]))
        return reply["result"]

    status = 1
    try:
        target = call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        call("Page.enable", session=session)
        call("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session)
        receive(lambda m: m.get("method") == "Page.loadEventFired")
        result = call("Runtime.evaluate", {"expression": "window.cgagenResult", "awaitPromise": True,
                                           "returnByValue": True}, session)
        if "exceptionDetails" in result:
            raise RuntimeError("the page threw: %s" % json.dumps(result["exceptionDetails"])[:2000])
        with open(out_path, "w") as f:
            f.write(result["result"].get("value", ""))
        if len(sys.argv) > 6:
            import base64
            shot = call("Page.captureScreenshot", {"format": "png"}, session)
            with open(sys.argv[6], "wb") as f:
                f.write(base64.b64decode(shot["data"]))
        status = 0
        try:
            call("Browser.close")
        except Exception:
            pass
    except TimeoutError:
        sys.stderr.write("browser_run: Chromium did not finish within %g s (hung?); stopped it\n" % timeout)
        status = 3
    except Exception as e:
        sys.stderr.write("browser_run: %s\n" % e)
    finally:
        try:  # after Browser.close, Chromium exits by itself; else (an error, a hang) it is stopped at once
            proc.wait(timeout=5 if status == 0 else 0.1)
        except subprocess.TimeoutExpired:
            pass
        try:  # Chromium's helpers (GPU, renderer, zygote) share its process group
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()
        subprocess.run(["rm", "-rf", profile])
    return status


if __name__ == "__main__":
    sys.exit(main())
