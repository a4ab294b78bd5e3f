#!/usr/bin/python3
"""Self-test of tests/slurm/cluster.py: start a private Slurm cluster, run job
arrays, a failing job, a cancel of one array index and a dependent job, stop
it, and check that nothing it started is left.

Exit 0: all passed. 1: a check failed (see the `error:` lines). 3: Slurm or
munge not installed (skip), unless FRUGAL_TEST_STRICT=1, where that is a
failure too. Takes ~15-25 s.
"""

import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cluster import SlurmCluster, SlurmError, SlurmUnavailable, find_leftover_processes  # noqa: E402

T0 = time.monotonic()
passed = []
failed = []


def log(msg):
    print("[%5.1fs] %s" % (time.monotonic() - T0, msg), flush=True)


def check(name, ok, detail=""):
    if ok:
        passed.append(name)
        log("ok: " + name)
    else:
        failed.append(name)
        print("error: %s%s" % (name, (": " + detail) if detail else ""), flush=True)
    return ok


def wait_for(pred, timeout, poll=0.2):
    """Poll pred() until it returns a true value or timeout passes; returns its last value."""
    deadline = time.monotonic() + timeout
    while True:
        value = pred()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(poll)


# Array task: record its index, take a moment so the dependent job really has to wait.
ARRAY_SCRIPT = """#!/bin/sh
echo "$SLURM_ARRAY_TASK_ID" > "{out}/task_$SLURM_ARRAY_TASK_ID.tmp"
sleep 1
mv "{out}/task_$SLURM_ARRAY_TASK_ID.tmp" "{out}/task_$SLURM_ARRAY_TASK_ID"
"""

# Dependent job: list which array outputs were complete when it started.
DEP_SCRIPT = """#!/bin/sh
cd "{out}" && ls task_* > dep_saw.tmp && mv dep_saw.tmp dep_saw
"""


def run_checks(c, out):
    # 1. A 4-task array and a job that depends on it (afterany), submitted together.
    array = c.sbatch(["--array=0-3", "-o", out + "/array_%A_%a.log"], ARRAY_SCRIPT.format(out=out))
    dep = c.sbatch(["--dependency=afterany:%d" % array, "-o", out + "/dep_%j.log"],
                   DEP_SCRIPT.format(out=out))
    # A job that fails with exit status 3, to see exit codes come through.
    bad = c.sbatch(["-o", "/dev/null", "--wrap", "exit 3"])
    log("submitted array %d, dependent %d, failing %d" % (array, dep, bad))

    res = c.wait(array, timeout=40)
    check("array has tasks 0..3", sorted(res) == [0, 1, 2, 3], repr(sorted(res)))
    check("array tasks COMPLETED with exit 0",
          all(r.state == "COMPLETED" and r.exit_code == 0 for r in res.values()), repr(res))
    contents = {}
    for i in range(4):
        try:
            with open(os.path.join(out, "task_%d" % i)) as f:
                contents[i] = f.read().strip()
        except OSError as e:
            contents[i] = str(e)
    check("array wrote files task_0..task_3 with their ids",
          contents == {i: str(i) for i in range(4)}, repr(contents))

    res = c.wait(dep, timeout=30)
    check("dependent job COMPLETED", res[None].state == "COMPLETED", repr(res))
    try:
        with open(os.path.join(out, "dep_saw")) as f:
            saw = f.read().split()
    except OSError as e:
        saw = [str(e)]
    check("dependent job ran after every array task", saw == ["task_%d" % i for i in range(4)], repr(saw))

    res = c.wait(bad, timeout=30)
    check("failing job is FAILED with exit code 3",
          res[None].state == "FAILED" and res[None].exit_code == 3, repr(res))

    # 2. Cancel one index of a running array.
    sleepers = c.sbatch(["--array=0-1", "-o", "/dev/null", "--wrap", "sleep 30"])
    running = wait_for(lambda: all(r.state == "RUNNING" for r in c.job_states(sleepers).values())
                       and len(c.job_states(sleepers)) == 2, timeout=20)
    check("array %d: both tasks RUNNING" % sleepers, running, repr(c.job_states(sleepers)))
    c.run("scancel", "%d_1" % sleepers)
    cancelled = wait_for(lambda: c.job_states(sleepers).get(1).state == "CANCELLED", timeout=15)
    states = c.job_states(sleepers)
    check("scancel %d_1: index 1 CANCELLED" % sleepers, cancelled, repr(states))
    check("scancel %d_1: index 0 still RUNNING" % sleepers,
          states.get(0) is not None and states[0].state == "RUNNING", repr(states))
    c.run("scancel", str(sleepers))
    res = c.wait(sleepers, timeout=20)
    check("array %d ended after scancel" % sleepers, sorted(r.state for r in res.values()) ==
          ["CANCELLED", "CANCELLED"], repr(res))

    # The jobcomp file holds the same final states (it outlives MinJobAge).
    comp = c.jobcomp_results(array)
    check("jobcomp file records the 4 array tasks",
          sorted(comp) == [0, 1, 2, 3] and all(r.state == "COMPLETED" for r in comp.values()), repr(comp))


def main():
    strict = os.environ.get("FRUGAL_TEST_STRICT") == "1"
    cluster = None
    try:
        with tempfile.TemporaryDirectory(prefix="frugal-slurm-out-") as out:
            os.chmod(out, 0o755)
            with SlurmCluster(cpus=2) as c:
                cluster = c
                log("cluster %s up in %s (node %s, ports %d/%d, pids %s)"
                    % (c.cluster_name, c.path, c.hostname, c.ctld_port, c.slurmd_port, c.pids))
                run_checks(c, out)
                t_stop = time.monotonic()
            log("cluster stopped in %.1fs" % (time.monotonic() - t_stop))
    except SlurmUnavailable as e:
        if strict:
            print("error: Slurm unavailable and FRUGAL_TEST_STRICT=1: %s" % e)
            print("slurm-selftest: 0 passed, 1 failed")
            return 1
        print("skip: Slurm unavailable: %s" % e)
        print("slurm-selftest: 0 passed, 0 failed, 1 skipped")
        return 3
    except (SlurmError, OSError, AttributeError, KeyError) as e:
        check("no exception", False, "%s: %s" % (type(e).__name__, e))

    # 3. Nothing may be left: daemons reaped, no process carrying the cluster's
    #    marker (slurmstepd, job scripts), folder removed.
    if cluster is not None:
        alive = []
        for name, pid in getattr(cluster, "pids", {}).items():
            try:
                os.kill(pid, 0)
                alive.append("%s(%d)" % (name, pid))
            except ProcessLookupError:
                pass
        check("slurmctld, slurmd, munged are gone", not alive, " ".join(alive))
        left = find_leftover_processes(cluster.path)
        check("no process of the cluster left", not left, repr(left))
        check("cluster folder removed", not os.path.exists(cluster.path), cluster.path)

    log("done")
    print("slurm-selftest: %d passed, %d failed" % (len(passed), len(failed)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
