#!/usr/bin/env python3
"""Renders the fidelity references: every model of models.json by the Khronos
glTF Sample Renderer and by three.js, in headless Chromium.

Writes, under tests/data/fidelity/ (or --out):
  <name>/khronos.png, <name>/three.png   8-bit RGBA; alpha 0 where nothing is drawn
  manifest.json                          per model: file, camera, lights, time,
                                         renderer versions, three.js's distance
                                         from Khronos (images.py)

Both renderers see the set-up of scene.py: frugal's light and camera rule, no
tone mapping, 4x MSAA. The pages are page/khronos.html and page/three.html; the
renderers are the npm packages pinned in package.json (npm ci --ignore-scripts
in this folder first). One browser, one tab at a time. docs/fidelity.md tells
the whole story.

Exit status: 0 all rendered, 1 a model failed or the set-up is incomplete (one
`error: <what>: <why>` line each), 2 bad command line, 3 chromium missing.
"""

import argparse
import base64
import collections
import json
import signal
import sys
import time
from pathlib import Path

import chromium
import files
import images
import scene
import serve

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
DEFAULT_OUT = REPO / "tests" / "data" / "fidelity"
RENDERERS = {"khronos": "@khronosgroup/gltf-viewer", "three": "three"}
KHRONOS_MODULE = "@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js"

# The Khronos renderer prefilters its environment into 256-pixel cube maps with
# 2048 (diffuse) and 1024 (specular) samples per texel, and integrates its BRDF
# look-up tables at 1024x1024 with 512 samples per texel: over two minutes per
# page on SwiftShader. Its sampler class is not exported, so the module is served
# with these sizes changed. A uniform environment filters to the same constant
# at any size and sample count (each filter is a normalised average), so the
# cube maps shrink freely; the BRDF table does not depend on the environment and
# keeps its 512 samples per texel at 128x128, bilinearly filtered. Against the
# unchanged renderer: means 0.01 level apart, at most 4 levels on 4 pixels of
# ClearCoatTest (docs/fidelity.md).
KHRONOS_IBL_SIZES = [
    ("this.textureSize = 256;", "this.textureSize = 32;"),
    ("this.lambertianSampleCount = 2048;", "this.lambertianSampleCount = 64;"),
    ("this.ggxSampleCount = 1024;", "this.ggxSampleCount = 64;"),
    ("this.lutResolution = 1024;", "this.lutResolution = 128;"),
]


class SetupError(Exception):
    """Something this run needs is missing: packages, models list, a file."""


def size_arg(text):
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("expected WxH, e.g. 400x300, got %r" % text) from None
    if not (16 <= w <= 4096 and 16 <= h <= 4096):
        raise argparse.ArgumentTypeError("width and height must be 16 to 4096")
    return w, h


def package_versions():
    """{renderer: version} of the installed packages, which must be the pinned ones."""
    try:
        pins = json.loads((HERE / "package.json").read_text())["dependencies"]
    except (OSError, ValueError, KeyError) as e:
        raise SetupError("research/fidelity/package.json: %s" % e) from None
    versions = {}
    for renderer, package in RENDERERS.items():
        try:
            installed = json.loads((HERE / "node_modules" / package / "package.json").read_text())["version"]
        except (OSError, ValueError, KeyError):
            installed = None
        if installed != pins.get(package):
            raise SetupError("node_modules holds %s %s, package.json pins %s: run "
                             "`npm ci --ignore-scripts` in research/fidelity"
                             % (package, installed or "(nothing)", pins.get(package)))
        versions[renderer] = installed
    return versions


def khronos_module():
    """The Khronos renderer's module with the IBL sizes above."""
    source = (HERE / "node_modules" / KHRONOS_MODULE).read_text()
    for old, new in KHRONOS_IBL_SIZES:
        if source.count(old) != 1:
            raise SetupError("%s: expected `%s` once; the IBL patch no longer fits this version"
                             % (KHRONOS_MODULE, old))
        source = source.replace(old, new)
    return source.encode()


