"""Headless Chromium with WebGL2 on SwiftShader, driven over the DevTools pipe.

The reference renderers are WebGL programs, and this machine has no GPU: Chromium's
ANGLE-on-SwiftShader gives a WebGL2 context (MAX_SAMPLES 4) in software. The
browser is driven with --remote-debugging-pipe: it reads commands on fd 3 and
writes replies and events on fd 4, each message JSON ended by a NUL byte (the
approach of tests/browser/check_page.py). Python 3 standard library only.

Pages are fetched from a loopback HTTP server (see serve.py); every other host is
unreachable (a dead proxy and a resolver that resolves nothing), so a page that
reaches for the network fails instead of quietly depending on it.
"""

import json
import os
import queue
import shutil
import signal
import subprocess
import tempfile
import threading
import time


class ChromiumUnavailable(Exception):
    """Chromium is missing or does not start."""


class BrowserError(Exception):
    """A page could not be driven (timeout, protocol error, crash, script error)."""


def find_chromium(given=None):
    """Path of the browser: the one given, else the first of the usual names on PATH."""
    for exe in ([given] if given else ["chromium", "chromium-browser", "google-chrome"]):
        path = shutil.which(exe)
        if path:
            return path
    raise ChromiumUnavailable("not found (%s); install it (apt-get install -y chromium) "
                              "or pass --chromium PATH" % (given or "chromium"))


