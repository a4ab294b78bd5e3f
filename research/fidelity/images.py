"""PNG reading and the three distances between two renders. Standard library only.

The distances, between images A and B of one size (8-bit RGBA):

  covered     a pixel whose alpha is at least 128. The references are drawn
              with 4x multisampling, so edge pixels are partly covered; a
              renderer without multisampling covers a pixel when its centre is
              inside, which "at least half covered" matches best.
  mean_diff   over the pixels both cover: the mean of |A - B| over R, G and B,
              in 8-bit levels (0-255).
  over_32     over the same pixels: the fraction with some channel off by more
              than 32 levels (what a viewer sees as a wrong colour, not noise).
  coverage    the fraction of all pixels covered by exactly one of the two.
"""

import struct
import zlib

COVERED_ALPHA = 128
FAR_LEVELS = 32

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # colour type -> samples per pixel


class PngError(Exception):
    pass


def read_png(path):
    """Returns (width, height, rgba) of an 8-bit PNG file, rgba a bytes of 4 per pixel."""
    with open(path, "rb") as f:
        return decode_png(f.read())


def decode_png(data):
    """Decodes an 8-bit grey, grey+alpha, RGB or RGBA PNG (not interlaced) to RGBA."""
    if not data.startswith(PNG_SIGNATURE):
        raise PngError("not a PNG file")
    pos, header, idat = 8, None, []
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) < length:
            raise PngError("truncated in its %s chunk" % kind.decode("latin-1"))
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        pos += 12 + length
    if header is None or not idat:
        raise PngError("no IHDR or IDAT chunk")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in _CHANNELS or interlace:
        raise PngError("unsupported PNG (bit depth %d, colour type %d, interlace %d)"
                       % (depth, colour, interlace))
    try:
        raw = zlib.decompress(b"".join(idat))
    except zlib.error as e:
        raise PngError("corrupt image data: %s" % e) from None
    bpp = _CHANNELS[colour]
    stride = width * bpp
    if len(raw) < height * (stride + 1):
        raise PngError("image data too short")
    pixels = _unfilter(raw, height, stride, bpp)
    return width, height, _to_rgba(pixels, colour)


def _unfilter(raw, height, stride, bpp):
    out = bytearray(height * stride)
    prev = bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:    # Sub
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif kind == 2:  # Up
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif kind == 3:  # Average
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif kind == 4:  # Paeth
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif kind != 0:
            raise PngError("unknown filter type %d in row %d" % (kind, y))
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return out


def _to_rgba(pixels, colour):
    if colour == 6:
        return bytes(pixels)
    n = len(pixels) // _CHANNELS[colour]
    rgba = bytearray(n * 4)
    if colour == 2:
        for c in range(3):
            rgba[c::4] = pixels[c::3]
        rgba[3::4] = b"\xff" * n
    elif colour == 0:
        for c in range(3):
            rgba[c::4] = pixels
        rgba[3::4] = b"\xff" * n
    else:  # 4: grey + alpha
        for c in range(3):
            rgba[c::4] = pixels[0::2]
        rgba[3::4] = pixels[1::2]
    return bytes(rgba)


def distance(a, b):
    """The three distances between two RGBA images given as (width, height, rgba)."""
    if a[:2] != b[:2]:
        raise ValueError("images differ in size: %dx%d and %dx%d" % (a[:2] + b[:2]))
    pa, pb = a[2], b[2]
    both = only_one = diff_sum = far = 0
    for i in range(0, len(pa), 4):
        ca, cb = pa[i + 3] >= COVERED_ALPHA, pb[i + 3] >= COVERED_ALPHA
        if ca != cb:
            only_one += 1
        elif ca:
            both += 1
            dr, dg, db = abs(pa[i] - pb[i]), abs(pa[i + 1] - pb[i + 1]), abs(pa[i + 2] - pb[i + 2])
            diff_sum += dr + dg + db
            if max(dr, dg, db) > FAR_LEVELS:
                far += 1
    pixels = len(pa) // 4
    return {
        "mean_diff": round(diff_sum / (3 * both), 3) if both else None,
        "over_32": round(far / both, 5) if both else None,
        "coverage": round(only_one / pixels, 5),
        "both_cover": both,
    }
