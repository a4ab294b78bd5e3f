"""Threads and long runs: two renderers on two threads give the images each gives alone; a renderer
made on one thread renders on another; 1,000 frames leave the process's memory where it was."""
import threading
from pathlib import Path

import numpy as np

import frugal

SIZE = (96, 72)


def frames(renderer, count, scene_fps=30.0):
    return [renderer.render(time=i / scene_fps).color.copy() for i in range(count)]


def test_two_threads_two_renderers(bunny):
    specs = [bunny, "builtin:cubes?count=12"]
    renderers = [frugal.Renderer(frugal.load(spec), size=SIZE, cull="conservative") for spec in specs]
    alone = [frames(r, 8) for r in renderers]
    again = [frugal.Renderer(frugal.load(spec), size=SIZE, cull="conservative") for spec in specs]
    results, errors = [None, None], []

    def work(i):
        try:
            results[i] = frames(again[i], 8)
        except Exception as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    for i in range(2):
        for a, b in zip(alone[i], results[i]):
            np.testing.assert_array_equal(a, b)


def test_a_renderer_moves_between_threads():
    """Made on this thread, used on another, then here again, then dropped on a third."""
    renderer = frugal.Renderer(frugal.load("builtin:cubes?count=6"), size=SIZE)
    here = renderer.render(time=0.5).color.copy()
    there = []
    worker = threading.Thread(target=lambda r=renderer: there.append(r.render(time=0.5).color.copy()))
    worker.start()
    worker.join()
    np.testing.assert_array_equal(here, there[0])
    np.testing.assert_array_equal(here, renderer.render(time=0.5).color)
    holder = [renderer]
    del renderer
    dropper = threading.Thread(target=holder.clear)
    dropper.start()
    dropper.join()


def resident_kb():
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    raise AssertionError("no VmRSS in /proc/self/status")


def test_a_thousand_frames_without_memory_growth():
    """Frames, their arrays and stats made and dropped 1,000 times: after a warm-up of 100, the
    resident size grows by less than 4 MB (a leaked 96x72 frame would be 41 KB a frame: 41 MB)."""
    scene = frugal.load("builtin:cubes?count=12")
    renderer = frugal.Renderer(scene, size=SIZE, ids=True, reuse=True)
    camera = frugal.Camera.look_at((0, 3, 9), (0, 0, 0))

    def one(i):
        frame = renderer.render(camera, time=(i % 60) / scene.fps)
        return int(frame.color[0, 0, 0]) + int(frame.ids.max()) + float(frame.depth.min()) + \
            frame.stats.reuse.redrawn_tris + len(frame.stats.to_dict()) + len(repr(frame.camera))

    for i in range(100):
        one(i)
    before = resident_kb()
    for i in range(1000):
        one(i)
    grown = resident_kb() - before
    assert grown < 4096, f"resident size grew by {grown} KB over 1,000 frames"


def test_frames_kept_keep_their_images():
    """A renderer fills the memory of frames no longer referenced; a frame still held, or an array
    of it, is never written again."""
    scene = frugal.load("builtin:cubes?count=12")
    renderer = frugal.Renderer(scene, size=SIZE, ids=True)
    first = renderer.render(time=0.0)
    color, ids = first.color, first.ids
    expected = color.copy(), ids.copy()
    del first  # the arrays still hold the frame
    for i in range(1, 6):
        later = renderer.render(time=i * 0.4)
        assert not np.array_equal(later.color, expected[0])
    np.testing.assert_array_equal(color, expected[0])
    np.testing.assert_array_equal(ids, expected[1])
