#!/usr/bin/python3
"""Real-browser check of a self-contained HTML report page.

Why: the report is meant to be opened from disk, offline, years later. A page
that looks right in the generator's unit tests can still throw in a browser,
pull a script from a CDN, or carry a mask image that does not decode. This
loads the page in headless Chromium with the network cut off and fails on:

  * any request whose URL is not file:, data:, about: or blob:;
  * any console error/assert, uncaught exception, or browser log entry at
    level error (failed image/resource loads land there);
  * a missing, invisible or empty #recommendation, svg#pareto without circles,
    table#methods with < 2 body rows, table#papers with < 1 body row;
  * an img.mask that did not load/decode or is invisible, or fewer img.mask
    than --min-masks.

It then writes a full-page PNG screenshot for a human to look at.

Chromium is driven over the DevTools protocol with --remote-debugging-pipe:
the browser reads commands on fd 3 and writes replies/events on fd 4, each
message JSON terminated by a NUL byte. Python 3 standard library only.

Exit status: 0 pass, 1 page problems (one `error: <page>: <what>` line each on
stderr), 2 usage, 3 chromium missing or not startable (callers map to skip).
"""

import argparse
import base64
import json
import os
import queue
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse
import zlib
from pathlib import Path

ALLOWED_SCHEMES = ("file:", "data:", "about:", "blob:")

# Runs in the page after load; returns a list of human-readable problems.
PAGE_CHECK_JS = r"""
(async (minMasks) => {
  // Let late work (rAF callbacks, font loading) run so its errors surface.
  if (document.fonts) { await document.fonts.ready; }
  await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));

  const problems = [];
  // Why an element is not visible, or '' when it is.
  const hidden = (el) => {
    const cs = getComputedStyle(el);
    if (cs.display === 'none') return 'is display:none';
    if (cs.visibility !== 'visible') return 'is visibility:' + cs.visibility;
    const r = el.getBoundingClientRect();
    if (!(r.width > 0 && r.height > 0)) return 'has an empty bounding box';
    for (let e = el; e; e = e.parentElement) {   // opacity is not inherited
      if (parseFloat(getComputedStyle(e).opacity) === 0) return 'has opacity 0';
    }
    return '';
  };
  // Checks one required element; returns it when present.
  const need = (sel) => {
    const el = document.querySelector(sel);
    if (!el) { problems.push(sel + ' is missing'); return null; }
    const why = hidden(el);
    if (why) problems.push(sel + ' ' + why);
    return el;
  };
  const rows = (el) => el.querySelectorAll(':scope > tbody > tr').length;

  const rec = need('#recommendation');
  if (rec && !rec.textContent.trim()) problems.push('#recommendation has no text');

  const chart = need('svg#pareto');
  if (chart && chart.querySelectorAll('circle').length < 1)
    problems.push('svg#pareto has no circle (no points plotted)');

  const methods = need('table#methods');
  if (methods && rows(methods) < 2)
    problems.push('table#methods has ' + rows(methods) + ' body rows, need >= 2');

  const papers = need('table#papers');
  if (papers && rows(papers) < 1)
    problems.push('table#papers has no body rows');

  const masks = Array.from(document.querySelectorAll('img.mask'));
  const loaded = masks.map((img, i) => {
    const name = 'img.mask #' + (i + 1) + ' (' + (img.alt || img.src.slice(0, 40)) + ')';
    if (!img.complete || !(img.naturalWidth > 0 && img.naturalHeight > 0)) {
      problems.push(name + ' did not load/decode');
      return false;
    }
    const why = hidden(img);
    if (why) problems.push(name + ' ' + why);
    return true;
  });
  if (masks.length < minMasks)
    problems.push('found ' + masks.length + ' img.mask, need >= ' + minMasks);
  return {problems: problems,
          masks: masks.map((img, i) => ({src: img.src, alt: img.alt, loaded: loaded[i]}))};
})
"""


class ChromiumUnavailable(Exception):
    """Chromium is missing or did not start (exit 3, a skip for harnesses)."""


class CheckFailed(Exception):
    """The page check could not complete (timeout, protocol error, crash)."""


