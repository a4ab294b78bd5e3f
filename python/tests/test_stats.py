"""A frame's statistics and camera as typed objects (frugal.FrameStats and its parts, frugal.View),
against `frugal render --json` of the same frames: to_dict() has the record's keys, every one, with
its values (timings: the same kind of number); every key is an attribute of the same name holding
the same value; every attribute is in to_dict(). A field missing, renamed or added on either side
fails here."""
import json

import pytest

import frugal
from conftest import run_cli

SCENE = "builtin:dominoes?polygons=2000"
SIZE = (96, 72)

# The keys of the render JSON's frame record that the command line adds (not a frame's statistics).
CLI_ONLY = {"frame", "file", "write_ms", "encode_ms"}
# Keys whose values are times: measured anew by every run, compared by kind only.
TIMINGS = {"ms", "refined_state_costs_us"}
# A frame's culling, written in the record itself: the attributes of FrameStats.cull.
CULL_KEYS = {"tos", "pvs", "cull_ms", "ranges", "occlusion"}
# Decided by a measured time (occlusion skips itself where it did not pay lately): compared by kind.
OCCLUSION_VOLATILE = {"pvs", "ranges", "ran", "triangles_hidden", "draws"}

# name: (keyword arguments, the same as flags, frames, keys whose values may differ between runs)
CASES = {
    "plain": ({}, [], 1, set()),
    "conservative": ({"cull": "conservative"}, ["--cull", "conservative"], 1, set()),
    "oracle": ({"cull": "oracle"}, ["--cull", "oracle"], 1, set()),
    "occlusion": ({"cull": "occlusion"}, ["--cull", "occlusion"], 1, OCCLUSION_VOLATILE),
    "occlusion-ahead": ({"cull": "occlusion-ahead"}, ["--cull", "occlusion-ahead"], 3, OCCLUSION_VOLATILE),
    "reuse": ({"reuse": True}, ["--reuse"], 4, set()),
    "hsr-adaptive": ({"hsr": "adaptive", "cull": "sphere"}, ["--hsr", "adaptive", "--cull", "sphere"], 1, set()),
    "software-span": ({"backend": "software", "interp": "span"}, ["--backend", "software", "--interp", "span"], 1,
                      set()),
    "d32f-order-key": ({"depth_format": "d32f", "order": "key"}, ["--depth-format", "d32f", "--order", "key"], 1,
                       set()),
}


def is_timing(key):
    return key.endswith("_ms") or key in TIMINGS


def command_line_json(cli, tmp_path, flags, frames, scene=SCENE, size=SIZE):
    out = tmp_path / "render.json"
    run_cli(cli, "render", scene, "-q", "--size", f"{size[0]}x{size[1]}", "--frames", f"0:{frames - 1}",
            "-o", tmp_path / "f.png", "--json", out, *flags)
    return json.loads(out.read_text())


def python_frames(renderer, scene, frames, ahead=False):
    """Frame i at time i / fps, as `--frames 0:N-1` renders them; with occlusion-ahead each call
    names the next frame, as the command line does."""
    out = []
    for i in range(frames):
        following = {"next_time": (i + 1) / scene.fps} if ahead and i + 1 < frames else {}
        out.append(renderer.render(time=i / scene.fps, **following))
    return out


