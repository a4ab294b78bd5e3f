"""The scene set-up shared by the references and frugal: camera rule, light, environment.

Lighting is frugal's default (src/pipeline/Backend.h, Lighting), in the
physical units all three renderers use:

  * a directional light towards (0.35, 0.8, 0.5) normalised, world space, of
    intensity 0.7 pi: a white Lambertian surface facing it reflects 0.7, since
    the Lambert lobe is albedo / pi;
  * a uniform white environment of radiance 0.3, for the diffuse and the
    specular (image-based) terms: a white Lambertian surface reflects 0.3
    from it in any orientation.

A file with KHR_lights_punctual lights of its own keeps them (plus the
environment) instead of the directional light.

The camera looks at the centre of the scene's bounds from a fixed direction,
at the distance where the bounds' sphere just fits the vertical field of view
(the smaller one at a landscape size). Its numbers are rounded before anyone
renders with them, so that `frugal render --eye ... --target ...` given the
manifest's numbers sees exactly what the references saw.
"""

import json
import math
import struct

FOV_DEG = 40.0                       # frugal's default vertical field of view
VIEW_FROM = (0.5, 0.4, 1.0)          # target -> eye: in front (+z), right and above, so a box shows three faces
UP = (0.0, 1.0, 0.0)

TO_LIGHT = tuple(c / math.sqrt(0.35 ** 2 + 0.8 ** 2 + 0.5 ** 2) for c in (0.35, 0.8, 0.5))
LIGHT_INTENSITY = 0.7 * math.pi
ENVIRONMENT_RADIANCE = 0.3


class SceneError(Exception):
    pass


def read_gltf_json(path):
    """The JSON part of a .gltf or .glb file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        if len(data) < 20:
            raise SceneError("truncated GLB header")
        length, kind = struct.unpack("<I4s", data[12:20])
        if kind != b"JSON":
            raise SceneError("GLB's first chunk is not JSON")
        data = data[20:20 + length]
    try:
        doc = json.loads(data)
    except (ValueError, UnicodeDecodeError) as e:
        raise SceneError("not valid JSON: %s" % e) from None
    if not isinstance(doc, dict):
        raise SceneError("the JSON is not an object")
    return doc


def _matmul(a, b):
    """Product of two 4x4 column-major matrices (flat lists of 16)."""
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def _node_matrix(node):
    """A node's local transform, column-major: its matrix, or T * R * S."""
    if "matrix" in node:
        return [float(v) for v in node["matrix"]]
    tx, ty, tz = node.get("translation", (0, 0, 0))
    qx, qy, qz, qw = node.get("rotation", (0, 0, 0, 1))
    sx, sy, sz = node.get("scale", (1, 1, 1))
    r = [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + qz * qw), 2 * (qx * qz - qy * qw),
         2 * (qx * qy - qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qx * qw),
         2 * (qx * qz + qy * qw), 2 * (qy * qz - qx * qw), 1 - 2 * (qx * qx + qy * qy)]
    return [r[0] * sx, r[1] * sx, r[2] * sx, 0,
            r[3] * sy, r[4] * sy, r[5] * sy, 0,
            r[6] * sz, r[7] * sz, r[8] * sz, 0,
            tx, ty, tz, 1]


