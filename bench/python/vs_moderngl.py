#!/usr/bin/python3
"""frugal against moderngl, each used as a Python user would use it, on the same frame.

Both draw mesh 0 of the scene (the bunny by default) at --size with the same view and projection
matrices (those of a frugal frame through frugal.Camera.automatic()), the same triangles in the
same order (scene.mesh(0) gives them in frugal's drawing order), no face culling (an OBJ is
double-sided in frugal unless loaded with cull_backfaces=True), and the same lighting: frugal's
shaders/mesh.frag without texture or vertex colours, base colour white, and its default light
(src/pipeline/Backend.h, `Lighting`). Per frame, timed with time.perf_counter:

  frugal    f = r.render(cam); f.color; f.depth
            (colour is a view of the frame's memory; depth is converted from the 24-bit values to
            float32 window z on first access, a copy)
  moderngl  fbo.clear(...); vao.render(); then numpy arrays of
            fbo.read(components=4) and fbo.read(attachment=-1, dtype='f4'),
            flipped to top row first as frugal's are (views)
            on a standalone EGL context, RGBA8 colour and depth24 renderbuffers.

Blocks of --block frames alternate between the two in one process (the order rotates from round to
round); moderngl's context is made current for each of its blocks, outside the timing (frugal
makes its own current and releases it in every render). Reported: per-frame medians, p10, p90, the
ratio frugal / moderngl (the goal: <= 1.0), and how far the two last images agree: the fraction of
pixels whose coverage (depth below 1, i.e. not background) agrees, the mean absolute colour
difference, and the largest depth difference where both are covered. Also frugal's own phase
timings (render_ms, readback_ms: medians over 20 more frames after the timed ones).

If moderngl is missing or cannot make an EGL context, the JSON says "skipped" with the reason and
the script exits 0.

Run: PYTHONPATH=build/python /usr/bin/python3 bench/python/vs_moderngl.py [--json FILE]
"""

import sys
import time

import numpy as np

import benchutil

GOAL = 1.0  # frugal / moderngl, medians

# frugal's default light (src/pipeline/Backend.h, `Lighting`), in world space.
TO_LIGHT = (np.array([0.35, 0.8, 0.5]) / np.linalg.norm([0.35, 0.8, 0.5])).astype(np.float32)
AMBIENT, DIFFUSE = 0.3, 0.7

VERTEX_SHADER = """
#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_mvp;  // projection * view; the model matrix is the identity (checked)
out vec3 v_normal;   // world space, not normalised
void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
    v_normal = a_normal;
}
"""

# frugal's mesh.frag without the texture, vertex colour and id variants, base colour white.
FRAGMENT_SHADER = """
#version 330 core
in vec3 v_normal;
uniform vec3 u_toLight;  // world space, unit
uniform float u_ambient;
uniform float u_diffuse;
layout(location = 0) out vec4 o_color;
void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float lambert = max(0.0, dot(n, u_toLight));
    o_color = vec4(vec3(u_ambient + u_diffuse * lambert), 1.0);
}
"""

FAIRNESS = {
    "frugal": "r.render(cam): camera resolved and depth range fitted (a still scene's bounds kept from "
              "the first frame), context made current, a few state calls, clear, one indexed draw, glFinish, "
              "glReadPixels of colour (RGBA8) and of depth (GL_UNSIGNED_INT, shifted to the 24-bit values) "
              "into the memory of a frame no longer referenced, context released, a Frame object; "
              "then f.color (a view) and f.depth (float32 conversion, a copy)",
    "moderngl": "fbo.clear (colour and depth), vao.render (one indexed draw), fbo.read of colour (RGBA8) "
                "and of depth as float32 (Mesa converts), each into a new bytes object, wrapped by "
                "np.frombuffer and flipped (views); matrices and uniforms set once, before the loop",
    "common": "same llvmpipe, same triangles in the same order, same matrices, same shading arithmetic, "
              "no face culling, depth test less, 24-bit depth, one context current per block",
}


