"""frugal.Writer: frames' files written on threads of their own while Python renders the next frame,
byte for byte what Frame.write and the command line write; png_level; errors raised once."""
import filecmp

import numpy as np
import pytest

import frugal
from conftest import read_png, run_cli


def test_a_sequence_written_by_the_writer_equals_the_command_line(tmp_path, cli):
    spec = "builtin:dominoes?polygons=204"
    run_cli(cli, "render", spec, "-q", "--size", "128x96", "--frames", "0:4", "-o", tmp_path / "c_%d.png",
            "--depth", tmp_path / "d_%d.png", "--ids", tmp_path / "i_%d.png")
    scene = frugal.load(spec)
    renderer = frugal.Renderer(scene, size=(128, 96), ids=True)
    with frugal.Writer() as writer:
        for i in range(5):
            frame = renderer.render(time=i / scene.fps)
            writer.write(frame, color=tmp_path / f"pc_{i}.png", depth=tmp_path / f"pd_{i}.png",
                         ids=tmp_path / f"pi_{i}.png")
            frame.color[:] = 0  # the writer copied the images: changing them now changes nothing written
    for i in range(5):
        for mine, theirs in (("pc", "c"), ("pd", "d"), ("pi", "i")):
            assert filecmp.cmp(tmp_path / f"{mine}_{i}.png", tmp_path / f"{theirs}_{i}.png", shallow=False), (mine, i)


def test_every_png_level_gives_the_same_pixels(tmp_path):
    renderer = frugal.Renderer(frugal.load("builtin:cubes"), size=(96, 64), backend="software")
    frame = renderer.render()
    with frugal.Writer(png_level=1, threads=1, queue=1) as writer:
        writer.write(frame, color=tmp_path / "w1.png")
    for level in ("auto", 0, 2, 12):
        frame.write(color=tmp_path / f"f{level}.png", png_level=level)
        np.testing.assert_array_equal(read_png(tmp_path / f"f{level}.png"), frame.color)
    np.testing.assert_array_equal(read_png(tmp_path / "w1.png"), frame.color)


def test_bad_input_gets_one_clear_error(tmp_path):
    for level in (13, -1, "fast", 2.0, True):
        with pytest.raises(frugal.InputError, match="png_level: .* must be 0 to 12 or 'auto'"):
            frugal.Writer(png_level=level)
    with pytest.raises(frugal.InputError, match="writer threads 65"):
        frugal.Writer(threads=65)
    renderer = frugal.Renderer(frugal.load("builtin:cubes"), size=(32, 24), backend="software")
    frame = renderer.render()
    writer = frugal.Writer()
    with pytest.raises(frugal.InputError, match="ids: the frame has no ids"):
        writer.write(frame, ids=tmp_path / "i.png")
    # A folder that is not there: the error comes with the next call, and nothing is left behind.
    writer.write(frame, color=tmp_path / "missing" / "c.png")
    with pytest.raises(frugal.IoError, match="missing/c.png: cannot write: No such file or directory"):
        writer.finish()
    with pytest.raises(frugal.IoError):
        writer.close()
    with pytest.raises(frugal.InputError, match="the writer is closed"):
        writer.write(frame, color=tmp_path / "c.png")
    assert list(tmp_path.iterdir()) == []


def test_an_exception_in_the_block_is_not_replaced(tmp_path):
    renderer = frugal.Renderer(frugal.load("builtin:cubes"), size=(32, 24), backend="software")
    frame = renderer.render()
    with pytest.raises(ZeroDivisionError):
        with frugal.Writer() as writer:
            writer.write(frame, color=tmp_path / "missing" / "c.png")
            1 / 0


def test_linear_colour_as_float32_and_its_files(tmp_path, cli):
    """linear=True: Frame.linear is the (H, W, 4) float32 colour in linear light, color its display
    encoding (on the software reference the 8-bit render's bytes); write(linear=...) writes what
    frugal render --linear writes, byte for byte."""
    spec = "builtin:materials"
    plain = frugal.Renderer(frugal.load(spec), size=(96, 64), backend="software").render()
    assert plain.linear is None
    renderer = frugal.Renderer(frugal.load(spec), size=(96, 64), backend="software", linear=True)
    frame = renderer.render()
    assert frame.linear.dtype == np.float32 and frame.linear.shape == (64, 96, 4)
    np.testing.assert_array_equal(frame.color, plain.color)
    lit = frame.linear[..., :3]
    assert lit.max() > 0.5
    # The display encoding, checked against numpy's: within a level (rounding at the halfway points).
    encoded = np.rint(np.clip(lit, 0, 1) ** (1 / 2.2) * 255)
    assert np.abs(encoded - frame.color[..., :3]).max() <= 1
    frame.write(linear=tmp_path / "p.pfm")
    with frugal.Writer() as writer:
        writer.write(frame, linear=tmp_path / "w.png")
    run_cli(cli, "render", spec, "-q", "--size", "96x64", "--backend", "software", "-o", tmp_path / "c.png",
            "--linear", tmp_path / "c.pfm")
    run_cli(cli, "render", spec, "-q", "--size", "96x64", "--backend", "software", "-o", tmp_path / "c2.png",
            "--linear", tmp_path / "c.png16.png")
    assert filecmp.cmp(tmp_path / "p.pfm", tmp_path / "c.pfm", shallow=False)
    assert filecmp.cmp(tmp_path / "w.png", tmp_path / "c.png16.png", shallow=False)
    with pytest.raises(frugal.InputError, match="linear: the frame has no linear colour"):
        plain.write(linear=tmp_path / "x.pfm")
    with pytest.raises(frugal.InputError, match=r"linear .*x\.exr: name it \.pfm \(float32\) or \.png \(16-bit\)"):
        frame.write(linear=tmp_path / "x.exr")
