#!/usr/bin/env bash
# The goals of `--cull occlusion` (docs/occlusion.md), measured with `frugal cull-report` at 800×600 on
# the default backend (llvmpipe here), every method interleaved view by view: conservative (the
# plan occlusion starts from), occlusion, and the oracle (exactly the visible triangles: the floor);
# on an orbit, occlusion-ahead too (each frame's plan made while the frame before draws).
#   docs/occlusion/run.sh [BUILD_DIR] [OUT_DIR]     (defaults: build, docs/occlusion)
# Writes OUT_DIR/<case>.json and .csv (cull-report's), OUT_DIR/three-bunnies.svg with its gnuplot
# script, OUT_DIR/goals.csv and OUT_DIR/goals.json; prints the goals table.
set -euo pipefail
build=${1:-build}
out=${2:-docs/occlusion}
mkdir -p "$out"
bunny=/usr/share/glmark2/models/bunny.obj
three="builtin:copies?count=3&of=$bunny"
methods="--methods conservative,occlusion,oracle"
# An orbit around the three bunnies: 48 views 7.5 degrees apart, at the distance of the whole views,
# a little above them.
/usr/bin/python3 - "$out/orbit-path.json" <<'PY'
import json, math, sys
views = [{"eye": [round(11.56 * math.sin(a), 4), 2.0, round(11.56 * math.cos(a), 4)], "target": [0, 0, 0]}
         for a in (2 * math.pi * i / 48 for i in range(48))]
json.dump(views, open(sys.argv[1], "w"), indent=1)
PY
# name | scene | views and options (each row also gets --repeat 5)
cases=(
  "three-bunnies|$three|--views 32 --cull-backfaces --plot $out/three-bunnies.svg $methods"
  "bunny|$bunny|--views 32 --cull-backfaces $methods"
  "dominoes-low-front|builtin:dominoes?polygons=24000|--eye 0,3,70 --target 0,2,0 $methods"
  "cubes|builtin:cubes|--views 32 $methods"
  "orbit|$three|--camera-path $out/orbit-path.json --cull-backfaces --methods conservative,occlusion,occlusion-ahead,oracle"
)
for entry in "${cases[@]}"; do
  IFS='|' read -r name scene args <<<"$entry"
  # shellcheck disable=SC2086
  "$build/frugal" cull-report "$scene" $args --repeat 5 -q --json "$out/$name.json" --csv "$out/$name.csv" \
    > "$out/$name.txt"
  echo "$name: done" >&2
done
/usr/bin/python3 - "$out" <<'PY'
import csv, json, statistics, sys
out = sys.argv[1]

def rows(name):
    return json.load(open(f"{out}/{name}.json"))

def ratios(report, method, classes=None):
    r = [m["ratio_to_oracle"] for v in report["views"] for m in v["methods"]
         if m["method"] == method and (classes is None or v["class"] in classes)]
    return statistics.median(r), max(r)

def vs_conservative(report, classes=None):
    # Per view, occlusion's (cull + draw) over conservative's.
    out = []
    for v in report["views"]:
        if classes is not None and v["class"] not in classes:
            continue
        t = {m["method"]: m["cull_ms"] + m["draw_ms"] for m in v["methods"]}
        out.append(t["occlusion"] / t["conservative"])
    return statistics.median(out), max(out)

goals = []
def goal(what, value, limit, note=""):
    goals.append({"goal": what, "measured": round(value, 3), "limit": limit, "met": value <= limit, "note": note})

three = rows("three-bunnies")
med, worst = ratios(three, "occlusion", {"whole"})
cmed, cworst = ratios(three, "conservative", {"whole"})
goal("three bunnies, whole views: median x oracle", med, 1.15, f"conservative {cmed:.3f}")
goal("three bunnies, whole views: worst x oracle", worst, 1.5, f"conservative {cworst:.3f}")
med, worst = ratios(three, "occlusion")
cmed, cworst = ratios(three, "conservative")
goal("three bunnies, 32 views: median x oracle", med, 1.15, f"conservative {cmed:.3f}; worst {worst:.3f} (conservative {cworst:.3f})")
bunny = rows("bunny")
med, worst = ratios(bunny, "occlusion")
cmed, _ = ratios(bunny, "conservative")
goal("bunny, 32 views: median x oracle", med, 1.15, f"conservative {cmed:.3f}")
dom = rows("dominoes-low-front")
med, _ = ratios(dom, "occlusion")
cmed, _ = ratios(dom, "conservative")
goal("4000 dominoes seen low from the front: x oracle", med, 1.2, f"conservative {cmed:.3f}")
cubes = rows("cubes")
med, worst = vs_conservative(cubes)
goal("cubes (nothing to gain), 32 views: median x conservative", med, 1.03, f"worst view {worst:.3f}")
orbit = rows("orbit")
med, worst = ratios(orbit, "occlusion-ahead")
omed, _ = ratios(orbit, "occlusion")
cmed, _ = ratios(orbit, "conservative")
goal("orbit around three bunnies (48 views): occlusion-ahead, median x oracle", med, 1.1,
     f"worst {worst:.3f}; occlusion {omed:.3f}; conservative {cmed:.3f}")
for name, report in (("three-bunnies", three), ("bunny", bunny), ("dominoes-low-front", dom), ("cubes", cubes),
                     ("orbit", orbit)):
    exact = ("occlusion", "occlusion-ahead")
    misses = sum(m["misses"] for v in report["views"] for m in v["methods"] if m["method"] in exact)
    pixels = sum(m["pixels_differing"] for v in report["views"] for m in v["methods"] if m["method"] in exact)
    goal(f"{name}: misses and pixels differing", misses + pixels, 0, f"{misses} misses, {pixels} pixels")
with open(f"{out}/goals.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=["goal", "measured", "limit", "met", "note"])
    w.writeheader()
    w.writerows(goals)
json.dump(goals, open(f"{out}/goals.json", "w"), indent=2)
for g in goals:
    print(f"{'met    ' if g['met'] else 'NOT MET'}  {g['goal']}: {g['measured']} (limit {g['limit']}) {g['note']}")
PY
