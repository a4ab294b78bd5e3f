#!/usr/bin/env bash
# The library's overhead: `frugal render` of two builds side by side, 200 frames of the bunny and of
# builtin:cubes on egl-surfaceless, ROUNDS times, the builds alternating. Prints JSON: per build the
# median per-frame render_ms, readback_ms and write_ms (from the render JSON) and the median wall
# time of the 200 frames, and new ÷ old of each.
#
#   docs/overhead/run.sh OLD_FRUGAL NEW_FRUGAL [ROUNDS]     (OUT=DIR keeps the runs' files there)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: docs/overhead/run.sh OLD_FRUGAL NEW_FRUGAL [ROUNDS]" >&2; exit 2; }
OLD=$(realpath "$1"); NEW=$(realpath "$2"); R=${3:-5}
B=/usr/share/glmark2/models/bunny.obj
out=${OUT:-$(mktemp -d)}; cd "$out"
for r in $(seq $R); do
  for which in old new; do
    bin=$OLD; [ $which = new ] && bin=$NEW
    for scene in bunny cubes; do
      s=$B; [ $scene = cubes ] && s=builtin:cubes
      rm -f f_*.png
      t0=$(date +%s.%N)
      $bin render $s --frames 0:199 --backend egl-surfaceless -o f.png --json $which-$scene-$r.json -q
      t1=$(date +%s.%N)
      echo "$which $scene $r $(echo "$t1 - $t0" | bc)" >> wall.txt
    done
  done
done
python3 - <<'PY'
import json,glob,statistics as st,collections
res=collections.defaultdict(list)
for f in glob.glob('*-*-*.json'):
    which,scene,r=f[:-5].split('-')
    j=json.load(open(f))
    res[(which,scene,'render_ms')]+= [fr['render_ms'] for fr in j['frames']]
    res[(which,scene,'readback_ms')]+= [fr['readback_ms'] for fr in j['frames']]
    res[(which,scene,'write_ms')]+= [fr['write_ms'] for fr in j['frames']]
wall=collections.defaultdict(list)
for line in open('wall.txt'):
    which,scene,r,t=line.split(); wall[(which,scene)].append(float(t))
out={}
for scene in ['bunny','cubes']:
    d={}
    for k in ['render_ms','readback_ms','write_ms']:
        o=st.median(res[('old',scene,k)]); n=st.median(res[('new',scene,k)])
        d[k]={'old_median':o,'new_median':n,'new_over_old':n/o if o else None}
    o=st.median(wall[('old',scene)]); n=st.median(wall[('new',scene)])
    d['wall_s_200_frames']={'old_median':o,'new_median':n,'new_over_old':n/o}
    out[scene]=d
print(json.dumps(out,indent=2))
PY
