#!/usr/bin/env bash
# The goals of `frugal report`, measured: each scene's report is run twice, two independent runs,
# and their exact picks (settings.json) compared.
#   1. The two picks are the same method, or within 5 % of each other's time: in each run, the two
#      picks' times paired shot by shot and round by round (report.json's "shot_ms"; each shot's
#      median ratio, then their 20 % trimmed geometric mean, as the report pairs a method with the
#      plain render), the slower at most 1.05 times the faster.
#   2. A single-mesh scene (the bunny, drawn double- and single-sided, and glTF's BoxTextured)
#      never gets an order or a no-op as its pick, in either run, exact or within the budget: no
#      pick of the order family, and none whose draws repeat a row it adds to (report.json's
#      "same_draws_as": the plain render's, a no-op, or the cull's a combination adds an order to).
# Also as before: the first run's pick looked up in the second run (its paired ratio to the plain
# render there, and against the fastest exact method there that may be picked, by paired estimate),
# the report's wall time and the page's size.
#   docs/report/run.sh [BUILD_DIR] [OUT_DIR]     (defaults: build, docs/report)
# Writes OUT_DIR/goals.csv and OUT_DIR/goals.json; the reports stay in OUT_DIR/runs/. Exits 1 when a
# goal fails (after writing both files).
set -euo pipefail
build=${1:-build}
out=${2:-docs/report}
mkdir -p "$out/runs"
# name|scene|arguments|single mesh (1: goal 2 applies)
scenes=(
  "bunny|/usr/share/glmark2/models/bunny.obj|--views 32|1"
  "bunny-single-sided|/usr/share/glmark2/models/bunny.obj|--views 32 --cull-backfaces|1"
  "box|/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf|--views 32|1"
  "dominoes|builtin:dominoes|--frames 0:59|0"
  "cubes|builtin:cubes|--frames 0:29|0"
)
names=()
for entry in "${scenes[@]}"; do
  IFS='|' read -r name scene args single <<<"$entry"
  names+=("$name:$single")
  for run in a b; do
    dir="$out/runs/$name-$run"
    start=$EPOCHREALTIME
    # shellcheck disable=SC2086
    "$build/frugal" report "$scene" $args -q -o "$dir" > "$dir.txt"
    end=$EPOCHREALTIME
    /usr/bin/python3 -c "print($end - $start)" > "$dir.seconds"  # (bc is not on every machine)
    echo "$name $run: $(head -1 "$dir.txt") ($(cat "$dir.seconds") s)" >&2
  done
done
/usr/bin/python3 - "$out" "${names[@]}" <<'PY'
import json, math, os, statistics, sys
out, scenes = sys.argv[1], [s.split(":") for s in sys.argv[2:]]

def paired(a, b):
    """Row a's time against row b's, as the report pairs a method with the plain render: per shot
    the median of the rounds' log ratios, then the mean over the shots without the lowest and the
    highest 20 %, exponentiated."""
    shots = sorted(statistics.median(math.log(x / y) for x, y in zip(sa, sb))
                   for sa, sb in zip(a["shot_ms"], b["shot_ms"]))
    cut = int(0.2 * len(shots))
    kept = shots[cut:len(shots) - cut]
    return math.exp(sum(kept) / len(kept))

rows, failed = [], []
for name, single in scenes:
    a = json.load(open(f"{out}/runs/{name}-a/report.json"))
    b = json.load(open(f"{out}/runs/{name}-b/report.json"))
    ra = {r["name"]: r for r in a["rows"]}
    rb = {r["name"]: r for r in b["rows"]}
    pick_a, pick_b = a["recommended"]["exact"], b["recommended"]["exact"]
    # Goal 1: in each run, the slower of the two picks ÷ the faster.
    spread_a = max(paired(ra[pick_a], ra[pick_b]), paired(ra[pick_b], ra[pick_a]))
    spread_b = max(paired(rb[pick_a], rb[pick_b]), paired(rb[pick_b], rb[pick_a]))
    goal1 = pick_a == pick_b or max(spread_a, spread_b) <= 1.05
    # Goal 2: no order and no no-op picked, on a single mesh.
    picks = [(run, rs, run_doc["recommended"][k]) for run, run_doc, rs in (("a", a, ra), ("b", b, rb))
             for k in ("exact", "within_budget")]
    bad = [f"{run}:{p}" for run, rs, p in picks
           if p != "plain" and (rs[p]["family"] == "order" or rs[p]["same_draws_as"] is not None)]
    goal2 = None if single != "1" else not bad
    no_ops = sorted(r["name"] for r in a["rows"] if r["no_op"])
    adds_nothing = sorted(f'{r["name"]} > {r["same_draws_as"]}' for r in a["rows"]
                          if r["same_draws_as"] not in (None, "plain"))
    exact_b = [r for r in b["rows"] if r["exact"] and not r["floor"] and r["same_draws_as"] is None]
    fastest_b = min(exact_b, key=lambda r: r["x_plain_paired"])
    row = {
        "scene": name, "shots": a["shots"], "pick_a": pick_a, "pick_b": pick_b,
        "pick_a_x_plain_a": ra[pick_a]["x_plain_paired"],
        "pick_a_low_a": ra[pick_a]["x_plain_low"],
        "pick_a_high_a": ra[pick_a]["x_plain_high"],
        "pick_b_x_plain_b": rb[pick_b]["x_plain_paired"],
        "pick_b_low_b": rb[pick_b]["x_plain_low"],
        "pick_b_high_b": rb[pick_b]["x_plain_high"],
        "pick_a_x_plain_b": rb[pick_a]["x_plain_paired"],
        "slower_pick_over_faster_a": spread_a,
        "slower_pick_over_faster_b": spread_b,
        "goal_same_or_within_5pct": goal1,
        "goal_single_mesh_no_order_no_op": "n/a" if goal2 is None else goal2,
        "fastest_exact_b": fastest_b["name"],
        "pick_a_over_fastest_exact_b": paired(rb[pick_a], fastest_b),
        "no_ops_a": "; ".join(no_ops),
        "adds_nothing_a": "; ".join(adds_nothing),
        "seconds": float(open(f"{out}/runs/{name}-a.seconds").read()),
        "page_bytes": os.path.getsize(f"{out}/runs/{name}-a/index.html"),
        "backend": a["backend"],
    }
    rows.append(row)
    if not goal1:
        failed.append(f"{name}: picks {pick_a} and {pick_b} differ by {max(spread_a, spread_b):.3f}x (over 1.05)")
    if goal2 is False:
        failed.append(f"{name}: a single mesh picked an order or a no-op: {', '.join(bad)}")
json.dump(rows, open(f"{out}/goals.json", "w"), indent=2)
with open(f"{out}/goals.csv", "w") as f:
    keys = [k for k in rows[0] if k != "backend"]
    f.write(",".join(keys) + "\n")
    for r in rows:
        f.write(",".join(f"{r[k]:.4g}" if isinstance(r[k], float) else str(r[k]).lower() if isinstance(r[k], bool)
                         else str(r[k]) for k in keys) + "\n")
print(open(f"{out}/goals.csv").read(), end="")
for line in failed:
    print("goal failed: " + line, file=sys.stderr)
sys.exit(1 if failed else 0)
PY
