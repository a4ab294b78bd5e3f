"""What the Python benchmarks share: importing frugal, the command-line pieces, interleaved blocks,
summaries of timings, a description of the machine, and the JSON output.

Not a benchmark itself: overhead.py and vs_moderngl.py import it from their own folder.
"""

import argparse
import ctypes
import datetime
import importlib
import json
import os
import platform
import resource
import sys
import time

import numpy as np

BUNNY = "/usr/share/glmark2/models/bunny.obj"


def log(message):
    """Progress for the person watching: stderr, so that stdout holds only the JSON."""
    print(message, file=sys.stderr, flush=True)


def import_frugal(name="frugal"):
    """The frugal module, or frugal_bench (overhead.py's: frugal's binding plus cpp_loop, built into
    <build>/bench/python with FRUGAL_BUILD_BENCH), or an exit with a line that says where it is expected."""
    folder = "bench/python" if name == "frugal_bench" else "python"
    try:
        module = importlib.import_module(name)
    except ImportError as e:
        sys.exit(f"error: cannot import {name} ({e}); run with PYTHONPATH=<build>/{folder}, "
                 f"e.g. PYTHONPATH=build/{folder} /usr/bin/python3 ...")
    return module


def frugal_build(frugal):
    """Which frugal was measured: its version and its extension module's file and build time (the
    build folder may be rebuilt between two runs)."""
    path = getattr(frugal, "_frugal", frugal).__file__
    built = datetime.datetime.fromtimestamp(os.path.getmtime(path), datetime.timezone.utc)
    return {"version": frugal.__version__, "extension": path, "extension_mtime": built.isoformat(timespec="seconds")}


def size_arg(text):
    """argparse type for --size: 'WxH' with both above 0."""
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not WxH (e.g. 800x600)") from None
    if width <= 0 or height <= 0:
        raise argparse.ArgumentTypeError(f"'{text}': width and height must be above 0")
    return width, height


