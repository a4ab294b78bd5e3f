"""Bad input is refused with one line naming the value and the numbers, as an exception of the
error's kind under frugal.Error, never a crash."""
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import frugal
from test_memory_scene import box_arrays

POSITIONS, INDICES = box_arrays()


def refused(kind, match, call, *args, **kwargs):
    with pytest.raises(kind, match=match) as caught:
        call(*args, **kwargs)
    assert isinstance(caught.value, frugal.Error)
    assert "\n" not in str(caught.value), "one line"
    return str(caught.value)


def test_error_classes():
    assert issubclass(frugal.InputError, frugal.Error) and issubclass(frugal.InputError, ValueError)
    assert issubclass(frugal.BackendUnavailable, frugal.Error) and issubclass(frugal.BackendUnavailable, RuntimeError)
    assert issubclass(frugal.OutOfMemory, MemoryError) and issubclass(frugal.IoError, OSError)
    assert issubclass(frugal.Interrupted, frugal.Error)


@pytest.mark.parametrize("positions, indices, match", [
    (POSITIONS.astype(str), INDICES, r"positions: dtype <U\d+ is not a number type"),
    (POSITIONS[:, :2], INDICES, r"positions: expected an \(N, 3\) array, got shape \(8, 2\)"),
    (np.where(np.arange(24).reshape(8, 3) == 13, np.nan, POSITIONS), INDICES,
     r"mesh: position 4 is \(0\.5, nan, -0\.5\), not finite"),
    (POSITIONS, INDICES.astype(np.float64), r"indices: dtype float64 is not an integer type"),
    (POSITIONS, np.where(INDICES == 3, np.nan, INDICES), r"indices: dtype float64 is not an integer type \(and index 2 is NaN\)"),
    (POSITIONS, np.where(INDICES == 3, 120, INDICES), r"mesh: index 120 \(triangle 0\) is past the 8 vertices"),
    (POSITIONS, INDICES.astype(np.int64) - 1, r"indices: index -1 \(at 0\) is negative"),
    (POSITIONS, INDICES.reshape(-1)[:-1], r"mesh: 35 indices are not whole triangles"),
    (POSITIONS, INDICES.reshape(6, 6), r"indices: expected a \(T, 3\) or \(3T,\) array, got shape \(6, 6\)"),
    (POSITIONS, np.full((1, 3), 2**33, dtype=np.uint64), r"indices: index 8589934592 \(at 0\) is larger than"),
    ([[0, 0], [1]], INDICES, r"positions: not an array of numbers"),
])
def test_bad_mesh_arrays(positions, indices, match):
    scene = frugal.Scene()
    refused(frugal.InputError, match, scene.add_mesh, positions, indices)
    assert scene.mesh_count == 0, "nothing was added"


