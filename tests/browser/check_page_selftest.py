#!/usr/bin/python3
"""Self-test of check_page.py against a hand-made page and its broken variants.

fixtures/good.html must pass and leave a real full-width PNG screenshot. Each
variant is good.html with one change (BROKEN below, written into the output
folder) that breaks it in exactly one way: it must fail (exit 1) with every
`error:` line naming that reason, so the checker neither misses a problem nor
reports unrelated ones. Runs two checks at a time (each is one headless
Chromium).

usage: check_page_selftest.py [--out DIR] [--chromium PATH] [--jobs N]
Exit status: 0 all hold, 1 something failed (printed), 3 chromium missing.
"""

import argparse
import concurrent.futures
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
CHECKER = HERE / "check_page.py"
GOOD = HERE / "fixtures" / "good.html"
TIMEOUT = 60  # seconds per checker run; the harness kills it 15 s later

MASK_B = ('<img class="mask" alt="mask B" src="data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAQAAAAECAIAAAAm'
          'kwkpAAAAEElEQVR42mPQWBAARwzEcQDEwxGBeljglQAAAABJRU5ErkJggg==">')
END = "</body>"

# Each broken variant: (the text of good.html it replaces, wherever it stands, its replacement, a
# regex every error line must match).
BROKEN = {
    "console-error.html": (END, "<script>console.error('fixture: something went wrong');</script>\n" + END,
                           r"console error: fixture: something went wrong"),
    "exception.html": (END, "<script>throw new Error('fixture: boom');</script>\n" + END,
                       r"exception: Uncaught Error: fixture: boom"),
    "broken-mask.html": (MASK_B, '<img class="mask" alt="mask B" src="data:image/png;base64,bm90IGEgcG5n">',
                         r"img\.mask #2 \(mask B\) did not load"),
    "truncated-mask.html": (MASK_B, MASK_B[:MASK_B.index("EElEQVR42mPQ") + 12] + '">',
                            r"img\.mask #2 \(mask B\) data: PNG is truncated"),
    "external.html": ("</style>", '</style>\n<script src="http://example.com/x.js"></script>',
                      r"http://example\.com/x\.js"),
    "hidden-chart.html": ('<svg id="pareto"', '<svg id="pareto" style="display:none"', r"svg#pareto is display:none"),
    "no-masks.html": ('<img class="mask"', '<img class="thumbnail"', r"found 0 img\.mask, need >= 1"),
}
EXPECT = {"good.html": None, **{name: pattern for name, (_, _, pattern) in BROKEN.items()}}


def write_variants(out):
    """Writes each broken variant of good.html into `out`."""
    good = GOOD.read_text()
    for name, (old, new, _) in BROKEN.items():
        assert old in good, "good.html changed: %r is not in it" % old
        (out / name).write_text(good.replace(old, new))


def run_checker(page, shot, chromium, extra=()):
    cmd = [sys.executable, str(CHECKER), "--page", str(page), "--screenshot", str(shot),
           "--timeout", str(TIMEOUT), *extra]
    if chromium:
        cmd += ["--chromium", chromium]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT + 15)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        return None, "", "checker hung (killed after %d s)" % (TIMEOUT + 15)


def png_size(path):
    """(width, height) from a PNG's IHDR, or None when it is not a PNG."""
    head = path.read_bytes()[:24]
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_fixture(name, out, chromium):
    """Returns (name, list of failures, exit status, seconds)."""
    page, shot = (GOOD if name == "good.html" else out / name), out / (Path(name).stem + ".png")
    start = time.monotonic()
    rc, stdout, stderr = run_checker(page, shot, chromium, ["--min-masks", "1"])
    took = time.monotonic() - start
    fails = []
    errors = [l for l in stderr.splitlines() if l.startswith("error:")]
    pattern = EXPECT[name]
    if rc == 3:
        fails.append(stderr.strip())  # chromium unavailable: the caller skips
    elif pattern is None:
        if rc != 0:
            fails.append("expected exit 0, got %s: %s" % (rc, stderr.strip()))
        elif not stdout.startswith("ok: "):
            fails.append("no ok line: %r" % stdout)
        elif not shot.is_file() or shot.stat().st_size == 0:
            fails.append("no screenshot written at %s" % shot)
        else:
            size = png_size(shot)
            if size is None:
                fails.append("screenshot %s is not a PNG" % shot)
            elif size[0] < 1000:
                fails.append("screenshot %s is only %dx%d" % (shot, *size))
    else:
        if rc != 1:
            fails.append("expected exit 1, got %s: %s" % (rc, stderr.strip()))
        if not errors:
            fails.append("no error line on stderr")
        for line in errors:
            if not re.search(pattern, line):
                fails.append("unexpected reason (want /%s/): %s" % (pattern, line))
    return name, fails, rc, took


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, help="keep screenshots here (default: temp dir)")
    ap.add_argument("--chromium", help="browser executable (default: chromium on PATH)")
    ap.add_argument("--jobs", type=int, default=2, help="checks run at once (default 2)")
    args = ap.parse_args()

    out = args.out or Path(tempfile.mkdtemp(prefix="check_page_selftest."))
    out.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    failed = []
    try:
        # No browser needed: a missing executable must map to exit 3 (skip).
        rc, _, err = run_checker(GOOD, out / "none.png",
                                 "/nonexistent/chromium")
        if rc != 3 or not err.startswith("error: chromium: "):
            failed.append("missing chromium: expected exit 3, got %s: %s" % (rc, err.strip()))

        write_variants(out)
        with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
            results = list(pool.map(lambda n: check_fixture(n, out, args.chromium),
                                    sorted(EXPECT)))
        for name, fails, rc, _ in results:
            if rc == 3:
                if os.environ.get("FRUGAL_TEST_STRICT") == "1":
                    print("error: %s: %s, and FRUGAL_TEST_STRICT=1 forbids skipping" % (name, fails[0]),
                          file=sys.stderr)
                    return 1
                print("skip: %s: %s" % (name, fails[0]), file=sys.stderr)
                return 3
        for name, fails, rc, took in results:
            print("%-4s %-20s exit %s  %.1fs" % ("FAIL" if fails else "ok", name, rc, took))
            failed += ["%s: %s" % (name, f) for f in fails]
    finally:
        if args.out is None:
            shutil.rmtree(out, ignore_errors=True)

    for f in failed:
        print("error: " + f, file=sys.stderr)
    print("%s: %d fixtures in %.1fs" % ("FAILED" if failed else "passed", len(EXPECT),
                                         time.monotonic() - start))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
