"""frugal: an offscreen OpenGL renderer that does only the work a scene requires.

    import frugal
    scene = frugal.load("robot.glb")
    r = frugal.Renderer(scene, size=(800, 600), cull="conservative")
    f = r.render(camera=frugal.Camera.look_at(eye=(0, 2, 5), target=(0, 0, 0), fov=45))
    f.color  # (600, 800, 4) uint8, top row first
    f.stats.render_ms, f.stats.cull.pvs  # typed statistics; f.stats.to_dict() is the render JSON's record

See docs/python.md in frugal's repository.
"""

from ._frugal import (  # noqa: F401
    BackendUnavailable,
    Camera,
    CullPreparation,
    CullStats,
    Error,
    Frame,
    FrameStats,
    HsrStats,
    InputError,
    InterpStats,
    Interrupted,
    IoError,
    OcclusionFrameStats,
    OutOfMemory,
    Renderer,
    ReuseCounts,
    ReuseStats,
    Scene,
    StateChanges,
    StateCosts,
    View,
    Writer,
    __version__,
    default_settings,
    load,
    settings,
    settings_names,
    settings_schema,
)

__all__ = [
    "BackendUnavailable", "Camera", "CullPreparation", "CullStats", "Error", "Frame", "FrameStats", "HsrStats",
    "InputError", "InterpStats", "Interrupted", "IoError", "OcclusionFrameStats", "OutOfMemory", "Renderer",
    "ReuseCounts", "ReuseStats", "Scene", "StateChanges", "StateCosts", "View", "Writer", "__version__",
    "default_settings", "load", "settings", "settings_names", "settings_schema",
]