class Browser:
    """A headless Chromium process and its DevTools pipe."""

    def __init__(self, exe, timeout):
        self.timeout = timeout
        self.deadline = time.monotonic() + timeout
        self.waiting_for = "chromium to start"
        self.workdir = tempfile.mkdtemp(prefix="check_page.")
        self.events = queue.Queue()  # every message from the browser, in order
        self.pending = []            # events read while waiting for a reply
        self.next_id = 0
        self.proc = None
        args = [
            exe, "--headless=new", "--remote-debugging-pipe",
            "--user-data-dir=" + os.path.join(self.workdir, "profile"),
            "--no-first-run", "--no-default-browser-check", "--disable-gpu",
            "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--proxy-server=127.0.0.1:9",
            "--host-resolver-rules=MAP * ~NOTFOUND", "--window-size=1280,1024",
        ]
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

        self.stderr_path = os.path.join(self.workdir, "chromium.log")
        try:
            with open(self.stderr_path, "wb") as log:
                self.proc = subprocess.Popen(
                    args, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                    pass_fds=(3, 4), preexec_fn=child_fds,
                    start_new_session=True)  # own process group: kill all helpers
        except OSError as e:
            self.close()
            raise ChromiumUnavailable("cannot start %s: %s" % (exe, e))
        finally:
            os.close(cmd_r)
            os.close(res_w)
        threading.Thread(target=self._reader, daemon=True).start()

    def _reader(self):
        parts = []  # pieces of the message being received (screenshots are MBs)
        while True:
            try:
                chunk = os.read(self.res_r, 1 << 20)
            except OSError:
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

    def _next(self):
        left = self.deadline - time.monotonic()
        try:
            if left <= 0:
                raise queue.Empty
            msg = self.events.get(timeout=left)
        except queue.Empty:
            raise CheckFailed("timed out after %g s waiting for %s"
                              % (self.timeout, self.waiting_for)) from None
        if msg is None:
            raise CheckFailed("chromium exited unexpectedly" + self.log_tail())
        return msg

    def call(self, method, params=None, session=None):
        """Sends one command and returns its result; events are kept."""
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        self.waiting_for = "the reply to " + method
        try:
            while data:
                data = data[os.write(self.cmd_w, data):]
        except OSError as e:
            raise CheckFailed("cannot write to chromium: %s%s" % (e, self.log_tail()))
        while True:
            reply = self._next()
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise CheckFailed("%s failed: %s" % (method, reply["error"].get("message")))
                return reply.get("result", {})
            self.pending.append(reply)

    def event(self):
        """Next event: first those seen while waiting for replies."""
        return self.pending.pop(0) if self.pending else self._next()

    def drain(self):
        """Events already received, without waiting."""
        out, self.pending = self.pending, []
        while True:
            try:
                msg = self.events.get_nowait()
            except queue.Empty:
                return out
            if msg is not None:
                out.append(msg)

    def log_tail(self):
        try:
            with open(self.stderr_path, errors="replace") as f:
                # Chromium logs dozens of ERROR:dbus lines in any container
                # without a system bus; they never explain a failed start.
                lines = [l.rstrip() for l in f if l.strip() and ":ERROR:dbus/" not in l]
        except OSError:
            return ""
        return ("; chromium said: " + " | ".join(lines[-3:])) if lines else ""

    def close(self):
        """Asks the browser to quit, then kills the group; always reaps."""
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
            if getattr(self, fd, None) is not None:
                try:
                    os.close(getattr(self, fd))
                except OSError:
                    pass
                setattr(self, fd, None)
        shutil.rmtree(self.workdir, ignore_errors=True)


def describe_event(msg):
    """Returns a problem for an error-level console/log/network event, else None."""
    method, p = msg.get("method"), msg.get("params", {})
    if method in ("Network.requestWillBeSent", "Network.webSocketCreated"):
        url = p.get("request", {}).get("url") or p.get("url", "")
        if not url.startswith(ALLOWED_SCHEMES):
            return "network request to %s (the page must be self-contained)" % url
    elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
        text = " ".join(str(a.get("value", a.get("description", a.get("type"))))
                        for a in p.get("args", []))
        return "console %s: %s" % (p["type"], text)
    elif method == "Runtime.exceptionThrown":
        d = p.get("exceptionDetails", {})
        what = (d.get("exception", {}).get("description") or "").splitlines()
        return "exception: %s %s (line %d)" % (d.get("text", "Uncaught"),
                                               what[0] if what else "",
                                               d.get("lineNumber", -1) + 1)
    elif method == "Log.entryAdded":
        e = p.get("entry", {})
        if e.get("level") == "error":
            where = (" (%s)" % e["url"]) if e.get("url") else ""
            return "log %s error: %s%s" % (e.get("source", "?"), e.get("text", ""), where)
    return None


def png_problem(src):
    """Structural check of a data: PNG, or None when fine / not a data: PNG.

    Chromium shows a truncated PNG (valid header, cut-off data) as a loaded
    image with the right naturalWidth, so the in-page check alone misses it.
    """
    head, sep, payload = src.partition(",")
    if not sep or not head.lower().startswith("data:image/png"):
        return None
    try:
        if head.lower().endswith(";base64"):
            data = base64.b64decode("".join(urllib.parse.unquote(payload).split()),
                                    validate=True)
        else:
            data = urllib.parse.unquote_to_bytes(payload)
    except ValueError as e:
        return "has invalid base64 in its data: URL (%s)" % e
    if not data.startswith(b"\x89PNG\r\n\x1a\n"):
        return "data: URL is not a PNG"
    pos, idat, inflate = 8, False, zlib.decompressobj()
    while True:
        if pos + 12 > len(data):
            return "data: PNG is truncated (no IEND chunk)"
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        crc = data[pos + 8 + length:pos + 12 + length]
        if len(body) < length or len(crc) < 4:
            return "data: PNG is truncated in its %s chunk" % kind.decode("latin-1")
        if zlib.crc32(kind + body) != int.from_bytes(crc, "big"):
            return "data: PNG has a bad CRC in its %s chunk" % kind.decode("latin-1")
        if kind == b"IDAT":
            idat = True
            try:
                inflate.decompress(body)
            except zlib.error as e:
                return "data: PNG has corrupt image data (%s)" % e
        if kind == b"IEND":
            break
        pos += 12 + length
    if not idat or not inflate.eof:
        return "data: PNG has incomplete image data"
    return None