def load_models(path):
    try:
        listing = json.loads(Path(path).read_text())
        root, models = Path(listing["models_root"]), listing["models"]
    except (OSError, ValueError, KeyError) as e:
        raise SetupError("%s: %s" % (path, e)) from None
    for m in models:
        if not (isinstance(m, dict) and isinstance(m.get("name"), str) and isinstance(m.get("file"), str)):
            raise SetupError("%s: a model without a name and a file: %s" % (path, json.dumps(m)))
    names = [m["name"] for m in models]
    if len(set(names)) != len(names):
        raise SetupError("%s: model names are not unique" % path)
    return root, models


class ModelError(Exception):
    """One model could not be rendered; the others go on."""


# One reference image: the PNG as the browser encoded it, decoded (images.py),
# how many lights the file brought, and what the page logged.
Render = collections.namedtuple("Render", "png image file_lights console")


def render(browser, server, renderer, setup, timeout):
    """Renders one model with one renderer; returns a Render."""
    width, height = setup["size"]
    try:
        value, console = browser.run_page(
            server.url("/page/", renderer + ".html"),
            "renderReference(%s)" % json.dumps(setup), timeout, width, height)
        head, _, payload = value["image"].partition(",")
        if head != "data:image/png;base64":
            raise ModelError("%s: the canvas did not give a PNG" % renderer)
        png = base64.b64decode(payload)
        image = images.decode_png(png)
    except (chromium.BrowserError, images.PngError) as e:
        raise ModelError("%s: %s" % (renderer, e)) from None
    if image[:2] != (width, height):
        raise ModelError("%s: image is %dx%d, not %dx%d" % ((renderer,) + image[:2] + (width, height)))
    # Messages name the server's port, which changes from run to run.
    console = [line.replace(server.base, "") for line in console]
    return Render(png, image, value["file_lights"], console)


def covered(image):
    return sum(1 for a in image[2][3::4] if a >= images.COVERED_ALPHA)


def render_model(browser, server, root, model, size, versions, out, timeout):
    """Renders one model with both renderers, writes its images, returns its manifest entry."""
    name, path = model["name"], root / model["file"]
    t = float(model.get("time", 0.0))
    try:
        lo, hi = scene.scene_bounds(scene.read_gltf_json(path))
    except (OSError, scene.SceneError) as e:
        raise ModelError("%s: %s" % (model["file"], e)) from None
    camera = scene.camera_for(lo, hi, *size)
    lights = scene.light_setup()
    setup = {
        "model": server.url("/models/", model["file"]), "size": list(size),
        "camera": camera, "time": t,
        "light": {k: lights["directional"][k] for k in ("to_light", "intensity", "color")},
        "environment": {"radiance": lights["environment"]["uniform_radiance"]},
    }
    results = {}
    for renderer in RENDERERS:
        start = time.monotonic()
        result = results[renderer] = render(browser, server, renderer, setup, timeout)
        pixels = covered(result.image)
        print("%-8s %-32s %5.1f s  %6d pixels covered%s"
              % (renderer, name, time.monotonic() - start, pixels,
                 "  (%d console messages, in the manifest)" % len(result.console)
                 if result.console else ""),
              file=sys.stderr, flush=True)
        if not pixels:
            raise ModelError("%s: drew nothing" % renderer)

    for renderer, result in results.items():
        files.write_atomic(out / name / (renderer + ".png"), result.png)
    file_lights = results["khronos"].file_lights
    entry = {
        "name": name,
        "file": model["file"],
        "camera": camera,
        "bounds": {"min": lo, "max": hi},
        "lights": lights if not file_lights else {
            "file_lights": file_lights, "environment": lights["environment"]},
        "time": t,
        "renderers": dict(versions),
        "images": {r: "%s/%s.png" % (name, r) for r in RENDERERS},
        "three_vs_khronos": images.distance(results["three"].image, results["khronos"].image),
        "frugal": "frugal " + " ".join(scene.frugal_args(str(path), camera, t, "frugal.png")),
    }
    console = {r: results[r].console for r in RENDERERS if results[r].console}
    if console:
        entry["console"] = console  # what the pages warned about (unsupported extensions, ...)
    return entry