def test_bad_attributes_materials_textures_instances():
    scene = frugal.Scene()
    refused(frugal.InputError, r"mesh: 3 normals for 8 vertices", scene.add_mesh, POSITIONS, INDICES,
            normals=np.ones((3, 3)))
    refused(frugal.InputError, r"uvs: expected an \(N, 2\) array", scene.add_mesh, POSITIONS, INDICES,
            uvs=np.ones((8, 3)))
    refused(frugal.InputError, r"colors: expected an \(N, 4\) array, got shape \(8, 5\)", scene.add_mesh, POSITIONS,
            INDICES, colors=np.ones((8, 5)))
    refused(frugal.InputError, r"colors: not an array of numbers", scene.add_mesh, POSITIONS, INDICES,
            colors=[[1, 2], [3]])
    refused(frugal.InputError, r"material 4 does not exist \(the scene has 0\)", scene.add_mesh, POSITIONS, INDICES,
            material=4)
    refused(frugal.InputError, r"texture: dtype float32 is not uint8", scene.add_texture, np.zeros((4, 4, 4), np.float32))
    refused(frugal.InputError, r"texture: expected an \(H, W, 4\) or \(H, W, 3\) array, got shape \(4, 4\)",
            scene.add_texture, np.zeros((4, 4), np.uint8))
    refused(frugal.InputError, r"wrap: 'x' is not a mode", scene.add_texture, np.zeros((4, 4, 4), np.uint8), wrap="x")
    refused(frugal.InputError, r"material: texture 0 does not exist", scene.add_material, (1, 1, 1), texture=0)
    refused(frugal.InputError, r"color: value 1 is nan, not finite", scene.add_material, (1, np.nan, 1))
    refused(frugal.InputError, r"material: metallic 1.5 is not in \[0, 1\]", scene.add_material, metallic=1.5)
    refused(frugal.InputError, r"material: roughness nan is not in \[0, 1\]", scene.add_material, roughness=np.nan)
    refused(frugal.InputError, r"material: normal texture 0 does not exist", scene.add_material, normal_texture=0)
    refused(frugal.InputError, r"material: occlusion strength -1 is not in \[0, 1\]", scene.add_material,
            occlusion_strength=-1)
    refused(frugal.InputError, r"alpha: 'glass' is not an alpha mode \(opaque, mask, blend\)", scene.add_material,
            alpha="glass")
    refused(frugal.InputError, r"material: alpha cutoff -0.5 is not finite and at least 0", scene.add_material,
            alpha="mask", alpha_cutoff=-0.5)
    refused(frugal.InputError, r"instance: mesh 0 does not exist \(the scene has 0\)", scene.add_instance, 0)
    mesh = scene.add_mesh(POSITIONS, INDICES)
    refused(frugal.InputError, r"transform: expected a 4x4 matrix, got shape \(3, 3\)", scene.add_instance, mesh,
            np.eye(3))
    bad = np.eye(4)
    bad[1, 3] = np.inf
    refused(frugal.InputError, r"transform: row 1, column 3 is inf, not finite", scene.add_instance, mesh, bad)
    node = scene.add_instance(mesh)
    refused(frugal.InputError, r"node 7 does not exist \(the scene has 1\)", scene.set_transform, 7, np.eye(4))
    assert node == 0 and scene.instance_count == 1


def test_bad_files():
    refused(frugal.Error, r"no-such\.obj", frugal.load, "/nonexistent/no-such.obj")
    refused(frugal.InputError, r"builtin:nope", frugal.load, "builtin:nope")


def test_bad_settings():
    scene = frugal.load("builtin:cubes?count=2")
    refused(frugal.InputError, r"unknown setting 'colour' \(.*background", frugal.Renderer, scene, colour=1)
    methods = ", ".join(next(s for s in frugal.settings_schema() if s["name"] == "cull")["choices"])
    refused(frugal.InputError, re.escape(f"cull: 'x' is not a method ({methods})"), frugal.Renderer, scene, cull="x")
    refused(frugal.InputError, r"size: 'big' is not a size \(WxH, each 1 to 65536\)", frugal.Renderer, scene,
            size="big")
    refused(frugal.InputError, r"size: \(0, 5\) is not a size \(WxH, each 1 to 65536\)", frugal.Renderer, scene,
            size=(0, 5))
    refused(frugal.InputError, r"reuse: 1 is not true or false", frugal.Renderer, scene, reuse=1)
    refused(frugal.InputError, r"threads: 2\.5 is not a whole number from 0 to 256", frugal.Renderer, scene,
            threads=2.5)
    refused(frugal.InputError, r"reuse=True with cull='oracle': the oracle is an id pass", frugal.Renderer, scene,
            reuse=True, cull="oracle")


def in_python(code, **env):
    """Runs `code` in a fresh interpreter (with this one's module) and returns its stdout."""
    environment = dict(os.environ, **env)
    environment["PYTHONPATH"] = os.pathsep.join(sys.path)
    result = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                            env=environment, timeout=120)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_out_of_memory_is_checked_before_the_target():
    """Under a 2 GB address-space limit an 8192 x 8192 target (36 bytes a pixel) is refused."""
    out = in_python("""
        import resource, frugal
        scene = frugal.load("builtin:cubes?count=2")
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
        try:
            frugal.Renderer(scene, size=(8192, 8192), backend="software")
        except frugal.OutOfMemory as e:
            print("OutOfMemory:", e)
    """)
    assert out.startswith("OutOfMemory: size 8192x8192: needs about 2.4 GB"), out


