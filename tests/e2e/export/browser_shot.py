#!/usr/bin/env python3
"""Opens a page in headless Chromium and writes a PNG screenshot of it once OpenSeadragon has
loaded every tile of the view (the page's global `viewer`), through the DevTools protocol over a
pipe (--remote-debugging-pipe: no port, no WebSocket library).

  browser_shot.py CHROMIUM PAGE.html WIDTHxHEIGHT OUT.png

The viewport is exactly WIDTHxHEIGHT CSS pixels at a device scale of 1. Exit 0 with the
screenshot written; 1 when the page does not load its tiles within 60 s (with the reason);
77 when Chromium cannot start here (the reason on stdout, for SKIP_RETURN_CODE)."""
import base64
import json
import os
import subprocess
import sys
import tempfile
import time

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-extensions", "--mute-audio", "--hide-scrollbars", "--remote-debugging-pipe"]


class Pipe:
    def __init__(self, proc, to_fd, from_fd):
        self.proc, self.to_fd, self.from_fd = proc, to_fd, from_fd
        self.next_id, self.buf = 1, b""

    def send(self, method, params=None, session=None, timeout=30):
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        self.next_id += 1
        os.write(self.to_fd, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            while b"\0" not in self.buf:
                if time.monotonic() > deadline:
                    raise TimeoutError(method)
                chunk = os.read(self.from_fd, 1 << 20)
                if not chunk:
                    raise EOFError("Chromium closed the pipe")
                self.buf += chunk
            raw, self.buf = self.buf.split(b"\0", 1)
            reply = json.loads(raw)
            if reply.get("id") == msg["id"]:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]


def evaluate(pipe, session, expr):
    r = pipe.send("Runtime.evaluate", {"expression": expr, "returnByValue": True,
                                       "awaitPromise": True}, session)
    return r.get("result", {}).get("value")


LOADED = ("typeof viewer !== 'undefined' && viewer.world.getItemCount() > 0 && "
          "viewer.world.getItemAt(0).getFullyLoaded()")
FRAMES = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(true))))"


def main():
    chromium, page, size, out = sys.argv[1:5]
    width, height = (int(v) for v in size.split("x"))
    profile = tempfile.mkdtemp(prefix="vt-chromium-")
    to_r, to_w = os.pipe()
    from_r, from_w = os.pipe()
    # Chromium reads commands on fd 3 and writes replies on fd 4.
    try:
        proc = subprocess.Popen(
            [chromium, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}",
             "about:blank"],
            pass_fds=(3, 4), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            preexec_fn=lambda: (os.dup2(to_r, 3), os.dup2(from_w, 4)))  # kept: pass_fds
    except OSError as e:
        print(f"skip: cannot start {chromium}: {e}")
        return 77
    os.close(to_r)
    os.close(from_w)
    pipe = Pipe(proc, to_w, from_r)
    try:
        targets = pipe.send("Target.getTargets", timeout=30)["targetInfos"]
    except (EOFError, TimeoutError, OSError) as e:
        proc.kill()
        err = proc.stderr.read().decode(errors="replace").strip().splitlines()[-1:]
        print(f"skip: Chromium does not start here ({e}; {' '.join(err)})")
        return 77
    try:
        target = next(t for t in targets if t["type"] == "page")["targetId"]
        session = pipe.send("Target.attachToTarget", {"targetId": target, "flatten": True})[
            "sessionId"]
        pipe.send("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False},
                  session)
        pipe.send("Page.enable", {}, session)
        pipe.send("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session)
        deadline = time.monotonic() + 60
        while not evaluate(pipe, session, LOADED):
            if time.monotonic() > deadline:
                print(f"{page}: the viewer did not load its tiles within 60 s")
                return 1
            time.sleep(0.1)
        evaluate(pipe, session, FRAMES)
        shot = pipe.send("Page.captureScreenshot", {"format": "png"}, session)
        with open(out, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        return 0
    finally:
        try:
            pipe.send("Browser.close", timeout=10)
        except Exception:
            pass
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        subprocess.run(["rm", "-rf", profile])


if __name__ == "__main__":
    sys.exit(main())
