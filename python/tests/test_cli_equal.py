"""Every array a frame gives equals what `frugal render` writes for the same scene, settings and
camera: colour and ids from their PNGs, depth from the exact PFM; and Frame.write writes the same
bytes as the command line."""
import filecmp

import numpy as np
import pytest

import frugal
from conftest import read_ids, read_pfm, read_png, run_cli

SIZE = (160, 120)
EYE, TARGET = (0.3, 1.2, 2.6), (0.0, 0.1, 0.0)

CASES = {
    "plain": ({}, []),
    "conservative": ({"cull": "conservative"}, ["--cull", "conservative"]),
    "d32f": ({"depth_format": "d32f"}, ["--depth-format", "d32f"]),
    "order-key": ({"order": "key"}, ["--order", "key"]),
    "software": ({"backend": "software"}, ["--backend", "software"]),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_arrays_equal_the_command_line(tmp_path, cli, bunny, case):
    settings, flags = CASES[case]
    run_cli(cli, "render", bunny, "-q", "--size", f"{SIZE[0]}x{SIZE[1]}", "--eye", ",".join(map(str, EYE)),
            "--target", ",".join(map(str, TARGET)), "--fov", 45, "-o", tmp_path / "c.png",
            "--depth", tmp_path / "d.pfm", "--ids", tmp_path / "i.png", *flags)
    renderer = frugal.Renderer(frugal.load(bunny), size=SIZE, ids=True, **settings)
    frame = renderer.render(frugal.Camera.look_at(EYE, TARGET, fov=45))

    assert frame.color.shape == (SIZE[1], SIZE[0], 4) and frame.color.dtype == np.uint8
    assert frame.depth.shape == (SIZE[1], SIZE[0]) and frame.depth.dtype == np.float32
    assert frame.ids.shape == (SIZE[1], SIZE[0]) and frame.ids.dtype == np.uint32
    np.testing.assert_array_equal(frame.color, read_png(tmp_path / "c.png"))
    np.testing.assert_array_equal(frame.depth, read_pfm(tmp_path / "d.pfm"))
    np.testing.assert_array_equal(frame.ids, read_ids(tmp_path / "i.png"))
    assert (frame.ids > 0).sum() > 1000, "the bunny is in view"

    frame.write(color=tmp_path / "pc.png", depth=tmp_path / "pd.png", ids=tmp_path / "pi.png")
    run_cli(cli, "render", bunny, "-q", "--size", f"{SIZE[0]}x{SIZE[1]}", "--eye", ",".join(map(str, EYE)),
            "--target", ",".join(map(str, TARGET)), "--fov", 45, "-o", tmp_path / "c2.png",
            "--depth", tmp_path / "d2.png", *flags)
    assert filecmp.cmp(tmp_path / "pc.png", tmp_path / "c.png", shallow=False)
    assert filecmp.cmp(tmp_path / "pd.png", tmp_path / "d2.png", shallow=False)
    assert filecmp.cmp(tmp_path / "pi.png", tmp_path / "i.png", shallow=False)


def test_sequence_with_reuse_equals_the_command_line(tmp_path, cli):
    """A sequence through reuse: frame i at time i / fps, as `--frames 0:5` renders it."""
    spec = "builtin:dominoes?polygons=204"
    run_cli(cli, "render", spec, "-q", "--size", "128x96", "--reuse", "--frames", "0:5", "-o", tmp_path / "f.png",
            "--depth", tmp_path / "d.pfm")
    scene = frugal.load(spec)
    renderer = frugal.Renderer(scene, size=(128, 96), reuse=True)
    modes = []
    for i in range(6):
        frame = renderer.render(time=i / scene.fps)
        modes.append(frame.stats.reuse.mode)
        np.testing.assert_array_equal(frame.color, read_png(tmp_path / f"f_{i:04d}.png"))
        np.testing.assert_array_equal(frame.depth, read_pfm(tmp_path / f"d_{i:04d}.pfm"))
    assert "reuse" in modes, modes


def test_pose_camera_is_the_look_at_camera(bunny):
    """A camera-to-world pose (OpenGL convention) draws what the same look-at draws, but for float
    rounding: the pose's target (eye - its z axis) and up are not the look-at's to the last bit."""
    eye, target = np.array(EYE), np.array(TARGET)
    back = (eye - target) / np.linalg.norm(eye - target)  # the camera's +z
    right = np.cross((0, 1, 0), back)
    right /= np.linalg.norm(right)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = right, np.cross(back, right), back, eye
    renderer = frugal.Renderer(frugal.load(bunny), size=SIZE)
    a = renderer.render(frugal.Camera.from_pose(pose, fov=45))
    b = renderer.render(frugal.Camera.look_at(EYE, TARGET, fov=45))
    difference = np.abs(a.color.astype(int) - b.color.astype(int)).max(axis=2)
    assert difference.max() <= 1 and (difference > 0).mean() < 1e-3


def test_scene_camera_equals_the_command_line(tmp_path, cli):
    """A scene's own camera, as --camera 0 takes it (a glTF written here, with a camera node)."""
    from test_memory_scene import write_gltf, box_arrays
    positions, indices = box_arrays()
    path = write_gltf(tmp_path / "cam.gltf", [(positions, indices, None, None)], [(0, np.eye(4))],
                      camera=((0.5, 0.8, 4.0), 0.7))
    run_cli(cli, "render", path, "-q", "--size", "96x72", "--camera", 0, "-o", tmp_path / "c.png")
    scene = frugal.load(str(path))
    assert len(scene.cameras) == 1 and scene.cameras[0]["perspective"]
    frame = frugal.Renderer(scene, size=(96, 72)).render(frugal.Camera.from_scene(0))
    np.testing.assert_array_equal(frame.color, read_png(tmp_path / "c.png"))
