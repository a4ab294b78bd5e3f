"""What a renderer tells about itself, and closing it."""
import pytest

import frugal


def test_settings_round_trip_and_defaults():
    scene = frugal.load("builtin:cubes?count=3")
    r = frugal.Renderer(scene, size="64x48", cull="conservative", cull_bins="8x16", order="key", background=(1, 1, 1))
    assert r.settings == dict(frugal.default_settings(), size=(64, 48), cull="conservative", cull_bins=(8, 16),
                              order="key", background=(1.0, 1.0, 1.0, 1.0))
    assert sorted(frugal.settings_names()) == sorted(frugal.default_settings())
    assert r.backend in ("egl-surfaceless", "egl-device", "osmesa", "software")
    assert r.backend_log and r.backend_renderer
    assert r.triangle_count == scene.triangle_count == 36
    prepared = r.cull_preparation
    assert isinstance(prepared, frugal.CullPreparation) and r.state_costs is None
    assert prepared.total_ms >= prepared.map_ms >= 0 and prepared.sphere_ms >= 0 and not prepared.hull
    assert r.static_pair_bytes == 0
    assert r.extra_bytes == prepared.bytes > 0, "culling's maps, nothing else"
    reusing = frugal.Renderer(scene, size=(64, 48), reuse=True)
    assert reusing.extra_bytes == reusing.static_pair_bytes > 0
    assert frugal.Renderer(scene, size=(64, 48)).extra_bytes == 0


def test_occlusion_culling_gives_the_same_image_and_says_what_it_did():
    import numpy as np
    scene = frugal.load("builtin:dominoes?polygons=6000")
    with frugal.Renderer(scene, size=(160, 120), cull="conservative", ids=True) as plain, \
            frugal.Renderer(scene, size=(160, 120), cull="occlusion", ids=True) as culled:
        a, b = plain.render(), culled.render()
        assert np.array_equal(a.color, b.color) and np.array_equal(a.ids, b.ids)
        assert np.array_equal(a.depth, b.depth)
        occlusion = b.stats.cull.occlusion
        assert set(occlusion.to_dict()) == {"ran", "ms", "triangles_hidden"}
        assert occlusion.ahead is None and occlusion.ahead_wait_ms is None, "occlusion-ahead's only"
        assert b.stats.cull.pvs <= a.stats.cull.pvs
        assert a.stats.cull.occlusion is None and "occlusion" not in a.stats.to_dict()
        assert culled.extra_bytes > plain.extra_bytes or not occlusion.ran
    with pytest.raises(frugal.InputError, match="reuse=True with cull='occlusion'"):
        frugal.Renderer(scene, size=(32, 24), cull="occlusion", reuse=True)


def test_occlusion_ahead_makes_the_next_frames_plan_and_changes_no_image():
    import numpy as np
    scene = frugal.load("builtin:dominoes?polygons=6000")
    cameras = [frugal.Camera.look_at((x, 3.0, 40.0), (0.0, 2.0, 0.0)) for x in (-2.0, 0.0, 2.0)]
    with frugal.Renderer(scene, size=(160, 120), ids=True) as plain, \
            frugal.Renderer(scene, size=(160, 120), cull="occlusion-ahead", ids=True) as ahead:
        for i, camera in enumerate(cameras):
            following = cameras[i + 1] if i + 1 < len(cameras) else None
            a, b = plain.render(camera), ahead.render(camera, next_camera=following)
            assert np.array_equal(a.color, b.color) and np.array_equal(a.ids, b.ids)
            assert np.array_equal(a.depth, b.depth)
            assert b.stats.cull.occlusion.ahead == (i > 0)
        # A wrong guess costs a plan, not an image.
        b = ahead.render(cameras[0], next_camera=cameras[2])
        b = ahead.render(cameras[1])
        assert b.stats.cull.occlusion.ahead is False
        assert np.array_equal(b.color, plain.render(cameras[1]).color)
        with pytest.raises(frugal.InputError, match="next_time: .* is not finite"):
            ahead.render(cameras[0], next_time=float("nan"))


def test_tone_mapping_maps_the_lit_pixels_alike_on_both_backends():
    """tonemap= as the command line's --tonemap: each operator changes the lit pixels, not the
    background; GL and the software reference agree within a step; a bad name is refused."""
    import numpy as np
    scene = frugal.load("builtin:materials")

    def render(backend, **settings):
        with frugal.Renderer(scene, size=(96, 72), backend=backend, ids=True, **settings) as r:
            return r.render()

    plain = render("auto")
    background = plain.ids == 0
    for op in ("pbr-neutral", "aces"):
        mapped = render("auto", tonemap=op)
        assert np.array_equal(mapped.color[background], plain.color[background])
        assert (mapped.color[~background] != plain.color[~background]).any(axis=-1).mean() > 0.5
        assert np.abs(mapped.color.astype(int) - render("software", tonemap=op).color).max() <= 1
    assert np.array_equal(render("auto", tonemap="none").color, plain.color)
    with pytest.raises(frugal.InputError, match="tonemap: 'filmic' is not a tone-mapping operator"):
        frugal.Renderer(scene, tonemap="filmic")


