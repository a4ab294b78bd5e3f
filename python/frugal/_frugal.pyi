# Types of frugal's extension module (python/src). Checked against the module built: by mypy's
# stubtest (every name, class, method and property, and their kinds: python/tests/check-stubs.sh,
# CTest PythonStubs). The settings' parts, between '# <settings: ...>' lines, are written by
# python/stubgen.py from the library's schema, frugal.settings_schema(); python/tests/test_stubs.py
# checks they are current.
import os
from types import TracebackType
from typing import Any, Literal, Sequence, TypedDict

import numpy as np
import numpy.typing as npt

__version__: str

# What pybind11 makes every class the module binds of: its base (pybind11_builtins.pybind11_object)
# and its metaclass. A class without a constructor of its own (every one but Scene, Renderer and
# Writer) keeps pybind11_object's __init__, which raises TypeError: the stubs give them none.
class _pybind11_type(type): ...
class _pybind11_object(metaclass=_pybind11_type): ...

# ---- errors: one line, "<what>: <why>" -------------------------------------------------------------

class Error(Exception): ...
class InputError(Error, ValueError): ...
class BackendUnavailable(Error, RuntimeError): ...
class OutOfMemory(Error, MemoryError): ...
class Interrupted(Error): ...
class IoError(Error, OSError): ...

# ---- settings: the keyword arguments of Renderer and settings(), one a setting of the schema ------

_Path = str | os.PathLike[str]
_Pair = tuple[int, int] | str  # (A, B), or "AxB" as the command line writes it
_Colour = Sequence[float]  # r, g, b or r, g, b, a, each 0 to 1

# The Literal of each choice setting.
# <settings: choices>
_Backend = Literal["auto", "egl", "egl-device", "egl-surfaceless", "osmesa", "software"]
_Interp = Literal["exact", "span", "dda"]
_Cull = Literal["none", "sphere", "backface", "cones", "paper", "conservative", "occlusion", "occlusion-ahead",
                "oracle"]
_Order = Literal["submit", "key", "paper", "greedy", "best"]
_Hsr = Literal["zbuffer", "depthsort", "adaptive", "adaptive-convex"]
_DepthFormat = Literal["d24", "d32f"]
_Tonemap = Literal["none", "pbr-neutral", "aces"]
_Shading = Literal["full", "lambert"]
_Light = Literal["default", "none"]
# </settings: choices>

# Every setting with its value, as default_settings(), settings() and Renderer.settings give them.
class _Settings(TypedDict):
    # <settings: dict>
    size: tuple[int, int]
    backend: _Backend
    threads: int
    interp: _Interp
    cull: _Cull
    cull_bins: tuple[int, int]
    order: _Order
    refine_costs: int
    reuse: bool
    reuse_grain: int
    reuse_cell: int
    no_fallback: bool
    exact_static: bool
    hsr: _Hsr
    depth_format: _DepthFormat
    tonemap: _Tonemap
    shading: _Shading
    no_mipmaps: bool
    light: _Light
    environment: float
    environment_map: str
    no_environment_specular: bool
    samples: int
    background: tuple[float, float, float, float]
    ids: bool
    linear: bool
    # </settings: dict>

# One setting of settings_schema().
class _SettingInfo(TypedDict):
    name: str
    option: str | None
    key: str
    kind: Literal["switch", "whole", "pair", "choice", "colour"]
    default: Any
    help: str
    choices: list[str]
    range: tuple[int, int] | None
    expected: str
    conflicts: list[str]

def settings(
    *,
    settings: _Path | None = ...,
    # <settings: keywords>
    size: _Pair = ...,
    backend: _Backend = ...,
    threads: int = ...,
    interp: _Interp = ...,
    cull: _Cull = ...,
    cull_bins: _Pair = ...,
    order: _Order = ...,
    refine_costs: int = ...,
    reuse: bool = ...,
    reuse_grain: int = ...,
    reuse_cell: int = ...,
    no_fallback: bool = ...,
    exact_static: bool = ...,
    hsr: _Hsr = ...,
    depth_format: _DepthFormat = ...,
    tonemap: _Tonemap = ...,
    shading: _Shading = ...,
    no_mipmaps: bool = ...,
    light: _Light = ...,
    environment: float = ...,
    environment_map: str | os.PathLike[str] = ...,
    no_environment_specular: bool = ...,
    samples: int = ...,
    background: _Colour = ...,
    ids: bool = ...,
    linear: bool = ...,
    # </settings: keywords>
) -> _Settings: ...
def settings_names() -> list[str]: ...
def default_settings() -> _Settings: ...
def settings_schema() -> list[_SettingInfo]: ...

# ---- scenes and cameras ----------------------------------------------------------------------------

