"""Type stubs of slc (the native module slc._slc and its wrappers)."""

from os import PathLike
from typing import Any, Literal, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
STRATEGIES: list[str]
BUILTIN_SCENES: tuple[str, ...]

Backend = Literal["cpu", "gpu"]
ShaderName = Literal["vpl", "vsgl"]
Lobes = Literal["both", "diffuse", "glossy"]
ReferenceName = Literal["vpl", "path"]
ImportanceName = Literal["flux", "bidirectional"]
VsglDiffuse = Literal["clamped", "sg"]
Strategy = Literal[
    "none",
    "sphere",
    "enclosing-sphere",
    "ellipsoid",
    "clustered",
    "clustered-sphere",
    "clustered-enclosing-sphere",
]

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
    NO_LIST: int

class Scene:
    """A scene loaded once; what the backends build of it is kept between calls."""

    def __init__(self, spec: Optional[str] = None) -> None:
        """A .gltf/.glb/.obj file, a .toml scene-settings file or a built-in name (None: the
        built-in default)."""
    @staticmethod
    def load(path: Union[str, PathLike[str]]) -> Scene: ...
    @staticmethod
    def builtin(name: str = "default") -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def triangles(self) -> int: ...
    @property
    def lights(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def source(self) -> Optional[PathLike[str]]: ...
    def render(
        self,
        *,
        width: int = 512,
        height: int = 512,
        backend: Backend = "cpu",
        culling: Strategy = "ellipsoid",
        delta: float = 1e-3,
        interleave: int = 8,
        seed: int = 0,
        shader: ShaderName = "vpl",
        rsm: int = 64,
        lobes: Lobes = "both",
        denoise: bool = True,
        visibility: bool = False,
        spp: int = 1,
        metrics: bool = False,
        reference: Optional[ReferenceName] = None,
        vsgls: int = 1024,
        importance: ImportanceName = "flux",
        camera_vsgls: int = 1024,
        vsgl_diffuse: VsglDiffuse = "clamped",
        progress: bool = False,
    ) -> Frame: ...
    def compare(
        self,
        culling: Optional[Sequence[Strategy]] = None,
        reference: bool = True,
        *,
        width: int = 512,
        height: int = 512,
        backend: Backend = "cpu",
        delta: float = 1e-3,
        interleave: int = 8,
        seed: int = 0,
        rsm: int = 64,
        lobes: Lobes = "both",
        denoise: bool = True,
        visibility: bool = False,
        spp: int = 1,
        progress: bool = False,
    ) -> dict[str, Frame]: ...
    def vpls(
        self,
        *,
        width: int = 512,
        height: int = 512,
        backend: Backend = "cpu",
        seed: int = 0,
        rsm: int = 64,
        lobes: Lobes = "both",
    ) -> VplArrays: ...
    def light_lists(
        self,
        *,
        width: int = 512,
        height: int = 512,
        backend: Backend = "cpu",
        culling: Strategy = "ellipsoid",
        delta: float = 1e-3,
        interleave: int = 8,
        seed: int = 0,
        rsm: int = 64,
        lobes: Lobes = "both",
    ) -> LightListArrays: ...

def render(
    scene: Union[Scene, str, PathLike[str], None] = None,
    *,
    width: int = 512,
    height: int = 512,
    backend: Backend = "cpu",
    culling: Strategy = "ellipsoid",
    delta: float = 1e-3,
    interleave: int = 8,
    seed: int = 0,
    shader: ShaderName = "vpl",
    rsm: int = 64,
    lobes: Lobes = "both",
    denoise: bool = True,
    visibility: bool = False,
    spp: int = 1,
    metrics: bool = False,
    reference: Optional[ReferenceName] = None,
    vsgls: int = 1024,
    importance: ImportanceName = "flux",
    camera_vsgls: int = 1024,
    vsgl_diffuse: VsglDiffuse = "clamped",
    progress: bool = False,
) -> Frame: ...
def compare(
    scene: Union[Scene, str, PathLike[str], None] = None,
    culling: Optional[Sequence[Strategy]] = None,
    reference: bool = True,
    *,
    width: int = 512,
    height: int = 512,
    backend: Backend = "cpu",
    delta: float = 1e-3,
    interleave: int = 8,
    seed: int = 0,
    rsm: int = 64,
    lobes: Lobes = "both",
    denoise: bool = True,
    visibility: bool = False,
    spp: int = 1,
    progress: bool = False,
) -> dict[str, Frame]: ...
