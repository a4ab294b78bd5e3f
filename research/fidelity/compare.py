#!/usr/bin/env python3
"""Measures how far frugal's renders are from the fidelity references.

For each model of tests/data/fidelity/manifest.json, renders it with
`frugal render` at the manifest's camera, size and time, and measures frugal's
distances from the Khronos reference (images.py), next to three.js's from the
manifest. Prints a table; with --out DIR also writes fidelity.json,
fidelity.csv and frugal's images (frugal/<name>.png) there.

The goal the project holds frugal to (docs/fidelity.md), per model:
  mean_diff  at most three.js's + 2 levels, and never above 5 levels (where
             three.js itself disagrees with Khronos, its distance is no excuse);
  over_32    at most 2 % of the covered pixels;
  coverage   at most three.js's + 0.1 % of the image.

Exit status: 0 every model measured (whether or not it meets the goal: this
measures, it does not judge), 1 a model could not be measured (one
`error: <what>: <why>` line each), 2 bad command line.

With --check FILE (tests/data/fidelity/expected.json; CTest runs one model a
test) it judges too: a model FILE says meets the goal must still meet it, any
other must stay within the figures FILE records for it (or still be refused
with the reason FILE gives), else one `error:` line says which bound broke and
the exit status is 1.
"""

import argparse
import csv
import io
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import files
import images
import scene

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent

MEAN_MARGIN, MEAN_CAP = 2.0, 5.0
MAX_OVER_32 = 0.02
COVERAGE_MARGIN = 0.001
MEASURES = ("mean_diff", "over_32", "coverage")


class MeasureError(Exception):
    pass


def goal(three, frugal):
    """Which of the goal's three bounds frugal's distances meet, given three.js's."""
    bound = min(three["mean_diff"] + MEAN_MARGIN, MEAN_CAP)
    # None: the two images share no covered pixel, so colours cannot be compared.
    return {
        "mean_diff": frugal["mean_diff"] is not None and frugal["mean_diff"] <= bound,
        "over_32": frugal["over_32"] is not None and frugal["over_32"] <= MAX_OVER_32,
        "coverage": frugal["coverage"] <= three["coverage"] + COVERAGE_MARGIN,
    }


def three_of(entry):
    return {k: entry["three_vs_khronos"][k] for k in MEASURES}


def check(row, expected):
    """What breaks `expected` (an entry of --check's file) in a measured row: a list of reasons."""
    name = row["name"]
    if expected is None:
        return ["%s: not in the expectations file (add what it measures now)" % name]
    if "refused" in expected:
        if row["frugal"] is not None:
            return ["%s: was refused (%s) and now renders: record its figures" % (name, expected["refused"])]
        return [] if expected["refused"] in row["error"] else ["%s: %s" % (name, row["error"])]
    if row["frugal"] is None:
        return ["%s: %s" % (name, row["error"])]
    if expected.get("goal"):
        return ["%s: no longer meets the goal: %s %s" % (name, k, row["frugal"][k])
                for k in MEASURES if not row["meets_goal"][k]]
    ceilings = expected["at_most"]
    return ["%s: %s %s is above the %s recorded" % (name, k, row["frugal"][k], ceilings[k])
            for k in MEASURES if ceilings.get(k) is not None and
            (row["frugal"][k] is None or row["frugal"][k] > ceilings[k])]


def command_of(root, entry):
    """The frugal command line that reproduces one measurement, writing <name>.png."""
    return "frugal " + " ".join(scene.frugal_args(
        str(root / entry["file"]), entry["camera"], entry["time"], entry["name"] + ".png"))


def measure(frugal, root, refs, entry, workdir):
    """Renders one manifest entry with frugal; returns (row, frugal's PNG path)."""
    output = workdir / (entry["name"] + ".png")
    args = scene.frugal_args(str(root / entry["file"]), entry["camera"], entry["time"], str(output))
    run = subprocess.run([str(frugal)] + args + ["-q"], stdin=subprocess.DEVNULL,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        said = (run.stderr.strip() or run.stdout.strip()).splitlines()
        # Its last line is `error: FILE: why`; the file is known here.
        why = said[-1].removeprefix("error: ").removeprefix(args[1] + ": ") if said else ""
        raise MeasureError("frugal exited with status %d%s" % (run.returncode, ": " + why if why else ""))
    try:
        ours = images.read_png(output)
        khronos = images.read_png(refs / entry["images"]["khronos"])
    except (OSError, images.PngError) as e:
        raise MeasureError(str(e)) from None
    if ours[:2] != khronos[:2]:
        raise MeasureError("frugal's image is %dx%d, the reference's %dx%d" % (ours[:2] + khronos[:2]))
    three = three_of(entry)
    ours = {k: v for k, v in images.distance(ours, khronos).items() if k in MEASURES}
    return {"name": entry["name"], "three": three, "frugal": ours,
            "meets_goal": goal(three, ours)}, output


def table(rows):
    """The rows as a text table: levels, then percentages."""
    pct = lambda v: "-" if v is None else "%.2f%%" % (100 * v)
    lvl = lambda v: "-" if v is None else "%.2f" % v
    head = "%-32s %21s   %21s   %s" % ("", "three.js vs Khronos", "frugal vs Khronos", "goal met")
    sub = "%-32s %6s %7s %6s   %6s %7s %6s   %s" % (
        "model", "mean", ">32", "cover", "mean", ">32", "cover", "mean >32 cover")
    lines = [head, sub]
    for r in rows:
        t, f, g = r["three"], r["frugal"], r["meets_goal"]
        if f is None:
            lines.append("%-32s %6s %7s %6s   %s" % (
                r["name"], lvl(t["mean_diff"]), pct(t["over_32"]), pct(t["coverage"]), r["error"]))
            continue
        lines.append("%-32s %6s %7s %6s   %6s %7s %6s   %s" % (
            r["name"], lvl(t["mean_diff"]), pct(t["over_32"]), pct(t["coverage"]),
            lvl(f["mean_diff"]), pct(f["over_32"]), pct(f["coverage"]),
            " ".join("%-4s" % ("yes" if g[k] else "no") for k in MEASURES)))
    met = sum(all(r["meets_goal"].values()) for r in rows)
    lines.append("%d of %d models meet the goal" % (met, len(rows)))
    return "\n".join(lines)


def csv_text(rows):
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["name"] + ["three_" + k for k in MEASURES] + ["frugal_" + k for k in MEASURES]
               + ["meets_" + k for k in MEASURES] + ["error"])
    for r in rows:
        f = r["frugal"] or {}
        w.writerow([r["name"]] + [r["three"][k] for k in MEASURES] + [f.get(k) for k in MEASURES]
                   + [int(r["meets_goal"][k]) for k in MEASURES] + [r.get("error", "")])
    return out.getvalue()