class _SceneCamera(TypedDict):
    name: str
    node: int
    perspective: bool
    yfov_degrees: float
    aspect_ratio: float
    znear: float
    zfar: float

class _Instance(TypedDict):
    node: int
    mesh: int
    first_id: int
    triangles: int
    primitives: int

class _Decompression(TypedDict):
    method: str
    items: int
    compressed_bytes: int
    decoded_bytes: int
    seconds: float

class _Material(TypedDict):
    name: str
    color: tuple[float, float, float, float]
    texture: int | None
    double_sided: bool
    metallic: float
    roughness: float
    unlit: bool
    emissive: tuple[float, float, float]
    metallic_roughness_texture: int | None
    occlusion_texture: int | None
    occlusion_strength: float
    emissive_texture: int | None
    normal_texture: int | None
    normal_scale: float
    alpha: Literal["opaque", "mask", "blend"]
    alpha_cutoff: float
    specular: tuple[float, float, float] | None
    glossiness: float
    specular_glossiness_texture: int | None
    clearcoat: float
    clearcoat_roughness: float
    clearcoat_texture: int | None
    clearcoat_roughness_texture: int | None
    clearcoat_normal_texture: int | None
    clearcoat_normal_scale: float

class _MeshArrays(TypedDict):
    name: str
    topology: Literal["triangles", "lines", "points"]
    positions: npt.NDArray[np.float32]
    normals: npt.NDArray[np.float32]
    indices: npt.NDArray[np.uint32]
    triangle_source: npt.NDArray[np.uint32]
    colors: npt.NDArray[np.float32] | None
    uvs: npt.NDArray[np.float32] | None
    tangents: npt.NDArray[np.float32] | None
    material: int

class Scene(_pybind11_object):
    def __init__(self) -> None: ...
    def add_texture(self, pixels: npt.ArrayLike, *, wrap: Literal["repeat", "clamp", "mirror"] = ...,
                    filter: Literal["linear", "nearest"] = ...,
                    min_filter: Literal["linear", "nearest"] | None = ...,
                    mipmaps: Literal["none", "nearest", "linear"] = ..., srgb: bool = ..., name: str = ...) -> int: ...
    def add_material(self, color: _Colour = ..., *, texture: int | None = ..., double_sided: bool = ...,
                     metallic: float = ..., roughness: float = ..., unlit: bool = ..., emissive: Sequence[float] = ...,
                     metallic_roughness_texture: int | None = ..., occlusion_texture: int | None = ...,
                     occlusion_strength: float = ..., emissive_texture: int | None = ...,
                     normal_texture: int | None = ..., normal_scale: float = ...,
                     alpha: Literal["opaque", "mask", "blend"] = ..., alpha_cutoff: float = ...,
                     specular: Sequence[float] | None = ..., glossiness: float = ...,
                     specular_glossiness_texture: int | None = ..., clearcoat: float = ...,
                     clearcoat_roughness: float = ..., clearcoat_texture: int | None = ...,
                     clearcoat_roughness_texture: int | None = ..., clearcoat_normal_texture: int | None = ...,
                     clearcoat_normal_scale: float = ..., name: str = ...) -> int: ...
    def add_mesh(self, positions: npt.ArrayLike, indices: npt.ArrayLike, *, normals: npt.ArrayLike | None = ...,
                 colors: npt.ArrayLike | None = ..., uvs: npt.ArrayLike | None = ...,
                 tangents: npt.ArrayLike | None = ..., material: int | None = ..., name: str = ...,
                 file_order: bool = ..., topology: Literal["triangles", "lines", "points"] = ...) -> int: ...
    def add_light(self, kind: Literal["directional", "point", "spot"] = ..., *, color: Sequence[float] = ...,
                  intensity: float = ..., range: float = ..., inner_cone: float = ..., outer_cone: float = ...,
                  transform: npt.ArrayLike | None = ..., name: str = ...) -> int: ...
    def add_instance(self, mesh: int, transform: npt.ArrayLike | None = ..., *, name: str = ...) -> int: ...
    def set_transform(self, node: int, transform: npt.ArrayLike) -> None: ...
    def mesh(self, index: int) -> _MeshArrays: ...
    def world_transform(self, node: int, time: float = ...) -> npt.NDArray[np.float32]: ...
    def bounds(self, time: float = ...) -> tuple[tuple[float, float, float], tuple[float, float, float]]: ...
    @property
    def source(self) -> str: ...
    @property
    def mesh_count(self) -> int: ...
    @property
    def instance_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def duration(self) -> float: ...
    @property
    def fps(self) -> float: ...
    @property
    def node_names(self) -> list[str]: ...
    @property
    def cameras(self) -> list[_SceneCamera]: ...
    @property
    def instances(self) -> list[_Instance]: ...
    @property
    def materials(self) -> list[_Material]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def unsupported(self) -> list[str]: ...
    @property
    def decompressed(self) -> list[_Decompression]: ...

