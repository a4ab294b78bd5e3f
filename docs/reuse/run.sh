#!/bin/sh
# Re-measures everything in this folder (README.md quotes it): reuse-bench runs with their JSON, CSV,
# gnuplot script and SVG, the grain and cell tables, and the plan micro-benchmark. Run it from
# this folder on a quiet machine, after building frugal (scripts/demo) and the micro-benchmark
# (cmake -DFRUGAL_BUILD_BENCH=ON). About four minutes on 2 cores.
set -eu
B=../../build/frugal-lab
bench() {
    name=$1; shift
    "$B" reuse-bench "$@" --repeat 7 --json "$name.json" --csv "$name.csv" --plot "$name.svg" --quiet > "$name.txt"
}
# Paper 000's two scenes at their steady state (804: 60 of 134 dominoes falling from frame 59 on;
# 1,404: 3 of 234 from frame 2 on), and the first 70 frames of the 804 one, where the number
# falling rises from 1 to 60: the speed-up against the static share.
bench d804-software 'builtin:dominoes?polygons=804&static=0.5544' --frames 70:119 --backend software --size 640x480
bench d1404-software 'builtin:dominoes?polygons=1404&static=0.9866' --frames 0:49 --backend software --size 640x480
bench d804-llvmpipe 'builtin:dominoes?polygons=804&static=0.5544' --frames 70:119 --size 640x480
bench d1404-llvmpipe 'builtin:dominoes?polygons=1404&static=0.9866' --frames 0:49 --size 640x480
bench d804-ramp-software 'builtin:dominoes?polygons=804&static=0.5544' --frames 0:69 --backend software --size 640x480
bench d804-exact-static-software 'builtin:dominoes?polygons=804&static=0.5544' --frames 70:119 --backend software --size 640x480 --exact-static
# The large scene: 10,000 dominoes (120,000 triangles), 134 falling, 1920×1080.
bench large-llvmpipe 'builtin:dominoes?polygons=60000&static=0.9866' --frames 140:159 --size 1920x1080
bench large-exact-static-llvmpipe 'builtin:dominoes?polygons=60000&static=0.9866' --frames 140:159 --size 1920x1080 --exact-static
bench large-software 'builtin:dominoes?polygons=60000&static=0.9866' --frames 140:159 --size 1920x1080 --backend software
# Everything dynamic: 200 spinning cubes.
bench cubes-llvmpipe 'builtin:cubes?count=200' --frames 0:29
bench cubes-software 'builtin:cubes?count=200' --frames 0:29 --backend software

# The extents' grain and the grid's cell on the bunny circled by 32 cubes that start and stop.
orbit='builtin:orbit?count=32&duty=0.5&of=/usr/share/glmark2/models/bunny.obj'
table() {  # $1 = option, $2.. = values
    option=$1; shift
    echo "| backend | $option | full ms | reuse ms | oracle ms | plan ms | static triangles redrawn | pixels copied | speed-up |"
    echo "|---|---|---|---|---|---|---|---|---|"
    for value in "$@"; do
        for backend in egl-surfaceless software; do
            "$B" reuse-bench "$orbit" --frames 0:59 --backend $backend --repeat 3 "$option" "$value" --quiet \
                --json orbit.tmp.json > /dev/null
            python3 - "$backend" "$value" <<'PY'
import json, statistics as st, sys
d = json.load(open('orbit.tmp.json'))
fr = [f for f in d['frames'] if f['mode'] == 'reuse']
m = lambda k: st.median(f[k] for f in fr)
a = lambda k: st.mean(f[k] for f in fr)
print('| %s | %s | %.2f | %.2f | %.2f | %.3f | %d | %d | %.1f |' % (sys.argv[1], sys.argv[2], m('full_ms'), m('reuse_ms'),
      m('oracle_ms'), m('plan_ms'), round(a('static_redrawn_tris')), round(a('copied_px')), m('full_ms') / m('reuse_ms')))
PY
        done
    done
    rm -f orbit.tmp.json
}
table --reuse-grain 0 1 4 16 64 256 > grain.md
table --reuse-cell 4 8 16 32 64 > cell.md
../../build/bench/frugal_microbench --benchmark_filter=ReusePlan --benchmark_repetitions=5 \
    --benchmark_report_aggregates_only=true > plan-microbench.txt
