#!/usr/bin/python3
"""`frugal batch --slurm` on a real Slurm: a private one-node cluster on loopback (cluster.py).

1. A manifest of 9 jobs submitted as a 4-task array and a merge job: every task completes, and the
   merged output is byte for byte what one process gives (`frugal batch` then `batch merge`). One
   job reads the settings.json another writes: both run in one task, the writer first.
2. A task cancelled in the middle of a long job (scancel of one array index): its job has no done
   record and no half-written file is left; submitted again (the scripts run with --resume), the
   batch completes without redoing the jobs that had finished.

  batch_slurm_test.py --frugal BUILD/frugal --out DIR

Exit status: 0 pass, 1 fail, 3 slurm-wlm or munge missing (a skip, unless FRUGAL_TEST_STRICT=1).
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cluster import SlurmCluster, SlurmUnavailable  # noqa: E402

FAILURES = []


def check(condition, what):
    if not condition:
        FAILURES.append(what)
        print("error: " + what, file=sys.stderr)
    return condition


def write_manifest(path, jobs):
    with open(path, "w") as f:
        json.dump({"frugal_batch": 1, "defaults": {"size": "64x48"}, "jobs": jobs}, f, indent=1)


def frugal(args, env=None, cwd=None):
    run = subprocess.run(args, capture_output=True, text=True, env=env, cwd=cwd, timeout=300)
    if run.returncode != 0:
        raise RuntimeError("%s exited %d: %s" % (" ".join(args), run.returncode, run.stderr.strip()))
    return run.stdout


def submit(binary, manifest, out, shards, cluster):
    """`frugal batch --slurm`: (array job id, merge job id)."""
    printed = frugal([binary, "batch", manifest, "--slurm", str(shards), "--out", out], env=cluster.env)
    m = re.match(r"submitted: job array (\d+) \((\d+) shards of (\d+) jobs\), then merge job (\d+);", printed)
    if not m:
        raise RuntimeError("unexpected output of batch --slurm: " + printed)
    return m.group(1), m.group(4)


def states(results):
    return {task: r.state for task, r in results.items()}


def leftovers(folder):
    return [os.path.join(d, f) for d, _, files in os.walk(folder) for f in files if ".tmp-" in f]


def array_then_merge(binary, work, cluster):
    jobs = [{"id": "cubes-%d" % i, "scene": "builtin:cubes?count=%d" % (4 + i), "frames": "0:2",
             "outputs": ["color", "depth", "json"]} for i in range(4)]
    jobs += [{"id": "culled", "scene": "builtin:cubes", "settings": {"cull": "conservative", "order": "key"}},
             {"id": "dominoes", "scene": "builtin:dominoes", "frames": "0:4", "settings": {"reuse": True}},
             {"id": "cull", "command": "cull-report", "scene": "builtin:cubes", "views": 2, "repeat": 1},
             {"id": "report", "command": "report", "scene": "builtin:cubes?count=3", "views": 2, "repeat": 1},
             # Costlier than any job but dominoes: alone it would go to another task than culled.
             {"id": "culled-again", "scene": "builtin:cubes?count=7", "frames": "0:8",
              "settings": "culled/settings.json"}]
    manifest = os.path.join(work, "m.json")
    write_manifest(manifest, jobs)
    single = os.path.join(work, "single")
    frugal([binary, "batch", manifest, "--out", single, "-q"])
    frugal([binary, "batch", "merge", single])

    array = os.path.join(work, "array")
    array_id, merge_id = submit(binary, manifest, array, 4, cluster)
    results = cluster.wait(array_id, timeout=240)
    check(sorted(results) == [0, 1, 2, 3], "array %s: tasks %s, expected 0..3" % (array_id, sorted(results)))
    check(all(r.state == "COMPLETED" for r in results.values()), "array tasks: %s" % states(results))
    merged = cluster.wait(merge_id, timeout=120)
    check(all(r.state == "COMPLETED" for r in merged.values()), "merge job: %s" % states(merged))
    with open(os.path.join(single, "merged.json"), "rb") as a, open(os.path.join(array, "merged.json"), "rb") as b:
        check(a.read() == b.read(), "merged.json of 4 array tasks differs from one process's")
    with_reader = []
    for task in range(4):
        log = os.path.join(array, "slurm", "shard-%d.log" % task)
        if not check(os.path.exists(log), "no log " + log):
            continue
        text = open(log).read()
        writer, reader = text.find("] culled: done"), text.find("] culled-again: done")
        check((writer < 0) == (reader < 0), "task %d ran one of culled and culled-again: %s" % (task, text))
        if reader >= 0:
            with_reader.append(task)
            check(writer < reader, "task %d ran culled-again before culled, whose settings it reads" % task)
    check(len(with_reader) == 1, "culled-again ran in tasks %s, expected one" % with_reader)
    check(not leftovers(array), "temporary files left: %s" % leftovers(array))


def cancel_and_resume(binary, work, cluster):
    # The long job is the costliest: shard 0 takes it first. The short ones spread over both shards.
    jobs = [{"id": "long", "scene": "builtin:dominoes", "frames": "0:3999", "size": "160x120"}]
    jobs += [{"id": "short-%d" % i, "scene": "builtin:cubes?count=%d" % (3 + i)} for i in range(5)]
    manifest = os.path.join(work, "m2.json")
    write_manifest(manifest, jobs)
    out = os.path.join(work, "cancelled")
    array_id, merge_id = submit(binary, manifest, out, 2, cluster)
    started = time.monotonic()
    while not os.path.exists(os.path.join(out, "long", "color_0010.png")):
        if time.monotonic() - started > 120:
            raise RuntimeError("the long job did not start in 2 minutes")
        time.sleep(0.2)
    cluster.run("scancel", "%s_0" % array_id)
    results = cluster.wait(array_id, timeout=120)
    check(results.get(0) is not None and results[0].state == "CANCELLED",
          "scancel of task 0: %s" % states(results))
    check(results.get(1) is not None and results[1].state == "COMPLETED", "task 1: %s" % states(results))
    cluster.wait(merge_id, timeout=120)  # runs after the array, whatever its end; fails: long is not done
    check(not os.path.exists(os.path.join(out, "long", "done.json")), "the cancelled job has a done record")
    check(not os.path.exists(os.path.join(out, "merged.json")), "merged with a job not done")
    check(not leftovers(out), "temporary files left after scancel: %s" % leftovers(out))
    done_before = {}
    for i in range(5):
        path = os.path.join(out, "short-%d" % i, "done.json")
        if os.path.exists(path):
            done_before[path] = (os.stat(path).st_mtime_ns, open(path).read())
    check(len(done_before) >= 1, "no short job finished before the cancel")

    array_id, merge_id = submit(binary, manifest, out, 2, cluster)
    results = cluster.wait(array_id, timeout=240)
    check(all(r.state == "COMPLETED" for r in results.values()), "resubmitted array: %s" % states(results))
    merged = cluster.wait(merge_id, timeout=120)
    check(all(r.state == "COMPLETED" for r in merged.values()), "merge after resubmission: %s" % states(merged))
    check(os.path.exists(os.path.join(out, "merged.json")), "no merged.json after resubmission")
    for path, (mtime, text) in done_before.items():
        check(os.stat(path).st_mtime_ns == mtime and open(path).read() == text, path + " was redone")
    status = frugal([binary, "batch", "status", out])
    check(status.startswith("jobs: 6, done 6, running 0, failed 0, not started 0\n"), "status: " + status)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frugal", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    binary = os.path.abspath(args.frugal)
    work = os.path.abspath(args.out)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    try:
        with SlurmCluster(cpus=2) as cluster:
            array_then_merge(binary, work, cluster)
            cancel_and_resume(binary, work, cluster)
    except SlurmUnavailable as e:
        if os.environ.get("FRUGAL_TEST_STRICT") == "1":
            print("error: %s, and FRUGAL_TEST_STRICT=1 forbids skipping" % e, file=sys.stderr)
            return 1
        print("skip: %s" % e, file=sys.stderr)
        return 3
    except Exception as e:  # a cluster that did not start, a command that failed: one line
        print("error: %s" % e, file=sys.stderr)
        return 1
    if FAILURES:
        return 1
    print("ok: batch on Slurm: 4-task array merged as one process; cancel and resubmit finished the rest")
    return 0


if __name__ == "__main__":
    sys.exit(main())
