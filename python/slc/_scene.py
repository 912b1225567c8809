"""``slc.Scene``: a scene loaded once and rendered many times, with its camera, lights and
materials changeable from Python (checked as a settings file's are). It wraps the native
scene (``slc._slc.Scene``), which keeps what the backends build of it (BVH, GPU buffers)
between calls; this layer documents the options and fills in their defaults
(``slc._options``), and turns ``progress=True`` into a bar (``slc._progress``)."""

import inspect
import os
from os import PathLike
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _slc
from ._options import complete, document
from ._progress import Reporter

# How a scene was made, to make it again elsewhere (pickling, sweep workers): how it was
# loaded ("spec", "load" or "builtin") with its argument, then each change in order.
Recipe = Tuple[str, str, Tuple[Tuple[str, Any], ...]]

_SELF = [inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)]

# Work runs on a pool of threads made on first use; a process forked after that has the
# pool's state without its threads, and would wait for them forever.
_worked = False
_forked_after_work = False


def _note_fork() -> None:
    global _forked_after_work
    _forked_after_work = _worked


os.register_at_fork(after_in_child=_note_fork)


def _work() -> None:
    """Called before each call that renders: refuses to work in a process forked after work
    (it would hang), and notes that work began."""
    global _worked
    if _forked_after_work:
        raise _slc.SlcError(
            "this process was forked after slc rendered, without slc's worker threads: render"
            " in a process started by 'spawn' or 'forkserver' (for a pool:"
            " ProcessPoolExecutor(mp_context=multiprocessing.get_context('spawn')))"
        )
    _worked = True


