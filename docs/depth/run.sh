#!/usr/bin/env bash
# The figures of docs/depth/README.md: d32f against d24 (frugal-lab bench render, side by side in one
# process), what each format and depth range separates (frugal info), and z-fighting on the
# assimp engine (front surfaces that differ from the d32f render). Needs glmark2-data and
# assimp-testmodels (scripts/install-deps --tests) and a Release build in ../../build.
set -euo pipefail
cd "$(dirname "$0")"
F=../../build/frugal-lab
BUNNY=/usr/share/glmark2/models/bunny.obj
ENGINE=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
for backend in egl software; do
  $F bench render "$BUNNY" --backend $backend --repeat 40 -q > bench-bunny-$backend.json
  $F bench render "$ENGINE" --backend $backend --repeat 40 -q > bench-engine-$backend.json
done
$F info "$ENGINE" | grep -v "^  'Material" > info-engine.txt
# Z-fighting: d24 front surfaces against d32f's, with the file's planes and fitted.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for size in 800x600 1920x1080; do
  $F render "$ENGINE" --size $size --depth-format d32f --ids "$work/d32f.png" -o "$work/c.png" -q 2>/dev/null
  for range in fit file; do
    $F render "$ENGINE" --size $size --depth-range $range --ids "$work/$range.png" -o "$work/c.png" -q 2>/dev/null
    echo "$size $range: $($F compare "$work/$range.png" "$work/d32f.png" | grep 'beyond')"
  done
done > zfight-engine.txt