def main():
    ap = argparse.ArgumentParser(
        description="Render the fidelity references (Khronos glTF Sample Renderer and three.js) "
                    "of the models in models.json; see docs/fidelity.md.")
    ap.add_argument("--only", action="append", metavar="NAME",
                    help="render only this model (repeatable); the manifest keeps the others")
    ap.add_argument("--size", type=size_arg, default=(400, 300), metavar="WxH",
                    help="image size (default 400x300)")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT,
                    help="output folder (default tests/data/fidelity)")
    ap.add_argument("--models", type=Path, default=HERE / "models.json",
                    help="models list (default research/fidelity/models.json)")
    ap.add_argument("--chromium", help="browser executable (default: chromium on PATH)")
    ap.add_argument("--timeout", type=float, default=300.0,
                    help="seconds one render may take (default 300)")
    args = ap.parse_args()

    # Chromium runs in a session of its own: turn SIGTERM into an exit that
    # runs the clean-up, which kills it.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(128 + signal.SIGTERM))

    try:
        versions = package_versions()
        root, all_models = load_models(args.models)
        module = khronos_module()
        exe = chromium.find_chromium(args.chromium)
    except SetupError as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    except chromium.ChromiumUnavailable as e:
        print("error: chromium: %s" % e, file=sys.stderr)
        return 3
    unknown = sorted(set(args.only or []) - {m["name"] for m in all_models})
    if unknown:
        print("error: --only: no model named %s in %s" % (", ".join(unknown), args.models), file=sys.stderr)
        return 2
    models = [m for m in all_models if not args.only or m["name"] in args.only]

    manifest_path = args.out / "manifest.json"
    try:
        old = {m["name"]: m for m in json.loads(manifest_path.read_text())["models"]}
    except (OSError, ValueError, KeyError):
        old = {}
    entries, failed = {}, 0
    mounts = {"/page/": HERE / "page", "/pkg/": HERE / "node_modules", "/models/": root}
    try:
        with serve.Server(mounts, {"/khronos/gltf-viewer.module.js": module}) as server, \
                chromium.Browser(exe) as browser:
            versions["chromium"] = browser.version.get("product", "?")
            for model in models:
                try:
                    entries[model["name"]] = render_model(browser, server, root, model, args.size,
                                                          versions, args.out, args.timeout)
                except ModelError as e:
                    print("error: %s: %s" % (model["name"], e), file=sys.stderr)
                    failed += 1
    except chromium.ChromiumUnavailable as e:
        print("error: chromium: %s" % e, file=sys.stderr)
        return 3

    # Models not rendered this time keep their entries (and files) from before.
    manifest = {
        "about": "Fidelity references of research/fidelity/render_refs.py; docs/fidelity.md. "
                 "Image paths are relative to this file, model files to models_root.",
        "models_root": str(root),
        "setup": {
            "lights": scene.light_setup(),
            "tone_mapping": "none (Khronos: ToneMaps.NONE, exposure 1, output pow(c, 1/2.2); "
                            "three.js: NoToneMapping, SRGBColorSpace output)",
            "msaa": "4x (WebGL antialias: true on SwiftShader)",
            "background": "transparent (alpha 0)",
            "camera_rule": "look at the bounds' centre from direction %s at the distance where the "
                           "bounds' sphere fits the vertical fov of %g degrees" % (list(scene.VIEW_FROM), scene.FOV_DEG),
            "distances": "three_vs_khronos: mean_diff = mean |three - khronos| over R, G, B of the "
                         "pixels both cover (alpha >= 128), in 8-bit levels; over_32 = fraction of those "
                         "pixels with a channel off by more than 32; coverage = fraction of all pixels "
                         "covered by exactly one (research/fidelity/images.py)",
        },
        "models": [entries.get(m["name"]) or old[m["name"]]
                   for m in all_models if m["name"] in entries or m["name"] in old],
    }
    files.write_atomic(manifest_path, (files.json_text(manifest) + "\n").encode())
    if failed:
        print("error: %d of %d models failed" % (failed, len(models)), file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