class Scene:
    """A scene loaded once; what the backends build of it (the CPU's BVH, the GPU's buffers)
    is kept between calls, so a sweep renders it many times without loading it again.

    ``Scene(spec)`` takes a ``.gltf``/``.glb``/``.obj`` file, a ``.toml`` scene-settings file
    (see ``scenes/README.md``) or a built-in name (``slc.BUILTIN_SCENES``; ``None``: the
    built-in default). A scene does not change: ``with_materials``, ``with_camera`` and
    ``with_lights`` return changed copies. Scenes pickle as the recipe that made them (the
    files are read again where they are unpickled)."""

    __slots__ = ("_native", "_recipe")

    def __init__(self, spec: Union[str, "PathLike[str]", None] = None):
        spec = "default" if spec is None else str(spec)
        self._native = _slc.Scene(spec)
        self._recipe: Recipe = ("spec", spec, ())

    @classmethod
    def _made(cls, native: Any, recipe: Recipe) -> "Scene":
        scene = cls.__new__(cls)
        scene._native = native
        scene._recipe = recipe
        return scene

    @classmethod
    def load(cls, path: Union[str, "PathLike[str]"]) -> "Scene":
        """A scene from a file: ``.gltf``, ``.glb``, ``.obj`` or a ``.toml`` settings file."""
        return cls._made(_slc.Scene.load(Path(path)), ("load", str(path), ()))

    @classmethod
    def builtin(cls, name: str = "default") -> "Scene":
        """A built-in scene (``slc.BUILTIN_SCENES``)."""
        return cls._made(_slc.Scene.builtin(name), ("builtin", name, ()))

    def _changed(self, native: Any, change: Tuple[str, Any]) -> "Scene":
        kind, argument, changes = self._recipe
        return Scene._made(native, (kind, argument, changes + (change,)))

    def __reduce__(self):
        return (_rebuild, (self._recipe,))

    @property
    def name(self) -> str:
        """The scene's name: the built-in name or the file's stem."""
        return self._native.name

    @property
    def triangles(self) -> int:
        """Triangles the scene has."""
        return self._native.triangles

    @property
    def lights(self) -> List[Dict[str, Any]]:
        """The lights, each a dict with the keys of a settings file's ``[[lights]]`` table
        (``type``, ``position``, ``direction``, ``intensity`` or ``irradiance``, ...)."""
        return self._native.lights

    @property
    def camera(self) -> Optional[Dict[str, Any]]:
        """The camera as a settings file's ``[camera]`` table (``position``, ``target``,
        ``up``, ``yfov_deg``, ``znear``, ``zfar``), or ``None``: one framing the scene."""
        return self._native.camera

    @property
    def materials(self) -> List[str]:
        """Names of the scene's materials."""
        return self._native.materials

    @property
    def loads(self) -> int:
        """How many times a backend built its state of this scene (the CPU's BVH, the GPU's
        upload): once per backend used, however many frames were rendered."""
        return self._native.loads

    @property
    def warnings(self) -> List[str]:
        """What the loader dropped or ignored, and what was changed from Python."""
        return self._native.warnings

    @property
    def source(self) -> Optional[Path]:
        """The scene file, or ``None`` for a built-in scene."""
        source = self._native.source
        return None if source is None else Path(source)

    @property
    def files(self) -> List[Path]:
        """Every file the scene was read from (settings, scene file, material libraries,
        buffers, textures), as the reports' provenance lists them with their SHA-256."""
        return [Path(f) for f in self._native.files]

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
    ) -> "Scene":
        """A copy with the materials ``pattern`` matches (a name, or a glob with ``*``)
        overridden, as a settings file's ``[[materials]]`` entry:

            kd, f0: [r, g, b] in [0, 1] (diffuse albedo, specular reflectance at normal
                incidence)
            alpha: GGX alpha in (0, 1], or roughness = sqrt(alpha) in (0, 1], not both
            eta: relative index of refraction > 0 (exact dielectric Fresnel)
            double_sided: whether the back faces are lit too
            anisotropy_strength: in [0, 1] (glTF KHR_materials_anisotropy);
                anisotropy_rotation: its rotation in radians

        ``ValueError`` when a value is out of range, the pattern matches no material or the
        override sets nothing. The copy is loaded anew on its first render."""
        values = dict(
            kd=kd,
            f0=f0,
            alpha=alpha,
            roughness=roughness,
            eta=eta,
            double_sided=double_sided,
            anisotropy_strength=anisotropy_strength,
            anisotropy_rotation=anisotropy_rotation,
        )
        native = self._native.with_materials(pattern, **values)
        return self._changed(native, ("materials", (pattern, values)))

    def with_camera(self, camera: Optional[Dict[str, Any]] = None, **fields: Any) -> "Scene":
        """A copy with another camera, given as a dict or as keywords with the keys of a
        settings file's ``[camera]`` table:

            position, target: [x, y, z] (the eye and the point looked at)
            up: [x, y, z], default [0, 1, 0]; not parallel to the view
            yfov_deg: the full vertical field of view in degrees, in (0, 180)
            znear, zfar: default 0.01 and 1000, 0 < znear < zfar

        Checked as in a settings file: an unknown key, a missing one, a value out of range
        or not finite is a ``ValueError``. ``scene.with_camera(scene.camera, yfov_deg=30)``
        changes one value (keywords win over the dict)."""
        table = dict(camera or {}, **fields)
        return self._changed(self._native.with_camera(table), ("camera", table))

    def with_lights(self, lights: Sequence[Dict[str, Any]], *, replace: bool = True) -> "Scene":
        """A copy with ``lights`` in place of the scene's (``replace=False``: added after
        them), each a dict with the keys of a settings file's ``[[lights]]`` table:

            {"type": "point", "position": [x, y, z], "intensity": [r, g, b] W/sr}
            {"type": "spot", "position": ..., "target": [x, y, z] or "direction": ...,
             "intensity": ..., "inner_cone_deg": 0, "outer_cone_deg": 45}
            {"type": "directional", "direction": [x, y, z], "irradiance": [r, g, b] W/m²}

        (an intensity or irradiance may be one number for grey). Checked as in a settings
        file: ``ValueError`` for an unknown key or type, a missing key, a value out of range
        or not finite, or no light left."""
        lights = [dict(light) if isinstance(light, Mapping) else light for light in lights]
        native = self._native.with_lights(lights, replace)
        return self._changed(native, ("lights", (lights, replace)))

    @document("render", _SELF)
    def render(self, **options: Any) -> Any:
        """Renders one frame and returns a ``Frame`` (images as H×W×3 float32 arrays of linear
        radiance, ``report`` as slc render's report.json). Ctrl-C stops it within a tile or a
        pass and raises ``KeyboardInterrupt``.

        Options (keyword only):
{options}

        Raises ``TypeError`` for an unknown option or a value of the wrong type,
        ``ValueError`` for a value out of its range or an unknown name, ``slc.SlcError`` for
        what the library refuses (a backend without what is asked, a frame too large for the
        memory)."""
        options = complete("render", options)
        with Reporter(options["progress"], f"rendering {self.name}") as r:
            options["progress"] = r.callback
            _work()
            return self._native.render(**options)

    @document(
        "compare",
        _SELF
        + [
            inspect.Parameter("culling", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=None),
            inspect.Parameter("reference", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=True),
        ],
    )
    def compare(
        self, culling: Optional[Sequence[str]] = None, reference: bool = True, **options: Any
    ) -> Dict[str, Any]:
        """Every strategy of ``culling`` (a list of names of ``slc.STRATEGIES``; ``None``:
        every one the backend runs) on the same G-buffer, VPLs and ξ, each with its culling
        metrics (``Frame.lights``, ``Frame.fdr``, ``report["metrics"]``), and with
        ``reference`` every VPL with p = 1 as ``"reference_vpl"``. Returns a dict from name to
        ``Frame``.

        Options (keyword only):
{options}

        Raises as ``render`` does; ``culling`` given as one string is a ``TypeError``."""
        options = complete("compare", options)
        with Reporter(options["progress"], f"comparing on {self.name}") as r:
            options["progress"] = r.callback
            _work()
            return self._native.compare(culling, reference, **options)

    @document("vpls", _SELF)
    def vpls(self, **options: Any) -> Dict[str, Any]:
        """The VPLs of the frame the options describe, as a dict of numpy arrays (one row per
        VPL): ``position``, ``normal``, ``omega_i`` (towards where the light came from),
        ``flux``, ``kd`` (N×3 float32), ``alpha`` (GGX roughness), ``xi`` (the Russian
        roulette's number) (N float32), ``glossy`` (N bool: the glossy lobe, else the diffuse
        one), ``id`` (N uint32).

        Options (keyword only):
{options}"""
        options = complete("vpls", options)
        _work()
        return self._native.vpls(**options)

    @document("light_lists", _SELF)
    def light_lists(self, **options: Any) -> Dict[str, Any]:
        """The light lists the strategy ``culling`` builds for the frame (culled on the
        CPU): ``lists`` is the list of each pixel (H×W uint32, ``NO_LIST`` where the pixel
        has none), list l holds the VPL indices (rows of ``vpls``)
        ``indices[offsets[l]:offsets[l + 1]]``. ``shared`` (H×W uint32) is each pixel's
        second list, one many pixels share (``binned``: the VPLs of large range that may
        reach its cell), ``NO_LIST`` where it has none and everywhere for the other
        strategies; a pixel is shaded with the union of its two lists.

        Options (keyword only):
{options}"""
        options = complete("light_lists", options)
        _work()
        return self._native.light_lists(**options)

    def __repr__(self) -> str:
        return (
            f"<slc.Scene '{self.name}': {self.triangles} triangles, {len(self.lights)} lights>"
        )


def _rebuild(recipe: Recipe) -> Scene:
    """The scene ``recipe`` describes, made again (loading its file)."""
    kind, argument, changes = recipe
    scene = {"spec": Scene, "load": Scene.load, "builtin": Scene.builtin}[kind](argument)
    for change, value in changes:
        if change == "materials":
            pattern, values = value
            scene = scene.with_materials(pattern, **values)
        elif change == "camera":
            scene = scene.with_camera(value)
        else:
            lights, replace = value
            scene = scene.with_lights(lights, replace=replace)
    return scene
