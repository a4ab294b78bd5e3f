"""A typed use of the module, as a mypy --strict user writes it: check-stubs.sh checks it against the
stubs (python/frugal/_frugal.pyi), then runs it."""
import numpy as np
import numpy.typing as npt

import frugal


def frame_summary(scene: frugal.Scene) -> dict[str, float]:
    """What a frame cost and did, through the typed statistics (an optional part checked first)."""
    with frugal.Renderer(scene, size=(64, 48), cull="conservative", order="key", background=(1, 1, 1)) as r:
        frame: frugal.Frame = r.render(frugal.Camera.look_at((0, 3, 9), (0, 0, 0), fov=45), time=0.0)
        color: npt.NDArray[np.uint8] = frame.color
        depth: npt.NDArray[np.float32] = frame.depth
        stats: frugal.FrameStats = frame.stats
        out = {"render_ms": stats.render_ms, "draws": float(stats.state_changes.draws),
               "covered": float((depth < 1.0).mean()), "red": float(color[..., 0].mean())}
        if stats.cull is not None:
            out["pvs"] = float(stats.cull.pvs)
        view: frugal.View = frame.camera
        out["znear"] = view.znear
        out["m00"] = float(view.view_matrix[0, 0])
        prepared: frugal.CullPreparation | None = r.cull_preparation
        if prepared is not None:
            out["prepare_ms"] = prepared.total_ms
        cull: str = r.settings["cull"]
        assert cull == "conservative"
        record: dict[str, object] = stats.to_dict()
        assert "pvs" in record
    return out


def reuse_modes(frames: int) -> list[str]:
    scene = frugal.load("builtin:dominoes?polygons=204")
    r = frugal.Renderer(scene, size=(64, 48), reuse=True)
    modes: list[str] = []
    for i in range(frames):
        reuse = r.render(time=i / scene.fps).stats.reuse
        if reuse is not None:
            modes.append(reuse.mode)
    return modes


if __name__ == "__main__":
    try:
        print(frame_summary(frugal.load("builtin:cubes?count=3")), reuse_modes(3))
    except frugal.Error as e:
        raise SystemExit(f"error: {e}")
