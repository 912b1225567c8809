"""slc: stochastic light culling for VPLs on GGX microsurfaces, from Python.

Render, compare and analyse single-bounce global illumination with many virtual point lights
(VPLs) on the CPU or the GPU (wgpu). Images come back as H×W×3 float32 numpy arrays of linear
radiance, each frame's ``report`` is the dict ``slc render`` writes as ``report.json``.

    >>> import slc
    >>> frame = slc.render(width=64, height=48)
    >>> frame.indirect.shape
    (48, 64, 3)

A :class:`Scene` keeps what the backends build of it (BVH, GPU buffers) between calls, so a
sweep renders it many times without reloading. Every call releases the GIL while it works and
shows progress bars (stderr) only with ``progress=True``. Errors of the library are raised as
:class:`SlcError` with its message; an unknown option or a value of the wrong type is a
``TypeError``, an unknown name (strategy, backend…) a ``ValueError``.
"""

from ._slc import STRATEGIES, Frame, Scene, SlcError, __version__

__all__ = [
    "BUILTIN_SCENES",
    "Frame",
    "STRATEGIES",
    "Scene",
    "SlcError",
    "__version__",
    "compare",
    "render",
]

#: Names of the scenes built into slc (``Scene.builtin(name)``).
BUILTIN_SCENES = ("default", "cornell-glossy")


def _scene(scene):
    """``scene`` as a :class:`Scene`: a Scene, a path or built-in name, or None (the default)."""
    if isinstance(scene, Scene):
        return scene
    return Scene(None if scene is None else str(scene))


def render(scene=None, **options):
    """Renders one frame of ``scene`` (a :class:`Scene`, a file path, a built-in name, or
    None for the built-in default) and returns a :class:`Frame`. The options are those of
    ``slc render`` (see the stubs): width=512, height=512, backend="cpu", culling="ellipsoid",
    delta=1e-3, interleave=8, seed=0, shader="vpl", rsm=64, ..."""
    return _scene(scene).render(**options)


def compare(scene=None, culling=None, reference=True, **options):
    """Every strategy of ``culling`` (default: each of :data:`STRATEGIES` the backend runs;
    ``splatting`` and ``clustered-raster`` only on ``backend="gpu"``) on the same
    G-buffer, VPLs and ξ, each with its culling metrics (``Frame.lights``, ``Frame.fdr``,
    ``report["metrics"]``), and with ``reference`` every VPL with p = 1 as
    ``"reference_vpl"``. Returns a dict from name to :class:`Frame`."""
    return _scene(scene).compare(culling=culling, reference=reference, **options)
