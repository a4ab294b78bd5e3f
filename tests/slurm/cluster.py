"""A private, throw-away one-node Slurm cluster on loopback, for tests.

    from cluster import SlurmCluster, SlurmUnavailable

    try:
        with SlurmCluster(cpus=2) as c:
            job = c.sbatch(["--array=0-3", "-o", "/dev/null"], "#!/bin/sh\ntrue\n")
            results = c.wait(job, timeout=60)   # {0: JobResult(...), 1: ..., ...}
            subprocess.run(["squeue"], env=c.env)
    except SlurmUnavailable:
        sys.exit(3)                             # skip: slurm-wlm / munge not installed

Everything the cluster uses lives in one temporary folder: munge key, socket
and seed, slurm.conf, state and spool folders, pid and log files. The TCP ports
are chosen at start. /etc/slurm, /etc/munge and the system munge socket are never
read, so several clusters (and a system Slurm, if any) can run side by side.

Debian 12 packages: slurm-wlm (22.05.8) and munge (0.5.15). Must run as root
(slurmd runs jobs as the submitting user and SlurmUser=root here).

Standard library only; run with /usr/bin/python3.
"""

import atexit
import ctypes
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from collections import namedtuple

__all__ = ["SlurmCluster", "SlurmUnavailable", "SlurmError", "JobResult",
           "TERMINAL_STATES", "find_leftover_processes"]


class SlurmUnavailable(Exception):
    """Slurm or munge is not installed (or we are not root): callers skip (exit 3)."""


class SlurmError(Exception):
    """The cluster failed to start, a command failed, or a wait timed out."""


# One finished (or, from job_states(), current) job or array task.
#   job_id:    Slurm's own id of this record (array tasks get their own ids)
#   array_id:  ArrayJobId, or None for a plain job
#   task_id:   ArrayTaskId as int, or None for a plain job
#   state:     JobState, e.g. COMPLETED, FAILED, CANCELLED, TIMEOUT, RUNNING
#   exit_code: the batch script's exit status (first half of ExitCode=a:b)
#   signal:    the signal that ended it, 0 if none (second half of ExitCode)
#   reason:    Reason=..., e.g. None, NonZeroExitCode, Dependency
JobResult = namedtuple("JobResult", "job_id array_id task_id state exit_code signal reason")

# States in which a job/task has left the queue for good.
TERMINAL_STATES = frozenset([
    "COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "PREEMPTED",
    "BOOT_FAIL", "DEADLINE", "OUT_OF_MEMORY", "REVOKED", "SPECIAL_EXIT",
])

# Binaries we need; the daemons live in /usr/sbin, which a non-login PATH may lack.
_DAEMONS = ("munged", "slurmctld", "slurmd")
_CLIENTS = ("munge", "unmunge", "sbatch", "squeue", "scancel", "scontrol", "sinfo")
_SEARCH_PATH = os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/usr/bin", "/sbin", "/bin"])

# Environment variable put into the daemons' and the jobs' environment; its value
# (the cluster's folder) lets stop() find and kill anything the cluster started,
# including slurmstepd and job processes that outlived slurmd.
_MARKER = "FRUGAL_SLURM_CLUSTER"

# Unix socket paths must fit in sun_path (108 bytes); slurmd also puts step
# sockets "<spool>/<node>_<job>.<step>" there, so leave room.
_MAX_DIR_LEN = 70

_PR_SET_PDEATHSIG = 1


def _which(name):
    return shutil.which(name, path=_SEARCH_PATH)