class Skipped(Exception):
    """moderngl cannot run here: the benchmark reports why instead of failing."""


class ModernglRenderer:
    """A moderngl context drawing mesh `mesh` (scene.mesh(0)'s dict) into an offscreen framebuffer."""

    def __init__(self, mesh, size, view, projection, background):
        try:
            import moderngl
        except ImportError as e:
            raise Skipped(f"cannot import moderngl: {e}") from None
        try:
            self.ctx = ctx = moderngl.create_standalone_context(backend="egl")
        except Exception as e:  # moderngl and glcontext raise plain Exceptions
            first_line = (str(e).splitlines() or [""])[0]
            raise Skipped(f"moderngl.create_standalone_context(backend='egl'): "
                          f"{type(e).__name__}: {first_line}") from None
        self.info = {"gl_renderer": ctx.info["GL_RENDERER"], "gl_version": ctx.info["GL_VERSION"],
                     "moderngl": moderngl.__version__}
        self.width, self.height = size
        self.background = tuple(background)
        self.triangles = moderngl.TRIANGLES
        with ctx:  # a new context is current already; `with` makes that explicit
            program = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=FRAGMENT_SHADER)
            # numpy is row-major, GLSL matrices column-major: the transpose's bytes.
            program["u_mvp"].write(np.ascontiguousarray((projection @ view).T, dtype=np.float32).tobytes())
            program["u_toLight"].value = tuple(float(x) for x in TO_LIGHT)
            program["u_ambient"].value = AMBIENT
            program["u_diffuse"].value = DIFFUSE
            vertices = np.hstack([mesh["positions"], mesh["normals"]]).astype(np.float32)
            self.vao = ctx.vertex_array(
                program, [(ctx.buffer(vertices.tobytes()), "3f 3f", "a_position", "a_normal")],
                index_buffer=ctx.buffer(np.ascontiguousarray(mesh["indices"], dtype=np.uint32).tobytes()),
                index_element_size=4)
            self.fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(size, components=4)],
                                       depth_attachment=ctx.depth_renderbuffer(size))
            ctx.enable(moderngl.DEPTH_TEST)  # depth function '<', face culling off: moderngl's defaults

    def render(self):
        """One frame: clear, draw, and the images as numpy arrays, top row first (as frugal's)."""
        self.fbo.clear(*self.background, depth=1.0)
        self.vao.render(self.triangles)
        color = np.frombuffer(self.fbo.read(components=4), np.uint8).reshape(self.height, self.width, 4)[::-1]
        depth = np.frombuffer(self.fbo.read(attachment=-1, dtype="f4"), np.float32).reshape(
            self.height, self.width)[::-1]
        return color, depth

    def block(self, frames):
        """`frames` timed frames with the context current; their milliseconds and the last images."""
        ms = []
        with self.ctx:
            self.fbo.use()
            for _ in range(frames):
                t0 = time.perf_counter()
                images = self.render()
                ms.append((time.perf_counter() - t0) * 1e3)
        return ms, images


def frugal_block(r, cam, frames):
    """`frames` timed frugal frames, colour and depth read; their milliseconds and the last frame."""
    ms = []
    for _ in range(frames):
        t0 = time.perf_counter()
        f = r.render(cam)
        f.color  # a view of the frame's memory
        f.depth  # 24-bit values to float32 window z, kept by the frame
        ms.append((time.perf_counter() - t0) * 1e3)
    return ms, f


def frugal_phases(r, cam, frames=20):
    """Medians of frugal's own timings of its phases (render_ms: clear, draws and glFinish;
    readback_ms) over `frames` more frames, rendered after the timed ones."""
    stats = [r.render(cam).stats for _ in range(frames)]
    return {"render_ms": round(float(np.median([s.render_ms for s in stats])), 4),
            "readback_ms": round(float(np.median([s.readback_ms for s in stats])), 4)}