def main():
    ap = argparse.ArgumentParser(
        description="Render every model of the fidelity manifest with frugal and measure its "
                    "distance from the Khronos reference, next to three.js's (docs/fidelity.md).")
    ap.add_argument("--manifest", type=Path, default=REPO / "tests" / "data" / "fidelity" / "manifest.json",
                    help="references' manifest (default tests/data/fidelity/manifest.json)")
    ap.add_argument("--frugal", type=Path, default=REPO / "build" / "frugal",
                    help="frugal executable (default build/frugal)")
    ap.add_argument("--only", action="append", metavar="NAME", help="this model only (repeatable)")
    ap.add_argument("--out", type=Path, metavar="DIR",
                    help="write fidelity.json, fidelity.csv and frugal/<name>.png here")
    ap.add_argument("--check", type=Path, metavar="FILE",
                    help="hold each model to what FILE expects of it (tests/data/fidelity/expected.json); "
                         "exit 1 when one falls short")
    args = ap.parse_args()
    expectations = None
    if args.check:
        try:
            expectations = json.loads(args.check.read_text())["models"]
        except (OSError, ValueError, KeyError) as e:
            print("error: %s: %s" % (args.check, e), file=sys.stderr)
            return 1

    try:
        manifest = json.loads(args.manifest.read_text())
        root, entries = Path(manifest["models_root"]), manifest["models"]
    except (OSError, ValueError, KeyError) as e:
        print("error: %s: %s" % (args.manifest, e), file=sys.stderr)
        return 1
    if not (args.frugal.is_file() and shutil.which(str(args.frugal))):
        print("error: %s: no such executable (build frugal, or pass --frugal)" % args.frugal, file=sys.stderr)
        return 1
    unknown = sorted(set(args.only or []) - {e["name"] for e in entries})
    if unknown:
        print("error: --only: no model named %s in %s" % (", ".join(unknown), args.manifest), file=sys.stderr)
        return 2
    version = subprocess.run([str(args.frugal), "--version"], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True).stdout.strip()

    measured = [e for e in entries if not args.only or e["name"] in args.only]
    rows, failed = [], 0
    with tempfile.TemporaryDirectory(prefix="fidelity-frugal.") as tmp:
        for entry in measured:
            try:
                row, png = measure(args.frugal, root, args.manifest.parent, entry, Path(tmp))
            except MeasureError as e:
                if expectations is None:  # with --check, judged below against what is expected
                    print("error: %s: %s" % (entry["name"], e), file=sys.stderr)
                failed += 1
                # Kept in the table: a file frugal refuses is as far from the goal as can be.
                row, png = {"name": entry["name"], "three": three_of(entry), "frugal": None,
                            "error": str(e), "meets_goal": {k: False for k in MEASURES}}, None
            rows.append(row)
            if args.out and png:
                files.write_atomic(args.out / "frugal" / png.name, png.read_bytes())

    print(table(rows))
    if args.out:
        report = {
            "about": "frugal's distances from the Khronos references, next to three.js's "
                     "(research/fidelity/compare.py, docs/fidelity.md)",
            "frugal": version,
            "manifest": str(args.manifest),
            "goal": {"mean_diff": "<= three.js's + %g levels, at most %g" % (MEAN_MARGIN, MEAN_CAP),
                     "over_32": "<= %g" % MAX_OVER_32,
                     "coverage": "<= three.js's + %g" % COVERAGE_MARGIN},
            "models": [dict(r, command=command_of(root, e)) for r, e in zip(rows, measured)],
        }
        files.write_atomic(args.out / "fidelity.json", (files.json_text(report) + "\n").encode())
        files.write_atomic(args.out / "fidelity.csv", csv_text(rows).encode())
    if expectations is not None:
        broken = [why for r in rows for why in check(r, expectations.get(r["name"]))]
        for why in broken:
            print("error: %s" % why, file=sys.stderr)
        return 1 if broken else 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
