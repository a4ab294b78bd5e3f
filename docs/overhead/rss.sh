#!/usr/bin/env bash
# Resident memory of one long `frugal render` sequence: builtin:cubes at 64x48, frames 0:99999, every
# frame written as PNG and recorded in the render JSON, VmRSS sampled twice a second. Writes
# frame,rss_kb lines to stdout. Needs about 1 GB of disk for the frames (deleted at the end).
#
#   docs/overhead/rss.sh [FRUGAL] > rss-100k.csv
set -euo pipefail
frugal=$(realpath "${1:-build/frugal}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
"$frugal" render builtin:cubes --size 64x48 --frames 0:99999 -o f.png --json j.json 2> progress.txt &
pid=$!
echo "frame,rss_kb"
while kill -0 $pid 2>/dev/null; do
  rss=$(awk '/VmRSS/{print $2}' /proc/$pid/status 2>/dev/null || true)
  frame=$(tail -c 200 progress.txt | tr '\r' '\n' | grep -o "frame [0-9]*" | tail -1 | cut -d' ' -f2 || true)
  [ -n "$rss" ] && [ -n "$frame" ] && echo "$frame,$rss"
  sleep 0.5
done
wait $pid