def agreement(frame, moderngl_images):
    """How far a frugal frame and moderngl's (colour, depth) agree. Coverage is depth below 1 (the
    cleared value)."""
    (c1, d1), (c2, d2) = (frame.color, frame.depth), moderngl_images
    covered1, covered2 = d1 < 1.0, d2 < 1.0
    both = covered1 & covered2
    colour_diff = np.abs(c1[..., :3].astype(np.int16) - c2[..., :3].astype(np.int16))
    return {
        "coverage_agrees": round(float(np.mean(covered1 == covered2)), 6),
        "covered_fraction_frugal": round(float(covered1.mean()), 6),
        "covered_fraction_moderngl": round(float(covered2.mean()), 6),
        "mean_abs_color_diff": round(float(colour_diff.mean()), 4),  # 0..255, RGB, every pixel
        "pixels_color_diff_over_2": round(float(np.mean(colour_diff.max(axis=-1) > 2)), 6),
        "max_abs_depth_diff_covered": round(float(np.abs(d1[both] - d2[both]).max()), 8) if both.any() else None,
    }


def check_untransformed(scene, mesh):
    """This benchmark draws mesh 0 once with an identity model matrix: the scene must be just that."""
    if scene.mesh_count != 1 or scene.instance_count != 1:
        sys.exit(f"error: {scene.source}: {scene.mesh_count} meshes, {scene.instance_count} instances; "
                 "this benchmark needs one mesh placed once")
    if mesh["colors"] is not None or mesh["uvs"] is not None:
        sys.exit(f"error: {scene.source}: mesh 0 has vertex colours or uvs; the moderngl shader is the plain one")
    if not np.array_equal(scene.world_transform(scene.instances[0]["node"]), np.eye(4)):
        sys.exit(f"error: {scene.source}: the instance is transformed; the moderngl side draws mesh 0 untransformed")
    if mesh["material"] >= 0 and scene.materials[mesh["material"]]["color"] != (1.0, 1.0, 1.0, 1.0):
        sys.exit(f"error: {scene.source}: mesh 0's base colour is not white, as the moderngl shader's is")


def main():
    args, malloc, frugal, scene, r = benchutil.start(__doc__)
    width, height = args.size
    mesh = scene.mesh(0)
    check_untransformed(scene, mesh)
    cam = frugal.Camera.automatic()
    camera = r.render(cam).camera
    result = {
        **benchutil.run_header("vs_moderngl", benchutil.now_utc(), frugal, args, r),
        "camera": {k: getattr(camera, k) for k in ("eye", "forward", "yfov_degrees", "znear", "zfar")},
    }

    try:
        mgl = ModernglRenderer(mesh, (width, height), camera.view_matrix, camera.projection_matrix,
                            r.settings["background"])
    except Skipped as e:
        benchutil.log(f"skipped: {e}")
        benchutil.emit({**result, "skipped": str(e), "machine": benchutil.machine()}, args.json)
        return
    benchutil.log(f"moderngl {mgl.info['moderngl']} on {mgl.info['gl_renderer']}")

    machine = benchutil.machine()
    results, last = benchutil.run_interleaved({"frugal": lambda n: frugal_block(r, cam, n), "moderngl": mgl.block},
                                              args.frames, args.block, args.warmup)
    ratio = round(results["frugal"]["per_frame_ms"]["median"] / results["moderngl"]["per_frame_ms"]["median"], 4)
    benchutil.emit({
        **result,
        "moderngl": mgl.info,
        "frames_per_method": args.frames,
        "block": args.block,
        "warmup_per_method": args.warmup,
        "malloc": malloc,
        "fairness": FAIRNESS,
        "methods": results,
        "frugal_phases_ms": frugal_phases(r, cam),
        "ratio_frugal_over_moderngl": ratio,
        "goal_frugal_over_moderngl": GOAL,
        "meets_goal": ratio <= GOAL,
        "images": agreement(last["frugal"], last["moderngl"]),
        "machine": {**machine, "loadavg_after": benchutil.loadavg()},
    }, args.json)


if __name__ == "__main__":
    main()