def load(spec: _Path, *, cull_backfaces: bool = ..., file_order: bool = ...) -> Scene: ...

class Camera(_pybind11_object):
    @staticmethod
    def look_at(eye: npt.ArrayLike, target: npt.ArrayLike, fov: float = ..., *, up: npt.ArrayLike = ...,
                near: float | None = ..., far: float | None = ...,
                depth_range: Literal["fit", "file"] = ...) -> Camera: ...
    @staticmethod
    def from_pose(pose: npt.ArrayLike, fov: float = ..., *, near: float | None = ..., far: float | None = ...,
                  depth_range: Literal["fit", "file"] = ...) -> Camera: ...
    @staticmethod
    def from_scene(index: int = ...) -> Camera: ...
    @staticmethod
    def automatic() -> Camera: ...

# ---- statistics: attributes named as the render JSON's keys; to_dict() is its object ---------------

class StateChanges(_pybind11_object):
    @property
    def draws(self) -> int: ...
    @property
    def programs(self) -> int: ...
    @property
    def meshes(self) -> int: ...
    @property
    def textures(self) -> int: ...
    @property
    def toggles(self) -> int: ...
    @property
    def uniforms(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class OcclusionFrameStats(_pybind11_object):
    @property
    def ran(self) -> bool: ...
    @property
    def ms(self) -> float: ...
    @property
    def triangles_hidden(self) -> int: ...
    @property
    def ahead(self) -> bool | None: ...
    @property
    def ahead_wait_ms(self) -> float | None: ...
    def to_dict(self) -> dict[str, Any]: ...

class CullStats(_pybind11_object):
    @property
    def tos(self) -> int: ...
    @property
    def pvs(self) -> int: ...
    @property
    def cull_ms(self) -> float: ...
    @property
    def ranges(self) -> int | None: ...
    @property
    def occlusion(self) -> OcclusionFrameStats | None: ...
    def to_dict(self) -> dict[str, Any]: ...

class ReuseCounts(_pybind11_object):
    @property
    def p_dd(self) -> int: ...
    @property
    def p_ds(self) -> int: ...
    @property
    def p_sd(self) -> int: ...
    @property
    def p_ss(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class ReuseStats(_pybind11_object):
    @property
    def mode(self) -> Literal["full", "rebuild", "reuse"]: ...
    @property
    def reason(self) -> str: ...
    @property
    def p_dd(self) -> int: ...
    @property
    def p_ds(self) -> int: ...
    @property
    def p_sd(self) -> int: ...
    @property
    def p_ss(self) -> int: ...
    @property
    def instances(self) -> ReuseCounts: ...
    @property
    def copied_px(self) -> int: ...
    @property
    def cleared_px(self) -> int: ...
    @property
    def redrawn_tris(self) -> int: ...
    @property
    def static_redrawn_tris(self) -> int: ...
    @property
    def rects(self) -> int: ...
    @property
    def plan_ms(self) -> float: ...
    @property
    def overlap_ms(self) -> float: ...
    @property
    def extent_ms(self) -> float: ...
    def to_dict(self) -> dict[str, Any]: ...

class HsrStats(_pybind11_object):
    @property
    def mode(self) -> _Hsr: ...
    @property
    def polygons(self) -> int: ...
    @property
    def zbuffered_polygons(self) -> int: ...
    @property
    def zbuffered_share(self) -> float: ...
    @property
    def draws(self) -> int: ...
    @property
    def plan_ms(self) -> float: ...
    def to_dict(self) -> dict[str, Any]: ...

class InterpStats(_pybind11_object):
    @property
    def mode(self) -> _Interp: ...
    @property
    def spans(self) -> int: ...
    @property
    def overflow(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class FrameStats(_pybind11_object):
    @property
    def time(self) -> float: ...
    @property
    def render_ms(self) -> float: ...
    @property
    def readback_ms(self) -> float: ...
    @property
    def cull(self) -> CullStats | None: ...
    @property
    def reuse(self) -> ReuseStats | None: ...
    @property
    def hsr(self) -> HsrStats | None: ...
    @property
    def state_changes(self) -> StateChanges: ...
    @property
    def interp(self) -> InterpStats | None: ...
    @property
    def refined_state_costs_us(self) -> list[float] | None: ...
    @property
    def refine_ms(self) -> float | None: ...
    def to_dict(self) -> dict[str, Any]: ...

class View(_pybind11_object):
    @property
    def source(self) -> str: ...
    @property
    def eye(self) -> tuple[float, float, float]: ...
    @property
    def forward(self) -> tuple[float, float, float]: ...
    @property
    def perspective(self) -> bool: ...
    @property
    def yfov_degrees(self) -> float: ...
    @property
    def znear(self) -> float: ...
    @property
    def zfar(self) -> float: ...
    @property
    def depth_range(self) -> Literal["fit", "file"]: ...
    @property
    def given_znear(self) -> float: ...
    @property
    def given_zfar(self) -> float: ...
    @property
    def depth_format(self) -> _DepthFormat: ...
    @property
    def aspect_ratio(self) -> float: ...
    @property
    def file_aspect_ratio(self) -> float | None: ...
    @property
    def aspect_ratio_differs(self) -> bool: ...
    @property
    def view_matrix(self) -> npt.NDArray[np.float32]: ...
    @property
    def projection_matrix(self) -> npt.NDArray[np.float32]: ...
    def to_dict(self) -> dict[str, Any]: ...

class StateCosts(_pybind11_object):
    @property
    def kinds(self) -> list[str]: ...
    @property
    def start_us(self) -> list[float]: ...
    @property
    def us(self) -> list[float]: ...
    @property
    def rounds(self) -> int: ...
    @property
    def refine_every(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

class CullPreparation(_pybind11_object):
    @property
    def sphere_ms(self) -> float: ...
    @property
    def map_ms(self) -> float: ...
    @property
    def cluster_ms(self) -> float: ...
    @property
    def hull_ms(self) -> float: ...
    @property
    def total_ms(self) -> float: ...
    @property
    def hull(self) -> bool: ...
    @property
    def bytes(self) -> int: ...
    def to_dict(self) -> dict[str, Any]: ...

# ---- frames, the renderer, the writer --------------------------------------------------------------

_PngLevel = int | Literal["auto"]

class Frame(_pybind11_object):
    @property
    def color(self) -> npt.NDArray[np.uint8]: ...
    @property
    def depth(self) -> npt.NDArray[np.float32]: ...
    @property
    def depth_values(self) -> npt.NDArray[np.uint32]: ...
    @property
    def ids(self) -> npt.NDArray[np.uint32] | None: ...
    @property
    def linear(self) -> npt.NDArray[np.float32] | None: ...
    @property
    def stats(self) -> FrameStats: ...
    @property
    def camera(self) -> View: ...
    def write(self, *, color: _Path | None = ..., depth: _Path | None = ..., ids: _Path | None = ...,
              linear: _Path | None = ..., png_level: _PngLevel = ...) -> None: ...

class Renderer(_pybind11_object):
    def __init__(
        self,
        scene: Scene,
        *,
        settings: _Path | None = ...,
        # <settings: renderer keywords>
        size: _Pair = ...,
        backend: _Backend = ...,
        threads: int = ...,
        interp: _Interp = ...,
        cull: _Cull = ...,
        cull_bins: _Pair = ...,
        order: _Order = ...,
        refine_costs: int = ...,
        reuse: bool = ...,
        reuse_grain: int = ...,
        reuse_cell: int = ...,
        no_fallback: bool = ...,
        exact_static: bool = ...,
        hsr: _Hsr = ...,
        depth_format: _DepthFormat = ...,
        tonemap: _Tonemap = ...,
        shading: _Shading = ...,
        no_mipmaps: bool = ...,
        light: _Light = ...,
        environment: float = ...,
        environment_map: str | os.PathLike[str] = ...,
        no_environment_specular: bool = ...,
        samples: int = ...,
        background: _Colour = ...,
        ids: bool = ...,
        linear: bool = ...,
        # </settings: renderer keywords>
    ) -> None: ...
    def render(self, camera: Camera | None = ..., time: float = ..., *, next_camera: Camera | None = ...,
               next_time: float | None = ...) -> Frame: ...
    def set_transform(self, node: int, transform: npt.ArrayLike) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> Renderer: ...
    def __exit__(self, *args: object) -> None: ...
    @property
    def backend(self) -> str: ...
    @property
    def backend_renderer(self) -> str: ...
    @property
    def backend_log(self) -> list[str]: ...
    @property
    def settings(self) -> _Settings: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def cull_preparation(self) -> CullPreparation | None: ...
    @property
    def state_costs(self) -> StateCosts | None: ...
    @property
    def static_pair_bytes(self) -> int: ...
    @property
    def extra_bytes(self) -> int: ...

class Writer(_pybind11_object):
    def __init__(self, *, threads: int = ..., queue: int = ..., png_level: _PngLevel = ...) -> None: ...
    def write(self, frame: Frame, *, color: _Path | None = ..., depth: _Path | None = ...,
              ids: _Path | None = ..., linear: _Path | None = ...) -> None: ...
    def finish(self) -> None: ...
    def close(self) -> None: ...
    def __enter__(self) -> Writer: ...
    def __exit__(self, type: type[BaseException] | None, value: BaseException | None,
                 traceback: TracebackType | None) -> None: ...