class Browser:
    """One headless Chromium process and its DevTools pipe.

    Use as a context manager; close() always kills the whole process group.
    """

    FLAGS = [
        "--headless=new", "--remote-debugging-pipe",
        "--no-first-run", "--no-default-browser-check",
        "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--disable-extensions",
        # WebGL2 without a GPU: ANGLE on SwiftShader, which Chromium only uses
        # for WebGL when told that software rendering is wanted.
        "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
        "--enable-webgl", "--ignore-gpu-blocklist",
        # Offline: loopback bypasses the proxy; anything else goes nowhere.
        "--proxy-server=127.0.0.1:9",
        "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1",
    ]

    def __init__(self, exe):
        self.workdir = tempfile.mkdtemp(prefix="fidelity-chromium.")
        self.events = queue.Queue()  # every message from the browser, in order
        self.pending = []            # events read while waiting for a reply
        self.next_id = 0
        self.proc = None
        self.cmd_w = self.res_r = None
        args = [exe] + self.FLAGS + ["--user-data-dir=" + os.path.join(self.workdir, "profile")]
        if os.geteuid() == 0:
            args.append("--no-sandbox")  # Chromium refuses to run as root otherwise
        args.append("about:blank")

        # Our ends: cmd_w (we write), res_r (we read). Chromium's: fd 3, fd 4.
        cmd_r, self.cmd_w = os.pipe()
        self.res_r, res_w = os.pipe()

        def child_fds():
            # Move to high numbers first so dup2 to 3/4 cannot clobber either.
            hi_r = os.dup2(cmd_r, 100)
            hi_w = os.dup2(res_w, 101)
            os.dup2(hi_r, 3)
            os.dup2(hi_w, 4)

        self.log_path = os.path.join(self.workdir, "chromium.log")
        try:
            with open(self.log_path, "wb") as log:
                self.proc = subprocess.Popen(
                    args, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                    pass_fds=(3, 4), preexec_fn=child_fds,
                    start_new_session=True)  # own process group: close() kills all helpers
        except OSError as e:
            self.close()
            raise ChromiumUnavailable("cannot start %s: %s" % (exe, e))
        finally:
            os.close(cmd_r)
            os.close(res_w)
        threading.Thread(target=self._reader, daemon=True).start()

        try:
            self.version = self.call("Browser.getVersion", timeout=30)
        except BrowserError as e:
            try:  # EOF on the pipe can come just before the exit status
                status = self.proc.wait(timeout=1)
            except subprocess.TimeoutExpired:
                status = None
            self.close()
            if status is not None:
                raise ChromiumUnavailable("%s exited with status %d at startup%s"
                                          % (exe, status, self.log_tail()))
            raise ChromiumUnavailable("%s did not answer on the pipe: %s" % (exe, e))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _reader(self):
        parts = []  # pieces of the message being received (data: URLs are large)
        while True:
            try:
                chunk = os.read(self.res_r, 1 << 20)
            except (OSError, TypeError):  # TypeError: fd closed under us
                chunk = b""
            if not chunk:
                self.events.put(None)  # EOF: the browser went away
                return
            while True:
                end = chunk.find(b"\0")
                if end < 0:
                    parts.append(chunk)
                    break
                parts.append(chunk[:end])
                self.events.put(json.loads(b"".join(parts)))
                parts, chunk = [], chunk[end + 1:]

    def _next(self, deadline, waiting_for):
        left = deadline - time.monotonic()
        try:
            if left <= 0:
                raise queue.Empty
            msg = self.events.get(timeout=left)
        except queue.Empty:
            raise BrowserError("timed out waiting for %s" % waiting_for) from None
        if msg is None:
            self.events.put(None)  # keep reporting EOF to later callers
            raise BrowserError("chromium exited unexpectedly" + self.log_tail())
        return msg

    def call(self, method, params=None, session=None, timeout=60):
        """Sends one command and returns its result; events are kept for event()."""
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        try:
            while data:
                data = data[os.write(self.cmd_w, data):]
        except OSError as e:
            raise BrowserError("cannot write to chromium: %s%s" % (e, self.log_tail()))
        deadline = time.monotonic() + timeout
        while True:
            reply = self._next(deadline, "the reply to " + method)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise BrowserError("%s failed: %s" % (method, reply["error"].get("message")))
                return reply.get("result", {})
            self.pending.append(reply)

    def event(self, deadline, waiting_for):
        """Next event: first those seen while waiting for replies."""
        return self.pending.pop(0) if self.pending else self._next(deadline, waiting_for)

    def _drain(self):
        """Every event received so far, without waiting; the EOF mark is kept."""
        out, self.pending = self.pending, []
        while True:
            try:
                msg = self.events.get_nowait()
            except queue.Empty:
                return out
            if msg is None:
                self.events.put(None)
                return out
            out.append(msg)

    def log_tail(self):
        try:
            with open(self.log_path, errors="replace") as f:
                # Chromium logs dozens of ERROR:dbus lines in any container
                # without a system bus; they never explain a failure.
                lines = [l.rstrip() for l in f if l.strip() and ":ERROR:dbus/" not in l]
        except OSError:
            return ""
        return ("; chromium said: " + " | ".join(lines[-3:])) if lines else ""

    def close(self):
        """Asks the browser to quit, then kills its process group; always reaps."""
        if self.proc is not None:
            if self.proc.poll() is None:
                try:
                    msg = {"id": 0, "method": "Browser.close", "params": {}}
                    os.write(self.cmd_w, json.dumps(msg).encode() + b"\0")
                    self.proc.wait(timeout=5)
                except (OSError, subprocess.TimeoutExpired):
                    pass
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)  # leftover helpers
            except (ProcessLookupError, PermissionError):
                pass
            self.proc.wait()
            self.proc = None
        for fd in ("cmd_w", "res_r"):
            if getattr(self, fd) is not None:
                try:
                    os.close(getattr(self, fd))
                except OSError:
                    pass
                setattr(self, fd, None)
        shutil.rmtree(self.workdir, ignore_errors=True)

    def run_page(self, url, expression, timeout, width, height):
        """Opens url in a fresh tab, evaluates expression (awaiting a promise) and
        returns (value, console), console being the page's warnings and errors.

        A fresh tab per call: every render starts from a new WebGL context and
        a new JavaScript realm, so nothing one model leaves behind reaches the next.
        Raises BrowserError with the page's own errors when the script fails.
        """
        deadline = time.monotonic() + timeout
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        try:
            sid = self.call("Target.attachToTarget",
                            {"targetId": target, "flatten": True})["sessionId"]
            for domain in ("Page", "Runtime", "Log"):
                self.call(domain + ".enable", session=sid)
            self.call("Emulation.setDeviceMetricsOverride",
                      {"width": width, "height": height, "deviceScaleFactor": 1,
                       "mobile": False}, session=sid)
            console = []

            def note(msg):
                if msg.get("sessionId") == sid:
                    line = _console_line(msg)
                    if line and line not in console:
                        console.append(line)

            nav = self.call("Page.navigate", {"url": url}, session=sid)
            if nav.get("errorText"):
                raise BrowserError("cannot open %s: %s" % (url, nav["errorText"]))
            while True:
                msg = self.event(deadline, "the page's load event")
                note(msg)
                if msg.get("method") == "Page.loadEventFired" and msg.get("sessionId") == sid:
                    break

            left = max(1.0, deadline - time.monotonic())
            res = self.call("Runtime.evaluate",
                            {"expression": expression, "returnByValue": True,
                             "awaitPromise": True, "timeout": left * 1000},
                            session=sid, timeout=left)
            # Messages logged up to the script's end; those of other tabs and
            # the browser's own events are of no use later either.
            for msg in self._drain():
                note(msg)
            if "exceptionDetails" in res:
                d = res["exceptionDetails"]
                what = (d.get("exception", {}).get("description") or d.get("text", "")).splitlines()
                raise BrowserError("; ".join([what[0] if what else "script failed"] + console))
            return res["result"].get("value"), console
        finally:
            try:
                self.call("Target.closeTarget", {"targetId": target})
            except BrowserError:
                pass


def _console_line(msg):
    """A one-line description of a console warning/error or exception event, else None."""
    method, p = msg.get("method"), msg.get("params", {})
    if method == "Runtime.consoleAPICalled" and p.get("type") in ("warning", "error", "assert"):
        text = " ".join(str(a.get("value", a.get("description", a.get("type"))))
                        for a in p.get("args", []))
        return "console %s: %s" % (p["type"], text.splitlines()[0] if text else "")
    if method == "Runtime.exceptionThrown":
        d = p.get("exceptionDetails", {})
        what = (d.get("exception", {}).get("description") or d.get("text", "")).splitlines()
        return "exception: %s" % (what[0] if what else "?")
    if method == "Log.entryAdded":
        e = p.get("entry", {})
        if e.get("level") in ("warning", "error"):
            where = " (%s)" % e["url"] if e.get("url") else ""
            return "log %s %s: %s%s" % (e.get("source", "?"), e["level"], e.get("text", ""), where)
    return None