def test_no_egl_vendor_is_backend_unavailable_and_auto_falls_back():
    """The headless-container failure: no EGL vendor library. One line; auto takes OSMesa instead."""
    out = in_python("""
        import frugal
        scene = frugal.load("builtin:cubes?count=2")
        try:
            frugal.Renderer(scene, size=(32, 24), backend="egl-surfaceless")
        except frugal.BackendUnavailable as e:
            print("BackendUnavailable:", e)
        try:
            print("auto:", frugal.Renderer(scene, size=(32, 24)).backend)
        except frugal.BackendUnavailable as e:
            print("auto: unavailable:", e)
    """, __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent/vendor.json")
    lines = out.splitlines()
    assert lines[0] == ("BackendUnavailable: backend egl-surfaceless: no usable GL context: egl-surfaceless: no EGL "
                        "display: no EGL vendor library answered (libglvnd reads /usr/share/glvnd/egl_vendor.d; "
                        "Debian: libegl-mesa0) (__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json is set)"), out
    assert lines[1] in ("auto: osmesa", "auto: unavailable: backend auto: no usable GL context") or \
        lines[1].startswith("auto: unavailable: backend auto: no usable GL context"), out


def test_bad_cameras_and_frames():
    scene = frugal.load("builtin:cubes?count=2")
    refused(frugal.InputError, r"eye and target coincide", frugal.Camera.look_at, (1, 2, 3), (1, 2, 3))
    refused(frugal.InputError, r"fov: 180\.0+ degrees: must be above 0 and below 180", frugal.Camera.look_at,
            (0, 0, 5), (0, 0, 0), fov=180)
    refused(frugal.InputError, r"eye: expected 3 numbers, got shape \(2,\)", frugal.Camera.look_at, (0, 5), (0, 0, 0))
    refused(frugal.InputError, r"pose: row 0, column 0 is nan", frugal.Camera.from_pose, np.full((4, 4), np.nan))
    renderer = frugal.Renderer(scene, size=(32, 24))
    refused(frugal.InputError, r"camera 2: the scene has 0 cameras|camera 2", renderer.render,
            frugal.Camera.from_scene(2))
    refused(frugal.InputError, r"time: nan is not finite", renderer.render, time=float("nan"))
    refused(frugal.InputError, r"ids: the frame has no ids", renderer.render().write, ids="x.png")
    refused(frugal.IoError, r"/nonexistent/c\.png", renderer.render().write, color="/nonexistent/c.png")


def test_without_osmesa_the_module_starts_and_renders_with_egl(tmp_path):
    """Mesa 25.1 and later have no OSMesa: frugal loads it only when asked for. With libOSMesa
    hidden (a private mount namespace binds /dev/null over it), the module imports, auto renders
    with EGL, and asking for osmesa is BackendUnavailable with the reason."""
    from conftest import require
    library = Path("/usr/lib/x86_64-linux-gnu/libOSMesa.so.8")
    require(library.exists(), f"{library} (Debian libosmesa6), to hide")
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True)
    require(probe.returncode == 0, "a private mount namespace (unshare -m: root)")
    script = tmp_path / "no_osmesa.py"
    script.write_text(textwrap.dedent("""
        import frugal
        scene = frugal.load("builtin:cubes?count=2")
        print("auto:", frugal.Renderer(scene, size=(32, 24)).backend)
        try:
            frugal.Renderer(scene, size=(32, 24), backend="osmesa")
        except frugal.BackendUnavailable as e:
            print("osmesa:", e)
    """))
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    hidden = library.resolve()
    result = subprocess.run(["unshare", "-m", "sh", "-c", f"mount --bind /dev/null {hidden} && "
                             f"exec {sys.executable} {script}"], capture_output=True, text=True, env=environment,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "auto: egl-surfaceless", result.stdout
    assert lines[1].startswith("osmesa: backend osmesa: no usable GL context: osmesa: cannot load libOSMesa.so.8 ("), \
        result.stdout
    assert lines[1].endswith("Mesa 25.1 and later have no OSMesa; Debian 12: apt-get install libosmesa6"), result.stdout