def positive_int(text):
    """argparse type for counts that must be at least 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value}: must be at least 1")
    return value


def add_common_args(parser, malloc, frames=200, block=10, warmup=20):
    """The options both benchmarks take."""
    parser.add_argument("--frames", type=positive_int, default=frames,
                        help=f"timed frames per method (default {frames})")
    parser.add_argument("--block", type=positive_int, default=block,
                        help=f"frames per block; the methods' blocks alternate (default {block})")
    parser.add_argument("--warmup", type=positive_int, default=warmup,
                        help=f"untimed frames per method before the timed ones (default {warmup})")
    parser.add_argument("--size", type=size_arg, default=(800, 600), metavar="WxH",
                        help="image size (default 800x600)")
    parser.add_argument("--scene", default=BUNNY, help=f"scene file or frugal spec (default {BUNNY})")
    parser.add_argument("--malloc", choices=("pinned", "default"), default=malloc,
                        help="pinned: glibc keeps freed memory mapped (mallopt), so that no allocation pays "
                             "for mapping fresh pages; default: glibc's adaptive thresholds, as a user gets "
                             f"them (default {malloc}; see README.md)")
    parser.add_argument("--json", metavar="FILE", help="also write the JSON object to FILE")


def start(description, module="frugal"):
    """What both benchmarks do first: parse the options, set the allocator, import `module` (frugal,
    or frugal_bench), load the scene and make a renderer of the size asked for (its defaults
    otherwise). Returns (args, the allocator's description, the module, the scene, the renderer); a
    frugal error exits with its line."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_args(parser, malloc="default")
    args = parser.parse_args()
    malloc = set_malloc(args.malloc)
    frugal = import_frugal(module)
    try:
        scene = frugal.load(args.scene)
        renderer = frugal.Renderer(scene, size=args.size)
    except frugal.Error as e:
        sys.exit(f"error: {e}")
    width, height = args.size
    log(f"{scene!r} on {renderer.backend} ({renderer.backend_renderer}), {width}x{height}")
    return args, malloc, frugal, scene, renderer


def run_header(benchmark, date, frugal, args, renderer):
    """The fields every benchmark's JSON starts with: what ran, when, on which build and backend."""
    return {
        "benchmark": benchmark,
        "date": date,
        "frugal": frugal_build(frugal),
        "backend": renderer.backend,
        "gl_renderer": renderer.backend_renderer,
        "scene": args.scene,
        "triangles": renderer.triangle_count,
        "size": list(args.size),
    }


# glibc's mallopt parameters (malloc.h).
M_TRIM_THRESHOLD = -1
M_MMAP_THRESHOLD = -3


def set_malloc(mode):
    """--malloc: with "pinned", blocks up to 32 MiB come from the heap and the heap is not trimmed, so
    memory a frame frees is reused by the next one instead of being returned to the kernel and
    faulted in again. Setting either threshold also turns off glibc's adaptive thresholds, under
    which a loop that frees each frame before making the next (frugal's C++ loop does) can pay a
    page fault per 4 KiB of every image, every frame (frugal's frames reuse their memory, so its
    loops should not). Returns the mode's description for the JSON."""
    if mode == "default":
        return "default: glibc's adaptive mmap and trim thresholds"
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        sys.exit("error: --malloc pinned needs glibc's mallopt; use --malloc default")
    if mallopt(M_MMAP_THRESHOLD, 32 << 20) != 1 or mallopt(M_TRIM_THRESHOLD, 1 << 30) != 1:
        sys.exit("error: mallopt refused the thresholds; use --malloc default")
    return "pinned: mallopt(M_MMAP_THRESHOLD, 32 MiB), mallopt(M_TRIM_THRESHOLD, 1 GiB)"


def minor_faults():
    """The process's minor page faults so far (every thread's)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


def rounds(frames, block, methods):
    """The interleaved schedule: a list of rounds, each a list of (method, frame count) with every
    method once. The order rotates from round to round, so that no method always runs first after
    another one (a block's first frame may pay for the switch); the last round is short when
    `block` does not divide `frames`."""
    sizes = [block] * (frames // block) + ([frames % block] if frames % block else [])
    schedule = []
    for i, size in enumerate(sizes):
        shift = i % len(methods)
        order = methods[shift:] + methods[:shift]
        schedule.append([(method, size) for method in order])
    return schedule


def run_interleaved(blocks, frames, block, warmup):
    """Runs `blocks` ({method: function(frames) -> (per-frame ms, anything)}): `warmup` untimed frames
    of each, then `frames` of each in the interleaved rounds. Returns two dicts by method: the
    summaries of its per-frame ms, of its blocks' wall ms per frame (timed here, around the call)
    and of their minor page faults per frame; and what its last block returned besides the timings."""
    methods = list(blocks)
    log(f"warm-up: {warmup} frames per method")
    for method in methods:
        blocks[method](warmup)

    runs = {m: {"ms": [], "block_ms": [], "faults": [], "last": None} for m in methods}
    schedule = rounds(frames, block, methods)
    for i, round_ in enumerate(schedule, 1):
        for method, n in round_:
            run = runs[method]
            faults, start = minor_faults(), time.perf_counter()
            ms, run["last"] = blocks[method](n)
            run["block_ms"].append((time.perf_counter() - start) * 1e3 / n)
            run["faults"].append((minor_faults() - faults) / n)
            run["ms"] += ms
        if i % 5 == 0 or i == len(schedule):
            medians = ", ".join(f"{m} {np.median(runs[m]['ms']):.3f}" for m in methods)
            log(f"round {i}/{len(schedule)}: median ms so far: {medians}")
    summaries = {m: {"per_frame_ms": summary(r["ms"]), "block_ms_per_frame": summary(r["block_ms"]),
                     "minor_faults_per_frame": summary(r["faults"])} for m, r in runs.items()}
    return summaries, {m: r["last"] for m, r in runs.items()}


def summary(ms):
    """n, median, p10, p90, mean, min and max of a list of numbers (milliseconds, faults), to 4 decimals."""
    a = np.asarray(ms, dtype=np.float64)
    values = {
        "median": np.median(a), "p10": np.percentile(a, 10), "p90": np.percentile(a, 90),
        "mean": a.mean(), "min": a.min(), "max": a.max(),
    }
    return {"n": int(a.size), **{k: round(float(v), 4) for k, v in values.items()}}


def _cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or None


def loadavg():
    """The 1, 5 and 15 minute load averages: the machine may be shared."""
    return [round(x, 2) for x in os.getloadavg()]


def machine():
    """What the figures were measured on, with the load average when the run starts."""
    return {
        "cpu_count": os.cpu_count(),
        "cpu_model": _cpu_model(),
        "platform": platform.platform(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "lp_num_threads": os.environ.get("LP_NUM_THREADS"),
        "loadavg_before": loadavg(),
    }


def now_utc():
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


def emit(result, path):
    """The JSON object on stdout and, with --json, in `path`."""
    text = json.dumps(result, indent=2)
    print(text)
    if path:
        try:
            with open(path, "w") as f:
                f.write(text + "\n")
        except OSError as e:
            sys.exit(f"error: cannot write {path}: {e}")
        log(f"wrote {path}")
