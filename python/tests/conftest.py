"""Shared fixtures of the module's tests: the command line they compare with (FRUGAL_CLI, set by
CTest), the bunny, and readers of the files the command line writes."""
import os
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest

BUNNY = "/usr/share/glmark2/models/bunny.obj"


def strict():
    """Under scripts/test (FRUGAL_TEST_STRICT=1) a missing dependency fails instead of skipping."""
    return os.environ.get("FRUGAL_TEST_STRICT") == "1"


def require(condition, why):
    if not condition:
        if strict():
            pytest.fail(f"{why} (FRUGAL_TEST_STRICT=1: a skip is a failure here)")
        pytest.skip(why)


@pytest.fixture(scope="session")
def cli():
    """The frugal command line built beside the module."""
    path = os.environ.get("FRUGAL_CLI") or shutil.which("frugal")
    require(path and Path(path).exists(), "no frugal command line (set FRUGAL_CLI)")
    return path


@pytest.fixture(scope="session")
def bunny():
    require(Path(BUNNY).exists(), f"{BUNNY} is missing (Debian glmark2-data)")
    return BUNNY


def run_cli(cli, *args):
    result = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, f"frugal {' '.join(map(str, args))}: {result.stderr}"
    return result


def read_png(path):
    """A PNG as frugal writes it (8-bit RGBA or 16-bit grey, not interlaced) as a numpy array, top
    row first: (H, W, 4) uint8 or (H, W) uint16."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert interlace == 0 and (depth, colour) in ((8, 6), (16, 0)), f"{path}: depth {depth}, colour type {colour}"
    channels, size = (4, 1) if colour == 6 else (1, 2)
    stride, bpp = width * channels * size, channels * size
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, stride + 1)
    rows = np.zeros((height, stride), dtype=np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        above = rows[y - 1] if y > 0 else np.zeros(stride, dtype=np.int32)
        if kind in (0, 2):
            rows[y] = (line + (above if kind == 2 else 0)) & 255
            continue
        out = np.zeros(stride, dtype=np.int32)  # Sub, Average, Paeth depend on the pixel to the left
        for x in range(stride):
            left = out[x - bpp] if x >= bpp else 0
            up, corner = above[x], (above[x - bpp] if x >= bpp else 0)
            if kind == 1:
                predict = left
            elif kind == 3:
                predict = (left + up) // 2
            else:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                predict = left if pa <= pb and pa <= pc else (up if pb <= pc else corner)
            out[x] = (line[x] + predict) & 255
        rows[y] = out
    pixels = rows.astype(np.uint8)
    if colour == 6:
        return pixels.reshape(height, width, 4)
    return pixels.reshape(height, width, 2).astype(np.uint16) @ np.array([256, 1], dtype=np.uint16)


def read_pfm(path):
    """A one-channel little-endian PFM as (H, W) float32, top row first (the file is bottom-up)."""
    data = Path(path).read_bytes()
    magic, size, scale, rest = data.split(b"\n", 3)
    assert magic == b"Pf" and float(scale) < 0, f"{path}: not a little-endian grey PFM"
    width, height = map(int, size.split())
    return np.frombuffer(rest, dtype="<f4").reshape(height, width)[::-1]


def read_ids(path):
    """An id PNG (RGBA bytes = the 32-bit id, little-endian) as (H, W) uint32."""
    return np.ascontiguousarray(read_png(path)).view("<u4")[..., 0]
