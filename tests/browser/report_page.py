#!/usr/bin/python3
"""The page `frugal report` writes, opened in headless Chromium (check_page.py) with no network.

Runs `frugal report` on a scene where some methods are inexact (so the page has masks), then checks
that the page loads without a console error and shows the recommendation, the chart, both tables
and one visible, decodable mask per inexact method of report.json; the screenshot is kept.

  report_page.py --frugal BUILD/frugal --out DIR [--chromium PATH]

Exit status: 0 pass, 1 fail, 3 chromium missing (a skip, unless FRUGAL_TEST_STRICT=1, under which
a missing dependency fails as in every other test).
"""

import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frugal", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--chromium", default=None)
    args = parser.parse_args()

    os.makedirs(args.out, exist_ok=True)
    report_dir = os.path.join(args.out, "report")
    # 4 views of 12 cubes at 320x240: paper culling and depth sort differ, the others are exact.
    run = subprocess.run([args.frugal, "report", "builtin:cubes?count=12", "--views", "4", "--size", "320x240",
                          "--repeat", "1", "-q", "-o", report_dir], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"error: frugal report: exit {run.returncode}: {run.stderr.strip()}", file=sys.stderr)
        return 1
    with open(os.path.join(report_dir, "report.json")) as f:
        report = json.load(f)
    inexact = sum(1 for r in report["rows"] if r["differing_px"] > 0)
    if inexact == 0:
        print("error: frugal report: no method differs in colour, so no mask to check", file=sys.stderr)
        return 1

    check = [sys.executable, os.path.join(HERE, "check_page.py"), "--page", os.path.join(report_dir, "index.html"),
             "--screenshot", os.path.join(args.out, "report-page.png"), "--min-masks", str(inexact)]
    if args.chromium:
        check += ["--chromium", args.chromium]
    status = subprocess.run(check).returncode
    if status == 3 and os.environ.get("FRUGAL_TEST_STRICT") == "1":
        print("error: chromium is missing, and FRUGAL_TEST_STRICT=1 forbids skipping", file=sys.stderr)
        return 1
    return status


if __name__ == "__main__":
    sys.exit(main())
