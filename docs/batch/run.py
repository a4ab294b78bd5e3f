#!/usr/bin/python3
"""What sharding costs: a 200-job manifest run in one process on one core, then as N shards on N
cores at once (N = the cores here), each pinned with taskset; and what merging costs.

  docs/batch/run.py [BUILD_DIR] [OUT_DIR]      (defaults: build, docs/batch)

Goal (issue 22): the shards' wall time at most 1.1x the one process's divided by N. Every job renders
with one rasterizer thread (settings "threads": 1), so a core is a core. Writes OUT_DIR/overhead.json
and overhead.csv; the runs themselves go to a temporary folder.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

build = sys.argv[1] if len(sys.argv) > 1 else "build"
out_dir = sys.argv[2] if len(sys.argv) > 2 else "docs/batch"
frugal = os.path.abspath(os.path.join(build, "frugal"))
cores = len(os.sched_getaffinity(0))
work = tempfile.mkdtemp(prefix="frugal-batch-bench.")


def manifest(path, count=200):
    jobs = []
    for i in range(count):
        kind = i % 4
        if kind == 0:
            jobs.append({"scene": "builtin:cubes?count=%d" % (8 + i % 40), "frames": "0:%d" % (2 + i % 7)})
        elif kind == 1:
            jobs.append({"scene": "builtin:dominoes?polygons=%d" % (204 + 12 * (i % 50)), "frames": "0:%d" % (3 + i % 5),
                         "settings": {"threads": 1, "reuse": True}})
        elif kind == 2:
            jobs.append({"scene": "builtin:default", "camera": {"eye": [0.3 * (i % 9), 1, 4], "target": [0, 0, 0]}})
        else:
            jobs.append({"scene": "builtin:materials", "settings": {"threads": 1, "order": "key"},
                         "outputs": ["color", "depth", "ids", "json"]})
    doc = {"frugal_batch": 1, "defaults": {"size": "320x240", "settings": {"threads": 1}}, "jobs": jobs}
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)


def timed(commands):
    """Starts every command at once; the wall time until the last one ends."""
    start = time.monotonic()
    procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for c in commands]
    for p, c in zip(procs, commands):
        _, err = p.communicate()
        if p.returncode != 0:
            sys.exit("error: %s exited %d: %s" % (" ".join(c), p.returncode, err.decode().strip()))
    return time.monotonic() - start


m = os.path.join(work, "m.json")
manifest(m)
rounds = []
for r in range(3):  # alternating, so that the machine's drift hits both
    one = timed([["taskset", "-c", "0", frugal, "batch", m, "--out", os.path.join(work, "one-%d" % r), "-q"]])
    shards = timed([["taskset", "-c", str(i), frugal, "batch", m, "--shard", "%d/%d" % (i, cores),
                     "--out", os.path.join(work, "n-%d" % r), "-q"] for i in range(cores)])
    merge = timed([[frugal, "batch", "merge", os.path.join(work, "n-%d" % r)]])
    rounds.append({"one_process_s": one, "shards_s": shards, "merge_s": merge,
                   "ratio": shards / (one / cores)})
    print("round %d: one process %.2f s, %d shards %.2f s, ratio %.3f, merge %.3f s"
          % (r, one, cores, shards, rounds[-1]["ratio"], merge), file=sys.stderr)
subprocess.run([frugal, "batch", "merge", os.path.join(work, "one-0")], check=True, stdout=subprocess.DEVNULL)
identical = open(os.path.join(work, "one-0", "merged.json"), "rb").read() == \
    open(os.path.join(work, "n-0", "merged.json"), "rb").read()
files = sum(len(fs) for _, _, fs in os.walk(os.path.join(work, "n-0")))
frames = sum(1 for d, _, fs in os.walk(os.path.join(work, "n-0")) for f in fs if f.startswith("color"))
ratios = sorted(x["ratio"] for x in rounds)
summary = {"jobs": 200, "cores": cores, "frames": frames, "files": files,
           "manifest_bytes": os.path.getsize(m),
           "median_ratio": ratios[len(ratios) // 2], "goal_ratio": 1.1,
           "merged_identical": identical, "rounds": rounds,
           "merge_ms_per_file": 1000 * sorted(x["merge_s"] for x in rounds)[1] / files}
os.makedirs(out_dir, exist_ok=True)
with open(os.path.join(out_dir, "overhead.json"), "w") as f:
    json.dump(summary, f, indent=2)
with open(os.path.join(out_dir, "overhead.csv"), "w") as f:
    f.write("round,one_process_s,shards_s,ratio,merge_s\n")
    for i, x in enumerate(rounds):
        f.write("%d,%.3f,%.3f,%.4f,%.3f\n" % (i, x["one_process_s"], x["shards_s"], x["ratio"], x["merge_s"]))
print(json.dumps({k: v for k, v in summary.items() if k != "rounds"}, indent=2))
shutil.rmtree(work)