def _free_port():
    """A TCP port that is free right now (the kernel picks it when binding port 0)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _tail(path, lines=25):
    try:
        with open(path, "r", errors="replace") as f:
            text = f.read().splitlines()
    except OSError:
        return "(no %s)" % path
    return "\n".join(["--- %s (last %d lines) ---" % (path, lines)] + text[-lines:])


def _expand_task_ids(spec):
    """'3' -> [3]; '0-3' -> [0,1,2,3]; '1,4-6:2%2' -> [1,4,6]. Pending tasks
    are shown by scontrol as one record with such a range."""
    ids = []
    spec = spec.split("%")[0]
    for part in spec.split(","):
        if not part:
            continue
        step = 1
        if ":" in part:
            part, step = part.split(":")
            step = int(step)
        if "-" in part:
            lo, hi = part.split("-")
            ids.extend(range(int(lo), int(hi) + 1, step))
        else:
            ids.append(int(part))
    return ids


def _parse_record(line):
    """Parse one 'Key=Value Key=Value ...' line (scontrol -o / jobcomp filetxt)."""
    rec = {}
    for m in re.finditer(r"(\S+?)=(\S*)", line):
        rec.setdefault(m.group(1), m.group(2))
    return rec


def _records_to_results(records):
    """Turn parsed job records into {task_id: JobResult} (task_id None for a plain job)."""
    out = {}
    for rec in records:
        code, _, sig = rec.get("ExitCode", "0:0").partition(":")
        array_id = rec.get("ArrayJobId")
        tasks = rec.get("ArrayTaskId")
        task_ids = _expand_task_ids(tasks) if (array_id and tasks) else [None]
        for tid in task_ids:
            out[tid] = JobResult(
                job_id=int(rec["JobId"]),
                array_id=int(array_id) if array_id else None,
                task_id=tid,
                state=rec.get("JobState", "UNKNOWN"),
                exit_code=int(code or 0),
                signal=int(sig or 0),
                reason=rec.get("Reason"),
            )
    return out


def _proc_environ_has(pid, needle):
    try:
        with open("/proc/%d/environ" % pid, "rb") as f:
            return needle in f.read().split(b"\0")
    except OSError:
        return False


def find_leftover_processes(workdir):
    """PIDs of live processes that carry this cluster's marker in their
    environment (daemons, slurmstepd, job scripts). Empty after stop()."""
    needle = ("%s=%s" % (_MARKER, workdir)).encode()
    me = os.getpid()
    pids = []
    for name in os.listdir("/proc"):
        if name.isdigit() and int(name) != me and _proc_environ_has(int(name), needle):
            try:
                with open("/proc/%s/stat" % name) as f:
                    if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                        continue  # a zombie is dead; its parent just has not reaped it
            except (OSError, IndexError):
                continue
            pids.append(int(name))
    return pids


def _kill_marked(workdir, rounds=50):
    """SIGKILL every process carrying workdir's marker until none is left."""
    for _ in range(rounds):
        left = find_leftover_processes(workdir)
        if not left:
            return
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        time.sleep(0.1)


def _guard_main(workdir, keep):
    """Body of the watchdog process (see SlurmCluster._start_guard)."""
    def cleanup(*_):
        _kill_marked(workdir)
        if not keep:
            shutil.rmtree(workdir, ignore_errors=True)
        os._exit(0)
    signal.signal(signal.SIGTERM, cleanup)
    signal.signal(signal.SIGHUP, signal.SIG_IGN)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    data = sys.stdin.buffer.read()          # EOF when the owner exits, however it dies
    if data != b"done":
        cleanup()


