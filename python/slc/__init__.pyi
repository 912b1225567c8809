"""Type stubs of slc. The option TypedDicts and the Strategy names are checked against the
package by python/tests/test_api.py."""

import concurrent.futures
from os import PathLike
from pathlib import Path
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, TypedDict, Union

from typing_extensions import Unpack

import numpy as np
import numpy.typing as npt

__version__: str
STRATEGIES: tuple[str, ...]
BUILTIN_SCENES: tuple[str, ...]

Backend = Literal["cpu", "gpu"]
GpuTiled = Literal["one-pass", "lists"]
ShaderName = Literal["vpl", "vsgl"]
Lobes = Literal["both", "diffuse", "glossy"]
ReferenceName = Literal["vpl", "path"]
ImportanceName = Literal["flux", "bidirectional"]
VsglDiffuse = Literal["clamped", "sg"]
# "splatting" and "clustered-raster" run on the GPU backend only; the others on both.
Strategy = Literal[
    "none",
    "sphere",
    "enclosing-sphere",
    "ellipsoid",
    "clustered",
    "clustered-sphere",
    "clustered-enclosing-sphere",
    "tight",
    "clustered-tight",
    "binned",
    "splatting",
    "clustered-raster",
]
#: ``progress(done, total)``: pixel-passes (render, compare) or grid points (sweep) finished.
ProgressCallback = Callable[[int, int], None]
Layer = Literal["total", "direct", "indirect"]

class SlcError(Exception):
    """An error of the library: a scene that cannot be loaded or rendered, settings out of
    their domain."""

class Frame:
    """One rendered frame."""

    direct: npt.NDArray[np.float32]
    """Direct light, H×W×3 float32, linear radiance."""
    indirect: npt.NDArray[np.float32]
    """Indirect (one-bounce) light, H×W×3 float32."""
    total: npt.NDArray[np.float32]
    """direct + indirect, H×W×3 float32."""
    lights: Optional[npt.NDArray[np.uint32]]
    """VPLs each pixel was shaded with, H×W; None unless metrics were measured."""
    fdr: Optional[npt.NDArray[np.float32]]
    """False discovery rate of each pixel's list, H×W; None unless metrics were measured."""
    report: dict[str, Any]
    """The frame's report.json as a dict (provenance, settings, timings_ms, metrics, ...)."""
    def _repr_png_(self) -> bytes:
        """The total image as an 8-bit sRGB PNG (what Jupyter shows)."""
    def save(
        self, path: Union[str, PathLike[str]], layer: Optional[Layer] = None, exposure: float = 0.0
    ) -> None:
        """A .png (one layer, sRGB) or .exr (every layer, metrics, provenance), written
        completely or not at all."""

class VplArrays(TypedDict):
    position: npt.NDArray[np.float32]
    normal: npt.NDArray[np.float32]
    omega_i: npt.NDArray[np.float32]
    flux: npt.NDArray[np.float32]
    kd: npt.NDArray[np.float32]
    alpha: npt.NDArray[np.float32]
    xi: npt.NDArray[np.float32]
    glossy: npt.NDArray[np.bool_]
    id: npt.NDArray[np.uint32]

class LightListArrays(TypedDict):
    offsets: npt.NDArray[np.uint32]
    indices: npt.NDArray[np.uint32]
    lists: npt.NDArray[np.uint32]
    shared: npt.NDArray[np.uint32]
    NO_LIST: int

class FrameOptions(TypedDict, total=False):
    """What a frame is made of (defaults as ``slc render``)."""

    width: int  # 512
    height: int  # 512
    backend: Backend  # "cpu"
    seed: int  # 0: seed of ξ, interleaving and sampling (u32)
    rsm: int  # 64: RSM texels per side and face
    lobes: Lobes  # "both"

class CullingOptions(FrameOptions, total=False):
    """The stochastic estimate's culling."""

    delta: float  # 1e-3: δ of eq. (2)
    interleave: int  # 8: K of K×K interleaving

class ListOptions(CullingOptions, total=False):
    culling: Strategy  # "ellipsoid"