def test_multisampling_smooths_edges_alike_on_both_backends():
    """samples= as the command line's --samples: 4 samples blend the edges with the background and
    keep the inside of surfaces; GL and the software reference agree (depth and ids exactly, each
    pixel's first sample); 2 is drawn as 4 here; a count that is not 1, 2, 4 or 8 is refused."""
    import numpy as np
    scene = frugal.load("builtin:cubes")

    def render(backend, **settings):
        with frugal.Renderer(scene, size=(192, 144), backend=backend, ids=True, background=(0, 0, 0), **settings) as r:
            return r.render()

    one = render("auto")
    four = render("auto", samples=4)
    edges = (one.color[..., :3] != four.color[..., :3]).any(axis=-1)
    assert 100 < edges.sum() < (one.ids != 0).sum() / 3
    software = render("software", samples=4)
    assert np.abs(four.color.astype(int) - software.color).max() <= 1
    assert np.array_equal(four.depth_values, software.depth_values)
    assert np.array_equal(four.ids, software.ids)
    assert np.array_equal(render("auto", samples=2).color, four.color)
    with pytest.raises(frugal.InputError, match="samples: 3 is not 1, 2, 4 or 8"):
        frugal.Renderer(scene, samples=3)


def test_a_transparent_background_gives_straight_alpha():
    """Over a transparent background a multisampled edge is partly covered: its alpha is the
    covered share and its colour the surface's own (straight alpha, as PNG defines it), not
    darkened by the background; with an opaque background every pixel has alpha 255."""
    import numpy as np
    scene = frugal.Scene()
    positions = np.array([[-1, -1, 0], [1, -0.7, 0], [0.2, 1, 0]], dtype=np.float32)
    material = scene.add_material((1.0, 0.5, 0.25), unlit=True, double_sided=True)
    scene.add_instance(scene.add_mesh(positions, np.array([[0, 1, 2]], dtype=np.uint32), material=material),
                       np.eye(4))
    camera = frugal.Camera.look_at((0, 0, 3), (0, 0, 0))
    for backend in ("auto", "software"):
        with frugal.Renderer(scene, size=(64, 48), samples=4, background=(0, 0, 0, 0), backend=backend) as r:
            f = r.render(camera)
        alpha = f.color[..., 3]
        inside = f.color[alpha == 255][:, :3]
        partial = (alpha > 0) & (alpha < 255)
        edge = f.color[partial][:, :3]
        assert len(inside) > 100 and len(edge) > 20
        # Within what 8 bits premultiplied by the alpha keep: half a step times 255 / alpha, and a
        # rounding on either side.
        error = np.abs(edge.astype(int) - inside[0]).max(axis=1)
        assert (error <= 255.0 / alpha[partial] / 2 + 1.5).all(), backend
        assert (f.color[alpha == 0] == 0).all()
        with frugal.Renderer(scene, size=(64, 48), samples=4, backend=backend) as r:
            assert (r.render(camera).color[..., 3] == 255).all()


def test_the_default_light_and_the_environment_are_keywords():
    """light= and environment= as --light and --environment: each changes only the lit pixels; no
    light and no environment leave the cubes black; bad values are refused with the expected form."""
    import numpy as np
    scene = frugal.load("builtin:cubes")

    def color(**settings):
        with frugal.Renderer(scene, size=(64, 48), background=(0, 0, 0), ids=True, **settings) as r:
            f = r.render()
            return f.color[..., :3].astype(int), f.ids != 0

    plain, covered = color()
    assert covered.sum() > 200
    assert np.array_equal(color(light="default", environment=0.3)[0], plain)
    assert color(light="none")[0][covered].sum() < plain[covered].sum() * 0.75
    assert color(environment=1)[0][covered].sum() > plain[covered].sum() * 1.25
    assert color(light="none", environment=0)[0].max() == 0
    with pytest.raises(frugal.InputError, match="environment: -1 is not a number from 0 to 1000000"):
        frugal.Renderer(scene, environment=-1)
    with pytest.raises(frugal.InputError, match="light: 'sun' is not a light"):
        frugal.Renderer(scene, light="sun")
    # shading="lambert": the diffuse approximation, the same triangles, GL and software alike.
    lambert, lambert_covered = color(shading="lambert")
    assert np.array_equal(lambert_covered, covered)
    assert (lambert != plain).any()
    with frugal.Renderer(scene, size=(64, 48), background=(0, 0, 0), backend="software", shading="lambert") as r:
        assert np.abs(r.render().color[..., :3].astype(int) - lambert).max() <= 1
    # no_environment_specular=True: the environment's diffuse lobe alone, never brighter.
    diffuse = color(no_environment_specular=True)[0]
    assert (diffuse[covered] < plain[covered]).any()
    assert (diffuse <= plain).all()


