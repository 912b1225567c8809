"""slc: stochastic light culling for VPLs on GGX microsurfaces, from Python.

Render, compare and analyse single-bounce global illumination with many virtual point lights
(VPLs) on the CPU or the GPU (wgpu). Images come back as H×W×3 float32 numpy arrays of linear
radiance, each frame's ``report`` is the dict ``slc render`` writes as ``report.json``.

    >>> import slc
    >>> frame = slc.render(width=64, height=48)
    >>> frame.indirect.shape
    (48, 64, 3)

A :class:`Scene` keeps what the backends build of it (BVH, GPU buffers) between calls, so a
sweep renders it many times without reloading; its camera, lights and materials can be
changed (``with_camera``, ``with_lights``, ``with_materials``), checked as a settings file's
are. :func:`sweep` renders a grid of options here, on a Ray cluster or on any
``concurrent.futures.Executor``. A :class:`Frame` shows itself in Jupyter and saves itself
(``Frame.save``: PNG or layered EXR).

Every call works without holding the GIL, stops on Ctrl-C with ``KeyboardInterrupt`` (within
a tile or a pass), and shows progress with ``progress=True`` (tqdm's bar if installed) or
reports it to a callable. Errors of the library are :class:`SlcError` with its message; an
unknown option or a value of the wrong type is a ``TypeError``, a value out of its range or
an unknown name (strategy, backend...) a ``ValueError``. ``help(slc.render)`` lists every
option.
"""

import inspect
from typing import Any, Dict

from ._options import document
from ._scene import Scene
from ._slc import BUILTIN_SCENES as _BUILTIN_SCENES
from ._slc import STRATEGIES as _STRATEGIES
from ._slc import Frame, SlcError, __version__
from ._sweep import sweep

__all__ = [
    "BUILTIN_SCENES",
    "Frame",
    "STRATEGIES",
    "Scene",
    "SlcError",
    "__version__",
    "compare",
    "render",
    "sweep",
]

#: Names of the culling strategies (``culling=``), from the library's own list.
STRATEGIES = tuple(_STRATEGIES)
#: Names of the scenes built into slc (``Scene.builtin(name)``).
BUILTIN_SCENES = tuple(_BUILTIN_SCENES)

_SCENE = [inspect.Parameter("scene", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None)]


def _scene(scene: Any) -> Scene:
    """``scene`` as a :class:`Scene`: a Scene, a path or built-in name, or None (the default)."""
    if isinstance(scene, Scene):
        return scene
    return Scene(scene)


@document("render", _SCENE)
def render(scene: Any = None, **options: Any) -> Frame:
    """Renders one frame of ``scene`` (a :class:`Scene`, a file path, a built-in name, or
    None for the built-in default) and returns a :class:`Frame`. A path or name is loaded
    for this call; keep a :class:`Scene` to render it again without loading it.

    Options (keyword only; the defaults are those of ``slc render``):
{options}

    Raises ``TypeError`` for an unknown option or a value of the wrong type, ``ValueError``
    for a value out of its range or an unknown name, :class:`SlcError` for what the library
    refuses, ``KeyboardInterrupt`` on Ctrl-C."""
    return _scene(scene).render(**options)


@document(
    "compare",
    _SCENE
    + [
        inspect.Parameter("culling", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None),
        inspect.Parameter("reference", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=True),
    ],
)
def compare(scene: Any = None, culling: Any = None, reference: bool = True, **options: Any) -> Dict[str, Frame]:
    """Every strategy of ``culling`` (a list of names of :data:`STRATEGIES`; default: every
    one the backend runs; ``splatting`` and ``clustered-raster`` only with ``backend="gpu"``)
    on the same G-buffer, VPLs and ξ, each with its culling metrics (``Frame.lights``,
    ``Frame.fdr``, ``report["metrics"]``), and with ``reference`` every VPL with p = 1 as
    ``"reference_vpl"``. Returns a dict from name to :class:`Frame`.

    Options (keyword only):
{options}

    Raises as :func:`render` does; ``culling`` given as one string is a ``TypeError``."""
    return _scene(scene).compare(culling, reference, **options)
