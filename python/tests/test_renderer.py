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
    assert set(r.cull_preparation) >= {"sphere_ms", "map_ms", "total_ms"} and r.state_costs is None
    assert r.static_pair_bytes == 0
    assert frugal.Renderer(scene, size=(64, 48), reuse=True).static_pair_bytes > 0


def test_close_and_context_manager():
    scene = frugal.load("builtin:cubes?count=3")
    with frugal.Renderer(scene, size=(32, 24)) as r:
        assert r.render().color.shape == (24, 32, 4)
    assert repr(r) == "<frugal.Renderer (closed)>"
    with pytest.raises(frugal.InputError, match="the renderer is closed"):
        r.render()
    r.close()  # twice is fine