class CompareOptions(CullingOptions, total=False):
    gpu_tiled: Optional[GpuTiled]  # None ("one-pass"): backend="gpu"'s tiled strategies in one pass, or through light lists (the same image)
    denoise: bool  # True
    visibility: bool  # False: shadow rays to every listed VPL
    progress: Union[bool, None, ProgressCallback]  # False: True for a bar (tqdm's if installed), or a callback

class RenderOptions(CompareOptions, total=False):
    culling: Strategy  # "ellipsoid"
    spp: int  # 1: passes averaged (jittered pixels and texels, new VPLs and ξ each)
    shader: ShaderName  # "vpl"
    metrics: bool  # False: measure culling metrics (Frame.lights, Frame.fdr)
    reference: Optional[ReferenceName]  # None: "vpl" (every VPL, p = 1) or "path"
    vsgls: int  # 1024: with shader="vsgl"
    importance: ImportanceName  # "flux"
    camera_vsgls: int  # 1024: for importance="bidirectional"
    vsgl_diffuse: VsglDiffuse  # "clamped"

class Camera(TypedDict, total=False):
    """A settings file's [camera] table."""

    position: Sequence[float]
    target: Sequence[float]
    up: Sequence[float]
    yfov_deg: float
    znear: float
    zfar: float

class Scene:
    """A scene loaded once; what the backends build of it is kept between calls."""

    def __init__(self, spec: Union[str, PathLike[str], None] = None) -> None:
        """A .gltf/.glb/.obj file, a .toml scene-settings file or a built-in name (None: the
        built-in default)."""
    @classmethod
    def load(cls, path: Union[str, PathLike[str]]) -> Scene: ...
    @classmethod
    def builtin(cls, name: str = "default") -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def triangles(self) -> int: ...
    @property
    def lights(self) -> List[Dict[str, Any]]:
        """Each a settings file's [[lights]] table."""
    @property
    def camera(self) -> Optional[Camera]:
        """A settings file's [camera] table, or None."""
    @property
    def materials(self) -> list[str]: ...
    @property
    def loads(self) -> int:
        """Backends that built their state of the scene (BVH, GPU upload): once each."""
    @property
    def warnings(self) -> list[str]: ...
    @property
    def source(self) -> Optional[Path]: ...
    @property
    def files(self) -> List[Path]: ...
    def with_materials(
        self,
        pattern: str,
        *,
        kd: Optional[Sequence[float]] = None,
        f0: Optional[Sequence[float]] = None,
        alpha: Optional[float] = None,
        roughness: Optional[float] = None,
        eta: Optional[float] = None,
        double_sided: Optional[bool] = None,
        anisotropy_strength: Optional[float] = None,
        anisotropy_rotation: Optional[float] = None,
    ) -> Scene:
        """A copy with the materials `pattern` (name or glob) matches overridden."""
    def with_camera(self, camera: Optional[Camera] = None, **fields: Unpack[Camera]) -> Scene: ...
    def with_lights(self, lights: Sequence[Mapping[str, Any]], *, replace: bool = True) -> Scene: ...
    def render(self, **options: Unpack[RenderOptions]) -> Frame: ...
    def compare(
        self,
        culling: Optional[Sequence[Strategy]] = None,
        reference: bool = True,
        **options: Unpack[CompareOptions],
    ) -> dict[str, Frame]: ...
    def vpls(self, **options: Unpack[FrameOptions]) -> VplArrays: ...
    def light_lists(self, **options: Unpack[ListOptions]) -> LightListArrays: ...

SceneLike = Union[Scene, str, PathLike[str], None]

def render(scene: SceneLike = None, **options: Unpack[RenderOptions]) -> Frame: ...
def compare(
    scene: SceneLike = None,
    culling: Optional[Sequence[Strategy]] = None,
    reference: bool = True,
    **options: Unpack[CompareOptions],
) -> dict[str, Frame]: ...
def sweep(
    scene: SceneLike,
    grid: Mapping[str, Sequence[Any]],
    executor: Union[None, Literal["ray"], concurrent.futures.Executor] = None,
    *,
    images: bool = False,
    progress: Union[bool, None, ProgressCallback] = False,
    **options: Unpack[RenderOptions],
) -> List[Dict[str, Any]]: ...