def compare(ours, theirs, path, volatile):
    """`ours` (to_dict()) against `theirs` (the command line's JSON): the same keys at every level,
    equal values but for timings and the volatile keys, which need only be of the same kind."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), f"{path}: {ours!r} is not an object"
        assert set(ours) == set(theirs), \
            f"{path}: keys only in Python {sorted(set(ours) - set(theirs))}, only in the CLI {sorted(set(theirs) - set(ours))}"
        for key in theirs:
            compare(ours[key], theirs[key], f"{path}.{key}", volatile if not is_timing(key) else None)
        return
    if volatile is None or path.rsplit(".", 1)[-1] in volatile:  # a timing, or a value decided by one
        kind = (int, float) if isinstance(theirs, (int, float)) and not isinstance(theirs, bool) else type(theirs)
        assert isinstance(ours, kind), f"{path}: {ours!r} is not a {kind}"
        return
    assert ours == theirs and type(ours) is type(theirs), f"{path}: Python {ours!r}, the CLI {theirs!r}"


def properties(obj):
    return sorted(name for name in dir(type(obj)) if isinstance(getattr(type(obj), name), property))


def check_attributes(obj, record, path):
    """Every key of `record` (obj.to_dict()) is an attribute of `obj` holding the same value (an
    object's attributes checked the same way, a tuple as the record's list); every attribute is in
    the record, or None (an optional part). FrameStats' culling is FrameStats.cull's."""
    flattened = {}
    if isinstance(obj, frugal.FrameStats) and obj.cull is not None:
        flattened = obj.cull.to_dict()
        check_attributes(obj.cull, flattened, f"{path}.cull")
    for key, value in record.items():
        owner = obj.cull if key in flattened else obj
        assert key in properties(owner), f"{path}: the record's '{key}' is not an attribute of {type(owner).__name__}"
        attribute = getattr(owner, key)
        if hasattr(attribute, "to_dict"):
            check_attributes(attribute, value, f"{path}.{key}")
        elif isinstance(attribute, tuple):
            assert list(attribute) == value, f"{path}.{key}"
        elif hasattr(attribute, "shape"):  # View's matrices
            assert (attribute == value).all() and attribute.shape == (4, 4), f"{path}.{key}"
        else:
            assert attribute == value and type(attribute) is type(value), f"{path}.{key}: {attribute!r} != {value!r}"
    for name in properties(obj):
        if name == "cull" and isinstance(obj, frugal.FrameStats):
            continue
        assert name in record or getattr(obj, name) is None, f"{path}: attribute '{name}' is not in to_dict()"


@pytest.mark.parametrize("case", list(CASES))
def test_stats_are_the_command_lines_record(tmp_path, cli, case):
    settings, flags, frames, volatile = CASES[case]
    document = command_line_json(cli, tmp_path, flags, frames)
    scene = frugal.load(SCENE)
    with frugal.Renderer(scene, size=SIZE, **settings) as renderer:
        ours = python_frames(renderer, scene, frames, ahead=settings.get("cull") == "occlusion-ahead")
    assert len(document["frames"]) == frames
    for i, (frame, record) in enumerate(zip(ours, document["frames"])):
        stats = frame.stats
        assert isinstance(stats, frugal.FrameStats) and stats is frame.stats, "made once"
        expected = {k: v for k, v in record.items() if k not in CLI_ONLY}
        compare(stats.to_dict(), expected, f"{case} frame {i}", volatile)
        check_attributes(stats, stats.to_dict(), f"{case} frame {i}")
    camera = ours[0].camera.to_dict()
    assert camera.pop("view_matrix").shape == camera.pop("projection_matrix").shape == (4, 4)
    compare(camera, document["camera"], f"{case} camera", set())
    check_attributes(ours[0].camera, ours[0].camera.to_dict(), f"{case} camera")


def test_each_part_is_there_with_its_setting_and_none_without():
    scene = frugal.load(SCENE)
    with frugal.Renderer(scene, size=SIZE) as plain:
        s = plain.render().stats
        assert (s.cull, s.reuse, s.hsr, s.interp, s.refined_state_costs_us, s.refine_ms) == (None,) * 6
        assert isinstance(s.state_changes, frugal.StateChanges) and s.state_changes.draws > 0
        assert set(s.to_dict()) == {"time", "render_ms", "readback_ms", "state_changes"}
        assert plain.cull_preparation is None and plain.state_costs is None
    with frugal.Renderer(scene, size=SIZE, cull="oracle") as oracle:
        cull = oracle.render().stats.cull
        assert isinstance(cull, frugal.CullStats) and cull.ranges is None and cull.occlusion is None
        assert 0 < cull.pvs < cull.tos and "ranges" not in cull.to_dict()
    with frugal.Renderer(scene, size=SIZE, cull="occlusion-ahead") as ahead:
        occlusion = ahead.render(next_time=0.0).stats.cull.occlusion
        assert isinstance(occlusion, frugal.OcclusionFrameStats) and occlusion.ahead is False
        assert set(occlusion.to_dict()) == {"ran", "ms", "triangles_hidden", "ahead", "ahead_wait_ms"}
    with frugal.Renderer(scene, size=SIZE, hsr="depthsort") as sorted_:
        hsr = sorted_.render().stats.hsr
        assert isinstance(hsr, frugal.HsrStats) and hsr.mode == "depthsort"
        assert hsr.zbuffered_polygons == 0 and hsr.zbuffered_share == 0.0 and hsr.polygons > 0
    with frugal.Renderer(scene, size=SIZE, backend="software", interp="dda") as software:
        interp = software.render().stats.interp
        assert isinstance(interp, frugal.InterpStats) and interp.mode == "dda" and interp.spans > 0
    with frugal.Renderer(scene, size=SIZE, reuse=True) as reusing:
        reuse = reusing.render().stats.reuse
        assert isinstance(reuse, frugal.ReuseStats) and reuse.mode == "rebuild" and reuse.reason == "first frame"
        assert isinstance(reuse.instances, frugal.ReuseCounts)
        assert reuse.to_dict()["instances"] == {"p_dd": reuse.instances.p_dd, "p_ds": reuse.instances.p_ds,
                                                "p_sd": reuse.instances.p_sd, "p_ss": reuse.instances.p_ss}


def test_cost_rounds_and_state_costs_are_typed(tmp_path, cli):
    """A cost-driven order: Renderer.state_costs is the render JSON's "state_costs"; a frame after a
    cost round carries its costs (the command line writes them in the record of the frame before)."""
    frames = 4
    document = command_line_json(cli, tmp_path, ["--order", "greedy", "--refine-costs", "1"], frames)
    scene = frugal.load(SCENE)
    with frugal.Renderer(scene, size=SIZE, order="greedy", refine_costs=1) as r:
        ours = python_frames(r, scene, frames)
        costs = r.state_costs
        assert isinstance(costs, frugal.StateCosts) and r.cull_preparation is None
        compare(costs.to_dict(), document["state_costs"], "state_costs", {"start_us", "us"})
        check_attributes(costs, costs.to_dict(), "state_costs")
        assert len(costs.us) == len(costs.kinds) == len(costs.start_us) and costs.refine_every == 1
    refinement = {"refined_state_costs_us", "refine_ms"}
    refined = [refinement <= set(f.stats.to_dict()) for f in ours]
    assert refined[0] is False and any(refined), refined
    assert refined[1:] == [refinement <= set(record) for record in document["frames"][:-1]]
    for i, frame in enumerate(ours):  # the order follows measured costs: the keys, not the values
        record = {k: v for k, v in document["frames"][i].items() if k not in CLI_ONLY}
        assert set(frame.stats.to_dict()) - refinement == set(record) - refinement
        check_attributes(frame.stats, frame.stats.to_dict(), f"frame {i}")
        if frame.stats.refined_state_costs_us is not None:
            assert len(frame.stats.refined_state_costs_us) == len(costs.kinds) and frame.stats.refine_ms >= 0


def test_a_scene_cameras_aspect_ratio_is_the_command_lines(tmp_path, cli):
    """View.file_aspect_ratio and aspect_ratio_differs (computed in the binding from the library's
    rule) against the command line's camera, for a glTF camera of aspect ratio 2 drawn at 4:3."""
    from test_memory_scene import box_arrays, write_gltf
    import numpy as np
    positions, indices = box_arrays()
    path = write_gltf(tmp_path / "cam.gltf", [(positions, indices, None, None)], [(0, np.eye(4))],
                      camera=((0.5, 0.8, 4.0), 0.7))
    gltf = json.loads(path.read_text())
    gltf["cameras"][0]["perspective"]["aspectRatio"] = 2.0
    path.write_text(json.dumps(gltf))
    for size, differs in (((96, 72), True), ((96, 48), False)):
        document = command_line_json(cli, tmp_path, ["--camera", 0], 1, scene=path, size=size)
        view = frugal.Renderer(frugal.load(str(path)), size=size).render(frugal.Camera.from_scene(0)).camera
        assert view.file_aspect_ratio == 2.0 and view.aspect_ratio_differs is differs
        ours = view.to_dict()
        del ours["view_matrix"], ours["projection_matrix"]
        compare(ours, document["camera"], f"camera {size}", set())


def test_objects_are_read_only_and_say_what_they_hold():
    scene = frugal.load(SCENE)
    frame = frugal.Renderer(scene, size=SIZE, cull="conservative", reuse=True).render()
    stats = frame.stats
    text = repr(stats)
    assert text.startswith("frugal.FrameStats(time=0.0, render_ms=") and "cull=frugal.CullStats(tos=" in text
    assert "state_changes=frugal.StateChanges(draws=" in text and "reuse=frugal.ReuseStats(mode='rebuild'" in text
    assert repr(frame.camera).startswith("frugal.View(source=") and "matrix" not in repr(frame.camera)
    assert frame.camera.view_matrix.shape == (4, 4) and str(frame.camera.projection_matrix.dtype) == "float32"
    with pytest.raises(AttributeError):
        stats.render_ms = 0.0
    with pytest.raises(TypeError):
        stats["render_ms"]  # noqa: B018 (the dict of old: to_dict() is the one-call path)
    with pytest.raises(TypeError):
        frugal.FrameStats()
    assert json.loads(json.dumps(stats.to_dict())) == stats.to_dict(), "plain JSON values"
