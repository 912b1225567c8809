"""``slc.sweep``: one render per point of a grid of options, here or on an existing engine (a
Ray cluster, or any ``concurrent.futures.Executor``: a process pool, Dask's), one row per
point with its settings, timings, metrics and provenance.

Each point is one task: the scene's recipe (how it was loaded and changed; files by absolute
path, which must exist where the task runs), the point's options and whether to return the
images. A worker keeps the scenes it loaded, so the points of one scene load it once per
worker. Every way of running gives the same rows in the same order (grid order), timings and
the per-process parts of the provenance aside."""

import concurrent.futures
import itertools
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

from ._options import METHODS, complete
from ._progress import Reporter
from ._scene import Recipe, Scene, _rebuild

#: Grid keys beyond the options of ``render``: scenes, and material overrides (dicts of
#: ``Scene.with_materials``' arguments with ``pattern``, or ``None``).
SCENE_KEYS = ("scene", "materials")

# Scenes a worker process loaded, by recipe; the last few are kept.
_SCENES: Dict[str, Scene] = {}
_KEPT_SCENES = 4

Task = Tuple[Recipe, Optional[Dict[str, Any]], Dict[str, Any], bool]


def sweep(
    scene: Any,
    grid: Dict[str, Sequence[Any]],
    executor: Any = None,
    *,
    images: bool = False,
    progress: Any = False,
    **options: Any,
) -> List[Dict[str, Any]]:
    """Renders ``scene`` at every point of ``grid`` and returns one dict per point, in grid
    order (the first key varies slowest).

    scene: a ``Scene``, a file path or a built-in name (``None``: the built-in default).
    grid: a dict from name to a list of values: the options of ``slc.render`` (e.g.
        ``{"culling": ["sphere", "ellipsoid"], "delta": [1e-4, 1e-3, 1e-2]}``), ``"scene"``
        (scenes, replacing ``scene``) and ``"materials"`` (overrides: dicts of
        ``Scene.with_materials``' arguments with ``"pattern"``, or ``None``; e.g. a roughness
        axis ``[{"pattern": "copper", "alpha": a} for a in (0.01, 0.1, 1)]``).
    executor: ``None`` renders here, one point after another; ``"ray"`` submits one Ray task
        per point (to the cluster ``ray.init(address=...)`` connected to; without it Ray
        starts a local one); a ``concurrent.futures.Executor`` (a thread pool, a process pool
        whose processes are spawned, not forked from one that rendered, or Dask's
        ``client.get_executor()``) gets one ``submit`` per point. slc must be installed and
        the scene files found at the same absolute paths where the tasks run.
    images: also return each point's ``direct``, ``indirect`` and ``total`` images (H×W×3
        float32 arrays) under ``"images"``.
    progress: ``True`` for a bar over the points (tqdm's if installed), a callable
        ``progress(done, total)``, or ``False``.
    options: the options of ``slc.render`` every point shares (a name may not be both here
        and in ``grid``).

    Each row holds ``point`` (the grid's values at it), ``scene`` (its name),
    ``scene_sha256``, ``settings`` (every option of the render), ``vpl_count``,
    ``timings_ms``, ``metrics``, ``image_means``, ``warnings`` and ``provenance``, as the
    frame's report has them. Ctrl-C cancels the points not yet done and raises
    ``KeyboardInterrupt``.
    """
    points = _points(grid, options)
    tasks = [_task(scene, point, options, images) for point in points]
    with Reporter(progress, f"sweeping {len(tasks)} points", unit=" points") as r:
        results = _run(tasks, executor, r.callback)
    return [dict(point=_shown(point), **row) for point, row in zip(points, results)]


def _points(grid: Dict[str, Sequence[Any]], options: Dict[str, Any]) -> List[Dict[str, Any]]:
    """The grid's points, checked: known names, lists of values, none also in ``options``."""
    if not isinstance(grid, dict) or not grid:
        raise TypeError("grid: expected a dict from option names to lists of values")
    known = METHODS["render"] + SCENE_KEYS
    for name, values in grid.items():
        if name not in known:
            raise TypeError(f"grid: unknown name '{name}'; the names are {', '.join(known)}")
        if name in options:
            raise TypeError(f"'{name}' is both in the grid and an option")
        if isinstance(values, (str, bytes, dict)) or not isinstance(values, Iterable):
            raise TypeError(f"grid['{name}']: expected a list of values, got {values!r}")
        if not list(values):
            raise ValueError(f"grid['{name}'] is empty: the grid would have no point")
    complete("render", options)  # unknown options fail here, before any task
    names = list(grid)
    return [dict(zip(names, values)) for values in itertools.product(*grid.values())]


