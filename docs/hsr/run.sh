#!/bin/sh
# Reproduces the tables of docs/hsr/README.md: frugal-lab hsr-bench on the paper's cubes (at the paper's
# 240x320 and at 1920x1080), the dominoes and the bunny, on the software reference and on llvmpipe
# (EGL surfaceless). Run from this folder after a build; about four minutes on 2 quiet cores.
set -eu
frugal=${FRUGAL:-../../build/frugal-lab}
bunny=/usr/share/glmark2/models/bunny.obj
for backend in software egl; do
    "$frugal" hsr-bench builtin:cubes --frames 0:299 --repeat 3 --backend $backend -q \
        --json cubes-$backend.json --csv cubes-$backend.csv --plot cubes-$backend.svg > cubes-$backend.txt
    "$frugal" hsr-bench builtin:cubes --size 1920x1080 --frames 0:99 --repeat 3 --backend $backend -q \
        --json cubes-hd-$backend.json --csv cubes-hd-$backend.csv > cubes-hd-$backend.txt
    "$frugal" hsr-bench builtin:dominoes --size 800x600 --frames 0:99 --repeat 3 --backend $backend -q \
        --json dominoes-$backend.json --csv dominoes-$backend.csv > dominoes-$backend.txt
    "$frugal" hsr-bench $bunny --cull-backfaces --size 800x600 --frames 0:29 --repeat 3 --backend $backend -q \
        --json bunny-$backend.json --csv bunny-$backend.csv > bunny-$backend.txt
done
# The error masks of depthsort's and the adaptive modes' worst frames on the paper's scene.
"$frugal" hsr-bench builtin:cubes --frames 0:299 --backend software -q --masks masks > /dev/null