def test_an_environment_map_is_a_keyword(tmp_path):
    """environment_map= as --environment-map (a str or a path): a uniform map of 0.25 draws what
    environment=0.25 draws, within a level; a file that is not one raises InputError."""
    import numpy as np
    # A 16x8 Radiance file of 0.25 everywhere: RGBE (128, 128, 128, exponent -1 + 128), flat.
    hdr = tmp_path / "uniform.hdr"
    hdr.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n" + bytes([128, 128, 128, 127]) * 128)
    scene = frugal.load("builtin:cubes")

    def color(**settings):
        with frugal.Renderer(scene, size=(64, 48), **settings) as r:
            return r.render().color.astype(int)

    uniform = color(environment=0.25)
    assert np.abs(color(environment_map=hdr) - uniform).max() <= 1
    assert np.abs(color(environment_map=str(hdr)) - uniform).max() <= 1
    with frugal.Renderer(scene, size=(8, 8), environment_map=hdr) as r:
        assert r.settings["environment_map"] == str(hdr)
    (tmp_path / "text.hdr").write_text("hello")
    with pytest.raises(frugal.InputError, match="environment-map .*text.hdr: not a Radiance file"):
        frugal.Renderer(scene, environment_map=tmp_path / "text.hdr")
    with pytest.raises(frugal.InputError, match="environment_map: 3 is not a path"):
        frugal.Renderer(scene, environment_map=3)


def test_close_and_context_manager():
    scene = frugal.load("builtin:cubes?count=3")
    with frugal.Renderer(scene, size=(32, 24)) as r:
        assert r.render().color.shape == (24, 32, 4)
    assert repr(r) == "<frugal.Renderer (closed)>"
    with pytest.raises(frugal.InputError, match="the renderer is closed"):
        r.render()
    r.close()  # twice is fine


def test_the_module_needs_only_the_documented_libraries():
    """What the extension links (ELF NEEDED) is what docs/python.md lists for run time: Mesa's EGL
    and the loaders' libraries; never libOSMesa, which is loaded only when asked for."""
    import subprocess
    from pathlib import Path
    needed = {line.split("[")[1].rstrip("]") for line in subprocess.run(
        ["readelf", "-d", frugal._frugal.__file__], capture_output=True, text=True, check=True).stdout.splitlines()
        if "(NEEDED)" in line}
    documented = {"libEGL.so.1", "libtinygltf.so.2d", "libtinyobjloader.so.2rc10", "libmeshoptimizer.so.2d",
                  "libstb.so.0", "libgmp.so.10", "libstdc++.so.6", "libm.so.6", "libgcc_s.so.1",
                  "libc.so.6", "ld-linux-x86-64.so.2"}
    assert needed <= documented, needed - documented
    assert not any("OSMesa" in name for name in needed)
    page = (Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()
    for package in ("libegl1", "libegl-mesa0", "libgl1-mesa-dri", "libtinygltf2d", "libtinyobjloader2rc10",
                    "libmeshoptimizer2d", "libstb0", "libgmp10", "python3-numpy"):
        assert package in page, f"docs/python.md does not name {package}"


def test_a_settings_file_is_where_the_keyword_arguments_start(tmp_path, cli):
    """settings= reads the command line's settings file; keyword arguments win over it; the frame
    equals `frugal render --settings` of the same file."""
    import numpy as np
    from conftest import read_png, run_cli
    path = tmp_path / "settings.json"
    path.write_text('{"cull": "conservative", "order": "key", "size": "96x72", "reuse": true}')
    scene = frugal.load("builtin:cubes?count=6")
    r = frugal.Renderer(scene, settings=path, order="submit")
    assert (r.settings["cull"], r.settings["order"], r.settings["size"], r.settings["reuse"]) == \
        ("conservative", "submit", (96, 72), True)
    run_cli(cli, "render", "builtin:cubes?count=6", "--settings", path, "--order", "submit", "-q",
            "-o", tmp_path / "c.png")
    np.testing.assert_array_equal(r.render().color, read_png(tmp_path / "c.png"))
    path.write_text('{"reuse": "yes"}')
    with pytest.raises(frugal.InputError, match=r"settings .*settings\.json: key 'reuse': \"yes\" is not true or false"):
        frugal.Renderer(scene, settings=path)
    with pytest.raises(frugal.IoError, match="cannot read the file"):
        frugal.Renderer(scene, settings=tmp_path / "none.json")


def test_a_compressed_file_says_what_was_decoded():
    """A Draco-compressed file loads (libdraco is linked into the module, not needed at run time)
    and says what the loader decoded; an uncompressed one decodes nothing."""
    from pathlib import Path
    seeds = Path(__file__).resolve().parents[2] / "tests" / "data" / "compressed"
    scene = frugal.load(seeds / "quads-draco.gltf")
    assert scene.triangle_count == 2
    [entry] = scene.decompressed
    assert entry["method"] == "KHR_draco_mesh_compression"
    assert entry["items"] == 1 and entry["decoded_bytes"] == 72 and entry["seconds"] >= 0
    assert frugal.Renderer(scene, size=(32, 24)).render().color[..., 3].any()
    assert frugal.load("builtin:cubes?count=2").decompressed == []