def _task(scene: Any, point: Dict[str, Any], options: Dict[str, Any], images: bool) -> Task:
    """One point as a task: the scene's recipe, its overrides and options."""
    point = dict(point)
    chosen = point.pop("scene", scene)
    materials = point.pop("materials", None)
    render_options = dict(options, **point)
    if render_options.get("progress"):
        raise TypeError("progress: give it to sweep itself (a bar over the points)")
    render_options["progress"] = False
    return (_recipe(chosen), materials, complete("render", render_options), images)


def _recipe(scene: Any) -> Recipe:
    """How to make ``scene`` anywhere: its recipe, with a file named by its absolute path."""
    if not isinstance(scene, Scene):
        spec = "default" if scene is None else str(scene)
        scene = ("spec", spec, ())
    else:
        scene = scene._recipe
    kind, argument, changes = scene
    if kind != "builtin" and Path(argument).exists():
        argument = str(Path(argument).resolve())
    return (kind, argument, changes)


def _shown(point: Dict[str, Any]) -> Dict[str, Any]:
    """The point as a row shows it: a scene by its name or path."""
    shown = dict(point)
    if isinstance(shown.get("scene"), Scene):
        shown["scene"] = shown["scene"].source or shown["scene"].name
    if isinstance(shown.get("scene"), Path):
        shown["scene"] = str(shown["scene"])
    return shown


def _run(tasks: List[Task], executor: Any, report: Any) -> List[Dict[str, Any]]:
    if executor is None:
        rows = []
        for task in tasks:
            rows.append(run_point(task))
            if report:
                report(len(rows), len(tasks))
        return rows
    if executor == "ray":
        return _run_on_ray(tasks, report)
    if isinstance(executor, concurrent.futures.Executor):
        return _run_on_executor(tasks, executor, report)
    raise TypeError(
        "executor: expected None, 'ray' or a concurrent.futures.Executor (for Dask:"
        f" client.get_executor()), got {executor!r}"
    )


def _run_on_executor(tasks: List[Task], executor: Any, report: Any) -> List[Dict[str, Any]]:
    futures = [executor.submit(run_point, task) for task in tasks]
    try:
        done = 0
        for _ in concurrent.futures.as_completed(futures):
            done += 1
            if report:
                report(done, len(futures))
        return [f.result() for f in futures]
    except BaseException:
        for f in futures:
            f.cancel()
        raise


def _run_on_ray(tasks: List[Task], report: Any) -> List[Dict[str, Any]]:
    try:
        import ray
    except ImportError as e:
        raise ImportError("executor='ray' needs Ray: pip install ray") from e
    remote = ray.remote(run_point)
    refs = [remote.remote(task) for task in tasks]
    try:
        pending = list(refs)
        while pending:
            ready, pending = ray.wait(pending, num_returns=1)
            if report:
                report(len(refs) - len(pending), len(refs))
        return ray.get(refs)
    except BaseException:
        for ref in refs:
            ray.cancel(ref, force=True)
        raise


def _cached(key: str, make: Any) -> Scene:
    """The scene this worker keeps under ``key``, made by ``make()`` the first time."""
    scene = _SCENES.get(key)
    if scene is None:
        scene = make()
        if len(_SCENES) >= _KEPT_SCENES:
            _SCENES.pop(next(iter(_SCENES)))
        _SCENES[key] = scene
    return scene


def run_point(task: Task) -> Dict[str, Any]:
    """Renders one point (in the process that runs the task) and returns its row."""
    recipe, materials, options, images = task
    scene = _cached(repr(recipe), lambda: _rebuild(recipe))
    if materials is not None:
        values = dict(materials)
        pattern = values.pop("pattern")
        base = scene
        scene = _cached(
            repr((recipe, materials)), lambda: base.with_materials(pattern, **values)
        )
    frame = scene.render(**options)
    report = frame.report
    row = {
        "scene": report["scene"],
        "scene_sha256": report["provenance"]["scene_sha256"],
        "settings": {k: v for k, v in options.items() if k != "progress"},
        "vpl_count": report["vpl_count"],
        "timings_ms": report["timings_ms"],
        "metrics": report["metrics"],
        "image_means": report["image_means"],
        "warnings": report["warnings"],
        "provenance": report["provenance"],
    }
    if images:
        row["images"] = {
            "direct": frame.direct,
            "indirect": frame.indirect,
            "total": frame.total,
        }
    return row
