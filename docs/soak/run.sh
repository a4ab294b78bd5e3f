#!/bin/sh
# Reproduces docs/soak/README.md. Run from this folder after a build, under `nice` when the machine
# is shared; about 6 minutes on 2 cores.
#   soak          `frugal-lab soak` with its defaults: builtin:cubes at 64x48, 100,000 frames and 1,000
#                 create/destroy cycles of each kind (backend, target, scene) on every backend
#   long-egl-ids  200,000 frames with triangle ids on llvmpipe (EGL surfaceless): past the 131,042
#                 renders after which other offscreen renderers are reported to draw blank frames
#   minimal       the same 100,000 frames drawn by the minimal GL program (no frugal code in the
#                 loop): what Mesa alone does with memory
set -eu
frugal=${FRUGAL:-../../build/frugal-lab}
nice -n 10 "$frugal" soak -q --json soak.json --csv soak.csv --plot soak.png > soak.txt
nice -n 10 "$frugal" soak --backend egl-surfaceless --ids --frames 0:199999 --cycles 0 -q \
    --json long-egl-ids.json --csv long-egl-ids.csv --plot long-egl-ids.png > long-egl-ids.txt
nice -n 10 "$frugal" soak --minimal -q --json minimal.json --csv minimal.csv --plot minimal.png > minimal.txt
