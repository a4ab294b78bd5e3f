#!/bin/sh
# Reproduces the tables of docs/hsr/README.md: frugal hsr-bench on the paper's cubes, the dominoes
# and the bunny, on the software reference and on llvmpipe, one run each. Run from this folder
# after a build (scripts/build or the README's commands); takes about two minutes on 2 cores.
set -eu
frugal=${FRUGAL:-../../build/frugal}
bunny=/usr/share/glmark2/models/bunny.obj
for backend in software egl; do
    "$frugal" hsr-bench builtin:cubes --frames 0:299 --backend $backend -q \
        --json cubes-$backend.json --csv cubes-$backend.csv --plot cubes-$backend.svg > cubes-$backend.txt
    "$frugal" hsr-bench builtin:dominoes --size 800x600 --frames 0:99 --backend $backend -q \
        --json dominoes-$backend.json --csv dominoes-$backend.csv > dominoes-$backend.txt
    "$frugal" hsr-bench $bunny --cull-backfaces --size 800x600 --frames 0:29 --backend $backend -q \
        --json bunny-$backend.json --csv bunny-$backend.csv > bunny-$backend.txt
done
"$frugal" hsr-bench builtin:cubes --frames 0:299 --backend software -q --masks masks > /dev/null