class SlurmCluster:
    """Context manager: a one-node Slurm cluster (slurmctld + slurmd + munged)
    on 127.0.0.1, all files in a temporary folder.

    workdir:    folder to use (created; must be short, see _MAX_DIR_LEN);
                default: a new tempfile.mkdtemp() folder.
    cpus:       CPUs the node advertises (may exceed the real core count).
    keep:       leave the folder in place after stop() (for debugging).
    start_timeout: seconds to wait for the node to become idle.
    die_with_parent: daemons get SIGKILL if the thread that started them dies
                (Linux PR_SET_PDEATHSIG), so a killed test leaves no daemons.
                Start the cluster from a thread that outlives it (e.g. main).

    Attributes after start: path, conf, env (pass to subprocess calls),
    hostname, cluster_name, ctld_port, slurmd_port, pids ({daemon: pid}).
    start() / stop() work without `with` too (stop() also runs at exit).
    """

    def __init__(self, workdir=None, cpus=2, keep=False, start_timeout=60.0,
                 die_with_parent=True, memory_mb=1024):
        self.cpus = int(cpus)
        self.keep = keep
        self.start_timeout = start_timeout
        self.die_with_parent = die_with_parent
        self.memory_mb = int(memory_mb)
        self._requested_dir = workdir
        self._made_dir = False
        self._procs = {}            # daemon name -> Popen, in start order
        self._old_handlers = {}
        self._stopped = True
        self._grace = 5.0           # seconds between SIGTERM and SIGKILL in stop()
        self.path = None
        self.env = None

    # ------------------------------------------------------------------ setup

    def _check_installed(self):
        self.bin = {}
        missing = []
        for name in _DAEMONS + _CLIENTS:
            p = _which(name)
            if p is None:
                missing.append(name)
            self.bin[name] = p
        if missing:
            raise SlurmUnavailable("not installed: %s (apt-get install slurm-wlm munge)"
                                   % " ".join(missing))
        if os.geteuid() != 0:
            raise SlurmUnavailable("the private Slurm cluster needs root (slurmd runs jobs as root here)")

    def _make_env(self):
        env = {k: v for k, v in os.environ.items()
               # Drop inherited Slurm settings (e.g. when the test itself runs
               # inside a Slurm job): SLURM_JOB_ID & co. would confuse sbatch.
               if not k.startswith(("SLURM_", "SBATCH_", "SQUEUE_", "SINFO_", "SCANCEL_",
                                    "SCONTROL_", "SRUN_", "SALLOC_", "MUNGE_"))}
        dirs = env.get("PATH", "").split(os.pathsep)
        for p in self.bin.values():
            d = os.path.dirname(p)
            if d not in dirs:
                dirs.append(d)
        env["PATH"] = os.pathsep.join(x for x in dirs if x)
        env["SLURM_CONF"] = self.conf
        env[_MARKER] = self.path
        return env

    def _preexec(self):
        # Own session: terminal ^C goes to the test, not the daemons, and each
        # daemon's process group can be killed as a whole.
        os.setsid()
        if self.die_with_parent:
            try:
                libc = ctypes.CDLL(None, use_errno=True)
                libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
            except Exception:
                pass

    def _spawn(self, name, argv):
        log = open(os.path.join(self.path, name + ".stderr"), "wb")
        try:
            self._procs[name] = subprocess.Popen(
                argv, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                env=self.env, cwd=self.path, preexec_fn=self._preexec, close_fds=True)
        finally:
            log.close()

    def _fail(self, message, *logs):
        tails = "\n".join(_tail(p) for p in logs)
        raise SlurmError("%s\n%s" % (message, tails))

    def _start_munge(self):
        key = os.path.join(self.path, "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o600)  # munged refuses a key readable by others
        self.munge_socket = os.path.join(self.path, "munge.socket")
        self._spawn("munged", [
            self.bin["munged"],
            "--foreground",       # stay a child we can reap; logs go to stderr then
            "--force",            # warn instead of refusing on loose permissions of the folders above
            "--key-file=" + key,
            "--socket=" + self.munge_socket,
            "--pid-file=" + os.path.join(self.path, "munged.pid"),
            "--log-file=" + os.path.join(self.path, "munged.log"),   # unused with -F, keeps /var/log out
            "--seed-file=" + os.path.join(self.path, "munged.seed"),
        ])
        errlog = os.path.join(self.path, "munged.stderr")
        deadline = time.monotonic() + 15
        while not os.path.exists(self.munge_socket):
            if self._procs["munged"].poll() is not None:
                self._fail("munged exited with %s" % self._procs["munged"].returncode, errlog)
            if time.monotonic() > deadline:
                self._fail("munged did not create its socket in 15 s", errlog)
            time.sleep(0.05)
        # Round trip: encode and decode a credential through our socket only.
        enc = subprocess.run([self.bin["munge"], "-n", "-S", self.munge_socket],
                             capture_output=True, env=self.env, timeout=15)
        dec = subprocess.run([self.bin["unmunge"], "-S", self.munge_socket], input=enc.stdout,
                             capture_output=True, env=self.env, timeout=15)
        if enc.returncode != 0 or dec.returncode != 0 or b"Success" not in dec.stdout:
            self._fail("munge self-check failed: %s %s" % (enc.stderr.decode(errors="replace"),
                                                          dec.stderr.decode(errors="replace")), errlog)

    def _write_conf(self):
        p = self.path
        os.makedirs(os.path.join(p, "state"), exist_ok=True)
        os.makedirs(os.path.join(p, "spool"), exist_ok=True)
        # Empty SPANK plug-in list: the default PlugStackConfig is /etc/slurm/plugstack.conf.
        with open(os.path.join(p, "plugstack.conf"), "w") as f:
            f.write("# no SPANK plug-ins\n")
        lines = [
            "# Generated by tests/slurm/cluster.py: a private one-node cluster on loopback.",
            "ClusterName=%s" % self.cluster_name,        # must be lower case
            # slurmctld only runs if this name is its own short hostname; the
            # (addr) part makes everyone reach it on loopback without DNS.
            "SlurmctldHost=%s(127.0.0.1)" % self.hostname,
            "SlurmctldPort=%d" % self.ctld_port,
            "SlurmdPort=%d" % self.slurmd_port,
            # Authenticate through our munged only (cred/munge reads the same AuthInfo).
            "AuthType=auth/munge",
            "AuthInfo=socket=%s" % self.munge_socket,
            "CredType=cred/munge",
            "SlurmUser=root",
            "SlurmdUser=root",
            "StateSaveLocation=%s/state" % p,
            "SlurmdSpoolDir=%s/spool" % p,
            "SlurmctldPidFile=%s/slurmctld.pid" % p,
            "SlurmdPidFile=%s/slurmd.pid" % p,
            "SlurmctldLogFile=%s/slurmctld.log" % p,
            "SlurmdLogFile=%s/slurmd.log" % p,
            "PlugStackConfig=%s/plugstack.conf" % p,
            # Every finished job and array task gets one line here (JobState,
            # ExitCode, ArrayJobId, ArrayTaskId): a record that outlives
            # MinJobAge, since sacct needs slurmdbd, which we do not run.
            "JobCompType=jobcomp/filetxt",
            "JobCompLoc=%s/jobcomp.txt" % p,
            "AccountingStorageType=accounting_storage/none",
            "JobAcctGatherType=jobacct_gather/none",
            # No cgroups: linuxproc tracks job processes by parentage, task/none
            # binds nothing. So no cgroup.conf is needed, even in a container.
            "ProctrackType=proctrack/linuxproc",
            "TaskPlugin=task/none",
            "MpiDefault=none",
            "SchedulerType=sched/backfill",
            # Schedule newly submitted batch jobs at once instead of batching
            # submissions for up to 3 s (the default batch_sched_delay).
            "SchedulerParameters=batch_sched_delay=0",
            "SelectType=select/cons_tres",
            "SelectTypeParameters=CR_Core",       # one array task per CPU
            # Use the CPUs/RealMemory below instead of what slurmd detects, so
            # cpus may exceed the real core count and the node is never drained
            # for "low socket*core*thread count".
            "SlurmdParameters=config_overrides",
            "ReturnToService=2",                  # a DOWN node comes back as soon as it registers
            "MinJobAge=300",                      # finished jobs stay in `scontrol show job` 5 min
            "MaxArraySize=1001",                  # task ids 0..1000
            "KillWait=2",                         # SIGTERM -> SIGKILL grace for scancel/timeouts (default 30 s)
            "MailProg=/bin/true",                 # never try to send mail
            # One socket of `cpus` single-thread cores: with only CPUs=N Slurm
            # would invent N sockets of one core.
            "NodeName=%s NodeAddr=127.0.0.1 CPUs=%d Sockets=1 CoresPerSocket=%d ThreadsPerCore=1"
            " RealMemory=%d State=UNKNOWN" % (self.hostname, self.cpus, self.cpus, self.memory_mb),
            "PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP",
        ]
        with open(self.conf, "w") as f:
            f.write("\n".join(lines) + "\n")

    def _check_daemons(self, names):
        for name in names:
            if self._procs[name].poll() is not None:
                self._fail("%s exited with %s during start" % (name, self._procs[name].returncode),
                           os.path.join(self.path, name + ".stderr"),
                           os.path.join(self.path, name + ".log"))

    def _node_state(self):
        """The node's state per sinfo (idle, unknown, down*, ...) or None.
        sinfo keeps retrying a controller that is not up (yet) for ~10 s, so
        watch the daemons meanwhile to report a crash at once."""
        with subprocess.Popen([self.bin["sinfo"], "-h", "-N", "-o", "%N %T"], stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True, env=self.env, cwd=self.path) as p:
            try:
                while p.poll() is None:
                    self._check_daemons(("slurmctld", "slurmd"))
                    time.sleep(0.05)
            finally:
                if p.poll() is None:
                    p.kill()
            out = p.stdout.read()
        for line in out.splitlines():
            parts = line.split()
            if len(parts) == 2 and parts[0] == self.hostname:
                return parts[1]
        return None

    def _start_slurm(self):
        conf = ["-f", self.conf]
        # -D: stay in the foreground as our child (logs go to the log file and stderr).
        self._spawn("slurmctld", [self.bin["slurmctld"], "-D"] + conf)
        # -N: the node name; slurmd would otherwise derive it from the hostname too.
        self._spawn("slurmd", [self.bin["slurmd"], "-D", "-N", self.hostname] + conf)
        deadline = time.monotonic() + self.start_timeout
        state = None
        while True:
            self._check_daemons(("slurmctld", "slurmd"))
            state = self._node_state()
            if state == "idle":
                return
            if time.monotonic() > deadline:
                self._fail("node %s not idle after %.0f s (state: %s)" % (self.hostname, self.start_timeout, state),
                           os.path.join(self.path, "slurmctld.log"), os.path.join(self.path, "slurmd.log"))
            time.sleep(0.2)

    def start(self):
        self._check_installed()
        if self._requested_dir:
            self.path = os.path.abspath(self._requested_dir)
            os.makedirs(self.path, exist_ok=True)
        else:
            self.path = tempfile.mkdtemp(prefix="frugal-slurm-")
        self._made_dir = True
        self._stopped = False
        atexit.register(self.stop)
        self._start_guard()
        if len(self.path) > _MAX_DIR_LEN:
            self.stop()
            raise SlurmError("cluster folder path too long for unix sockets (%d > %d chars): %s"
                             % (len(self.path), _MAX_DIR_LEN, self.path))
        self.conf = os.path.join(self.path, "slurm.conf")
        self.hostname = socket.gethostname().split(".")[0]
        self.cluster_name = "frugal" + uuid.uuid4().hex[:8]
        self.env = self._make_env()
        try:
            self._start_munge()
            # Ports picked now could be taken by someone else before the daemons
            # bind them; then start again with new ones.
            for attempt in range(3):
                self.ctld_port, self.slurmd_port = _free_port(), _free_port()
                while self.slurmd_port == self.ctld_port:
                    self.slurmd_port = _free_port()
                self._write_conf()
                try:
                    self._start_slurm()
                    break
                except SlurmError as e:
                    if attempt == 2 or "Address already in use" not in str(e):
                        raise
                    self._stop_daemons(("slurmd", "slurmctld"))
                    shutil.rmtree(os.path.join(self.path, "state"), ignore_errors=True)
                    shutil.rmtree(os.path.join(self.path, "spool"), ignore_errors=True)
        except BaseException:
            # slurmd ignores SIGTERM while it retries registering with a dead
            # slurmctld, so do not wait the full grace period here.
            self._grace = 1.0
            self.stop()
            raise
        self.pids = {name: p.pid for name, p in self._procs.items()}
        return self

    def _start_guard(self):
        """A watchdog in its own session that cleans up if this process dies
        without stop() (e.g. SIGKILL from a test timeout): it waits for EOF on
        a pipe only we hold, then kills everything carrying our marker
        (slurmstepd and jobs are not our children, so PDEATHSIG misses them)."""
        self._guard = subprocess.Popen(
            [sys.executable or "/usr/bin/python3", os.path.abspath(__file__), "--guard", self.path, "1" if self.keep else "0"],
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            start_new_session=True, close_fds=True)

    def _stop_guard(self):
        guard, self._guard = getattr(self, "_guard", None), None
        if guard is None:
            return
        try:
            guard.stdin.write(b"done")     # we cleaned up ourselves: just exit
            guard.stdin.close()
        except OSError:
            pass
        try:
            guard.wait(10)
        except subprocess.TimeoutExpired:
            guard.kill()
            guard.wait()

    # --------------------------------------------------------------- teardown

    def _stop_daemons(self, names, grace=5.0):
        for name in names:
            proc = self._procs.pop(name, None)
            if proc is None:
                continue
            if proc.poll() is None:
                try:
                    proc.terminate()
                    proc.wait(grace)
                except subprocess.TimeoutExpired:
                    pass
            # Kill what is left of its process group (e.g. a slurmstepd).
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            if proc.poll() is None:
                proc.kill()
            proc.wait()

    def stop(self):
        """Cancel all jobs, stop slurmd, slurmctld and munged (SIGTERM, then
        SIGKILL), kill anything else the cluster started, remove the folder
        unless keep. Safe to call more than once."""
        if self._stopped:
            return
        self._stopped = True
        try:
            atexit.unregister(self.stop)
            ctld = self._procs.get("slurmctld")
            if ctld is not None and ctld.poll() is None and "slurmd" in self._procs:
                # Let Slurm end running jobs itself, so their slurmstepd exit cleanly.
                try:
                    deadline = time.monotonic() + 5
                    while time.monotonic() < deadline:
                        # %F: the ArrayJobId for arrays, the JobId otherwise.
                        r = self.run(self.bin["squeue"], "-h", "-o", "%F", check=False, timeout=10)
                        ids = sorted(set(r.stdout.split()))
                        if r.returncode != 0 or not ids:
                            break
                        self.run([self.bin["scancel"]] + ids, check=False, timeout=10)
                        time.sleep(0.2)
                except subprocess.TimeoutExpired:
                    pass
            self._stop_daemons(("slurmd", "slurmctld", "munged"), self._grace)
            # Anything still carrying our marker (slurmstepd or job processes
            # that left slurmd's process group) is killed too.
            if self.path:
                _kill_marked(self.path)
        finally:
            self._restore_signals()
            if self.path and self._made_dir and not self.keep:
                shutil.rmtree(self.path, ignore_errors=True)
            self._stop_guard()

    # ---------------------------------------------------- context management

    def _on_signal(self, signum, frame):
        raise SystemExit(128 + signum)   # unwinds through __exit__ -> stop()

    def _install_signals(self):
        if threading.current_thread() is not threading.main_thread():
            return
        for sig in (signal.SIGTERM, signal.SIGHUP):
            if signal.getsignal(sig) == signal.SIG_DFL:
                self._old_handlers[sig] = signal.signal(sig, self._on_signal)

    def _restore_signals(self):
        for sig, old in self._old_handlers.items():
            signal.signal(sig, old)
        self._old_handlers = {}

    def __enter__(self):
        self._install_signals()
        try:
            return self.start()
        except BaseException:
            self._restore_signals()
            raise

    def __exit__(self, *exc):
        self.stop()
        return False

    # ------------------------------------------------------------- using it

    def run(self, *cmd, check=True, timeout=60, **kwargs):
        """Run a command against this cluster (env=self.env, cwd=self.path,
        text output captured). cmd may be given as separate args or one list.
        Raises SlurmError on a non-zero exit when check."""
        if len(cmd) == 1 and isinstance(cmd[0], (list, tuple)):
            cmd = tuple(cmd[0])
        kwargs.setdefault("env", self.env)
        kwargs.setdefault("cwd", self.path)
        kwargs.setdefault("capture_output", True)
        kwargs.setdefault("text", True)
        r = subprocess.run(list(cmd), timeout=timeout, **kwargs)
        if check and r.returncode != 0:
            raise SlurmError("%s exited %d: %s" % (" ".join(map(str, cmd)), r.returncode,
                                                  (r.stderr or "").strip()))
        return r

    def sbatch(self, args=(), script_text=None):
        """Submit a batch job; returns its job id (the ArrayJobId for an array).
        script_text is the script (it needs a #! line); without it, args must
        hold --wrap. The submit folder (default output place) is self.path."""
        cmd = [self.bin["sbatch"], "--parsable"] + list(args)
        if script_text is not None:
            fd, script = tempfile.mkstemp(prefix="job-", suffix=".sh", dir=self.path)
            with os.fdopen(fd, "w") as f:
                f.write(script_text)
            os.chmod(script, 0o755)
            cmd.append(script)
        out = self.run(cmd).stdout.strip()
        return int(out.split(";")[0])          # --parsable prints "id" or "id;cluster"

    def jobcomp_results(self, job_id):
        """Final records of a job / array from the jobcomp file (written as
        each job or task ends; kept after MinJobAge)."""
        records = []
        try:
            with open(os.path.join(self.path, "jobcomp.txt")) as f:
                for line in f:
                    rec = _parse_record(line)
                    if rec.get("JobId") == str(job_id) or rec.get("ArrayJobId") == str(job_id):
                        records.append(rec)
        except FileNotFoundError:
            pass
        return _records_to_results(records)

    def job_states(self, job_id):
        """Current {task_id: JobResult} of a job or array (task_id None for a
        plain job). Pending array tasks not yet split off are expanded from
        their range. Falls back to the jobcomp file once the job is purged.

        Quirk: tasks cancelled while still pending inside the array's range
        record are not listed at all (Slurm just drops them from the range;
        no record, no jobcomp line). Tasks cancelled once started (split off)
        are listed as CANCELLED."""
        r = self.run(self.bin["scontrol"], "-o", "show", "job", str(job_id), check=False)
        if r.returncode != 0:
            if "Invalid job id" in (r.stderr or ""):
                done = self.jobcomp_results(job_id)
                if done:
                    return done
            raise SlurmError("scontrol show job %s: %s" % (job_id, (r.stderr or "").strip()))
        return _records_to_results(_parse_record(l) for l in r.stdout.splitlines() if l.strip())

    def wait(self, job_id, timeout=60.0, poll=0.25, tasks=None):
        """Wait until the job and every array task have left the queue; return
        {task_id: JobResult} with their final states (task_id None for a plain
        job). Raises SlurmError on timeout.

        tasks: the array indexes submitted (e.g. range(4)); any Slurm no
        longer lists (cancelled while pending, see job_states) are returned
        with state "MISSING" instead of being left out."""
        deadline = time.monotonic() + timeout
        while True:
            states = self.job_states(job_id)
            if states and all(s.state in TERMINAL_STATES for s in states.values()):
                for tid in (tasks or ()):
                    if tid not in states:
                        states[tid] = JobResult(None, int(job_id), tid, "MISSING", 0, 0, None)
                return states
            if time.monotonic() > deadline:
                busy = sorted("%s:%s" % (k, v.state) for k, v in states.items()
                              if v.state not in TERMINAL_STATES)
                raise SlurmError("job %s not finished after %.0f s: %s" % (job_id, timeout, " ".join(busy)))
            time.sleep(poll)


if __name__ == "__main__" and len(sys.argv) == 4 and sys.argv[1] == "--guard":
    _guard_main(sys.argv[2], sys.argv[3] == "1")
