#!/usr/bin/python3
"""What Python costs per frame over frugal's C++ entry point.

One renderer, one camera (frugal.Camera.automatic()), three ways of rendering the same frame, in
blocks of --block frames that alternate within one process (their order rotates from round to round):

  python_render       f = r.render(cam), each call timed with time.perf_counter: the binding's
                      own cost (arguments, GIL release, the mutex, making the context current and
                      releasing it, the Frame object) on top of the C++ render.
  cpp_loop            frugal_bench.cpp_loop(r, cam, 0.0, K): the same renders in a C++ loop into
                      one reused Frame, each followed by the context release render() does, timed
                      per frame in C++ (std::chrono::steady_clock), no Python between frames.
  python_render_read  as python_render, plus f.color and f.depth, what a user reads: colour is a
                      view, depth is converted from 24 bits to float32 window z (a copy).

Reported: per-frame medians, p10 and p90 of each, and python_render / cpp_loop (the goal: <= 1.03).
Each block is also timed from Python as a whole (block_ms_per_frame). Minor page faults per frame
are counted per block: both loops render into memory used before (the C++ loop into its one Frame,
Python into a frame the renderer takes back once nothing refers to it), so neither should fault
pages in a frame; --malloc pinned fixes glibc's thresholds to check that the allocator does not
decide the ratio.

The module is frugal_bench (bench/python/BenchModule.cpp, built with -DFRUGAL_BUILD_BENCH=ON and
-DFRUGAL_BUILD_PYTHON=ON): frugal's binding itself, the same object files as frugal._frugal, plus
cpp_loop, so that the module users import has no benchmark hook. Both loops run on one renderer.

Run: PYTHONPATH=build/bench/python /usr/bin/python3 bench/python/overhead.py [--json FILE]
"""

import time

import benchutil

GOAL = 1.03  # python_render / cpp_loop, medians

WHAT = {
    "python_render": "f = r.render(cam) in a Python loop, each call timed with time.perf_counter",
    "cpp_loop": "frugal_bench.cpp_loop(r, cam, 0.0, K): the same renders in C++, timed per frame in C++",
    "python_render_read": "f = r.render(cam); f.color; f.depth in a Python loop, timed together",
}


def python_block(r, cam, frames, read):
    """`frames` renders from Python, each one's milliseconds."""
    ms = []
    for _ in range(frames):
        t0 = time.perf_counter()
        f = r.render(cam)
        if read:
            f.color  # a view of the frame's memory
            f.depth  # 24-bit values to float32 window z, on first access
        ms.append((time.perf_counter() - t0) * 1e3)
    return ms, None


def main():
    args, malloc, frugal, scene, r = benchutil.start(__doc__, module="frugal_bench")
    cam = frugal.Camera.automatic()

    started, machine = benchutil.now_utc(), benchutil.machine()
    results, _ = benchutil.run_interleaved({
        "python_render": lambda n: python_block(r, cam, n, read=False),
        "cpp_loop": lambda n: (frugal.cpp_loop(r, cam, 0.0, n), None),
        "python_render_read": lambda n: python_block(r, cam, n, read=True),
    }, args.frames, args.block, args.warmup)
    for method, what in WHAT.items():
        results[method] = {"what": what, **results[method]}

    def ratio(a, b, key="per_frame_ms"):
        return round(results[a][key]["median"] / results[b][key]["median"], 4)

    python_over_cpp = ratio("python_render", "cpp_loop")
    benchutil.emit({
        **benchutil.run_header("overhead", started, frugal, args, r),
        "camera": "frugal.Camera.automatic()",
        "settings": "frugal.Renderer defaults (frugal.default_settings())",
        "frames_per_method": args.frames,
        "block": args.block,
        "warmup_per_method": args.warmup,
        "malloc": malloc,
        "methods": results,
        "ratios": {
            "python_over_cpp": python_over_cpp,
            "goal_python_over_cpp": GOAL,
            "meets_goal": python_over_cpp <= GOAL,
            "python_over_cpp_block_wall": ratio("python_render", "cpp_loop", "block_ms_per_frame"),
            "python_read_over_cpp": ratio("python_render_read", "cpp_loop"),
            "python_read_over_python": ratio("python_render_read", "python_render"),
        },
        "machine": {**machine, "loadavg_after": benchutil.loadavg()},
    }, args.json)


if __name__ == "__main__":
    main()