def find_chromium(given):
    for exe in ([given] if given else ["chromium", "chromium-browser", "google-chrome"]):
        path = shutil.which(exe)
        if path:
            return path
    raise ChromiumUnavailable("not found (%s); pass --chromium PATH" % (given or "chromium"))


def check(page, screenshot, exe, min_masks, timeout, problems):
    """Runs the whole check, appending to problems; returns the mask count."""
    browser = Browser(exe, timeout)
    try:
        try:
            browser.call("Browser.getVersion")
        except CheckFailed as e:
            try:  # EOF on the pipe can come just before the exit status
                status = browser.proc.wait(timeout=1)
            except subprocess.TimeoutExpired:
                status = None
            if status is not None:
                raise ChromiumUnavailable("%s exited with status %d at startup%s"
                                          % (exe, status, browser.log_tail()))
            raise ChromiumUnavailable("%s did not answer on the pipe: %s" % (exe, e))

        target = browser.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        sid = browser.call("Target.attachToTarget",
                           {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            browser.call(domain + ".enable", session=sid)
        browser.call("Emulation.setDeviceMetricsOverride",
                     {"width": 1280, "height": 1024, "deviceScaleFactor": 1,
                      "mobile": False}, session=sid)

        nav = browser.call("Page.navigate", {"url": page.as_uri()}, session=sid)
        if nav.get("errorText"):
            problems.append("navigation failed: " + nav["errorText"])
            return 0

        def note(msg):
            # Only events of our page's session count.
            if msg.get("sessionId") == sid:
                what = describe_event(msg)
                if what and what not in problems:
                    problems.append(what)

        browser.waiting_for = "the page's load event"
        while True:
            msg = browser.event()
            note(msg)
            if msg.get("method") == "Page.loadEventFired" and msg.get("sessionId") == sid:
                break

        res = browser.call("Runtime.evaluate",
                           {"expression": "(%s)(%d)" % (PAGE_CHECK_JS, min_masks),
                            "returnByValue": True, "awaitPromise": True}, session=sid)
        if "exceptionDetails" in res:
            raise CheckFailed("page check script failed: %s" % res["exceptionDetails"].get("text"))
        value = res["result"]["value"]
        problems.extend(value["problems"])
        for i, mask in enumerate(value["masks"]):
            why = mask["loaded"] and png_problem(mask["src"])
            if why:
                problems.append("img.mask #%d (%s) %s" % (i + 1, mask["alt"] or "no alt", why))

        metrics = browser.call("Page.getLayoutMetrics", session=sid)
        size = metrics.get("cssContentSize") or metrics["contentSize"]
        shot = browser.call("Page.captureScreenshot", {
            "format": "png", "captureBeyondViewport": True,
            "clip": {"x": 0, "y": 0, "scale": 1,
                     "width": max(1280, size["width"]), "height": size["height"]},
        }, session=sid)
        screenshot.parent.mkdir(parents=True, exist_ok=True)
        tmp = screenshot.with_name(screenshot.name + ".tmp")
        tmp.write_bytes(base64.b64decode(shot["data"]))
        os.replace(tmp, screenshot)

        for msg in browser.drain():  # anything logged while checking
            note(msg)
        return len(value["masks"])
    finally:
        browser.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--page", required=True, type=Path, help="HTML file to check")
    ap.add_argument("--screenshot", required=True, type=Path, help="PNG to write")
    ap.add_argument("--chromium", help="browser executable (default: chromium on PATH)")
    ap.add_argument("--min-masks", type=int, default=1, help="img.mask needed (default 1)")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds for it all (default 60)")
    args = ap.parse_args()

    # Chromium runs in its own session, so a harness killing our process group
    # would miss it: turn SIGTERM into an exit that runs the cleanup.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(128 + signal.SIGTERM))

    name, problems, masks = str(args.page), [], 0
    if not args.page.is_file():
        print("error: %s: no such file" % name, file=sys.stderr)
        return 1
    try:
        exe = find_chromium(args.chromium)
        masks = check(args.page.resolve(), args.screenshot, exe,
                      args.min_masks, args.timeout, problems)
    except ChromiumUnavailable as e:
        print("error: chromium: %s" % e, file=sys.stderr)
        return 3
    except CheckFailed as e:
        problems.append(str(e))
    for p in problems:
        print("error: %s: %s" % (name, p), file=sys.stderr)
    if problems:
        return 1
    print("ok: %s: %d masks, screenshot %s" % (name, masks, args.screenshot))
    return 0


if __name__ == "__main__":
    sys.exit(main())