def scene_bounds(doc):
    """(min, max) of the default scene in its rest pose (node transforms, no
    animation or skinning), from the POSITION accessors' min and max, which the
    glTF spec requires; rounded to a millionth of the scene's size."""
    nodes, meshes, accessors = doc.get("nodes", []), doc.get("meshes", []), doc.get("accessors", [])
    scenes = doc.get("scenes", [])
    if not scenes:
        raise SceneError("no scene")
    roots = scenes[doc.get("scene", 0)].get("nodes", [])
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    identity = [1.0 if r == c else 0.0 for c in range(4) for r in range(4)]
    stack = [(i, identity, ()) for i in roots]
    while stack:
        index, parent, path = stack.pop()
        if index in path:
            raise SceneError("node %d is its own ancestor" % index)
        node = nodes[index]
        world = _matmul(parent, _node_matrix(node))
        stack.extend((child, world, path + (index,)) for child in node.get("children", []))
        if "mesh" not in node:
            continue
        for primitive in meshes[node["mesh"]].get("primitives", []):
            position = primitive.get("attributes", {}).get("POSITION")
            if position is None:
                continue
            accessor = accessors[position]
            if "min" not in accessor or "max" not in accessor:
                raise SceneError("accessor %d (POSITION) has no min/max" % position)
            a, b = accessor["min"], accessor["max"]
            for corner in ((x, y, z) for x in (a[0], b[0]) for y in (a[1], b[1]) for z in (a[2], b[2])):
                for i in range(3):
                    v = sum(world[k * 4 + i] * corner[k] for k in range(3)) + world[12 + i]
                    lo[i], hi[i] = min(lo[i], v), max(hi[i], v)
    if lo[0] > hi[0]:
        raise SceneError("the scene has no mesh to draw")
    if not all(math.isfinite(v) for v in lo + hi):
        raise SceneError("the scene's bounds are not finite")
    return _rounded(lo, lo, hi), _rounded(hi, lo, hi)


def _rounded(values, lo, hi):
    """values rounded to a millionth of the size of the box (lo, hi), as decimals:
    what the manifest and frugal's command line carry, free of float noise such as
    a centre at 5e-15 instead of 0."""
    size = max(math.dist(lo, hi), 1e-30)
    quantum = 10.0 ** (math.floor(math.log10(size)) - 6)
    return [float("%.12g" % (round(v / quantum) * quantum)) + 0.0 for v in values]


def camera_for(lo, hi, width, height):
    """The set-up's camera for bounds (lo, hi) and an image size."""
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = max(math.dist(lo, hi) / 2, 1e-6)
    # The sphere fits when it fits the narrower of the two fields of view.
    half_v = math.radians(FOV_DEG) / 2
    half_h = math.atan(math.tan(half_v) * width / height)
    distance = radius / math.sin(min(half_v, half_h))
    norm = math.sqrt(sum(c * c for c in VIEW_FROM))
    eye = [c + distance * d / norm for c, d in zip(centre, VIEW_FROM)]
    znear, zfar = _rounded([(distance - radius) / 2, 2 * (distance + radius)], lo, hi)
    return {
        "eye": _rounded(eye, lo, hi),
        "target": _rounded(centre, lo, hi),
        "up": list(UP),
        "yfov_deg": FOV_DEG,
        # Depth planes well around the sphere; they change only depth precision.
        "znear": znear,
        "zfar": zfar,
        "size": [width, height],
    }


def light_setup():
    return {
        "directional": {"to_light": list(TO_LIGHT), "intensity": LIGHT_INTENSITY,
                        "color": [1.0, 1.0, 1.0],
                        "note": "only where the file has no KHR_lights_punctual light"},
        "environment": {"uniform_radiance": ENVIRONMENT_RADIANCE},
    }


def frugal_args(model_path, camera, time, output):
    """frugal's command line for the same view (its --camera default could pick a
    file's camera, so eye and target are always given), on a transparent
    background so that its coverage can be read from alpha as the references',
    with 4 samples a pixel as their WebGL contexts have (antialias: true)."""
    num = lambda v: "%d" % v if v == int(v) else repr(v)
    vec = lambda v: ",".join(num(c) for c in v)
    return ["render", model_path, "-o", output, "--eye", vec(camera["eye"]),
            "--target", vec(camera["target"]), "--up", vec(camera["up"]),
            "--fov", num(camera["yfov_deg"]), "--size", "%dx%d" % tuple(camera["size"]),
            "--time", num(time), "--background", "0,0,0,0", "--samples", "4"]
