#!/usr/bin/env bash
# The figures of docs/writing.md: `frugal-lab write-bench` on the bunny, the engine and the dominoes at
# 1920x1080 (the encoder table and a 30-frame sequence of the bunny, 3 rounds), the read-back
# experiment on the bunny (30 frames a variant, 9 rounds: readback.json), and one frame in one
# process, `frugal render` of each scene, ROUNDS times, against OLD_FRUGAL when given (a build from
# before the frame writer; the runs alternate).
#
#   docs/writing/run.sh FRUGAL_LAB OUT_DIR [OLD_FRUGAL] [ROUNDS]   (FRUGAL_LAB: build/frugal-lab, which renders too)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: docs/writing/run.sh FRUGAL_LAB OUT_DIR [OLD_FRUGAL] [ROUNDS]" >&2; exit 2; }
frugal=$(realpath "$1"); out=$(realpath "$2"); old=${3:+$(realpath "$3")}; rounds=${4:-10}
bunny=/usr/share/glmark2/models/bunny.obj
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
mkdir -p "$out"
"$frugal" write-bench --scene "$bunny" --scene "$engine" --scene builtin:dominoes --size 1920x1080 \
  --levels 1,2,3,4,5,6,9 --repeat 7 --json "$out/write-bench.json" --csv "$out/write-bench.csv" \
  --plot "$out/write-bench.svg" --readback-frames 0 -q
"$frugal" write-bench --scene "$bunny" --size 1920x1080 --levels 2 --repeat 1 --frames 0 \
  --readback-frames 30 --rounds 9 --json "$out/readback.json" -q

# One frame, one process: the whole run's wall time, median of the rounds.
[ -n "$old" ] || exit 0
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for r in $(seq "$rounds"); do
  for which in old new; do
    bin=$frugal; [ $which = old ] && bin=$old
    for scene in bunny engine dominoes; do
      case $scene in bunny) s=$bunny;; engine) s=$engine;; dominoes) s=builtin:dominoes;; esac
      t0=$(date +%s%N)
      "$bin" render "$s" --size 1920x1080 -o "$work/x.png" -q 2>/dev/null
      t1=$(date +%s%N)
      echo "$which $scene $(( (t1 - t0) / 1000 ))" >> "$work/one.txt"
    done
  done
done
python3 - "$work/one.txt" "$out/one-frame.json" <<'PY'
import json, statistics, sys, collections
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    which, scene, us = line.split()
    runs[(which, scene)].append(int(us) / 1000)
result = {}
for scene in ["bunny", "engine", "dominoes"]:
    old, new = statistics.median(runs[("old", scene)]), statistics.median(runs[("new", scene)])
    result[scene] = {"old_median_ms": old, "new_median_ms": new, "new_over_old": new / old,
                     "rounds": len(runs[("new", scene)])}
json.dump(result, open(sys.argv[2], "w"), indent=2)
print(json.dumps(result, indent=2))
PY
