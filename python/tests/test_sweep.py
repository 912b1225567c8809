"""slc.sweep: a grid of options rendered here, on a thread or process pool, and on a local
Ray cluster of two workers, each giving the same rows (timings and the per-process parts of
the provenance aside); grids are checked before any work."""

import concurrent.futures
import multiprocessing
import os
from pathlib import Path

import numpy as np
import pytest

import slc

REPO = Path(__file__).resolve().parents[2]
FRAME = dict(width=24, height=16, rsm=8)
GRID = {"culling": ["sphere", "ellipsoid"], "delta": [1e-3, 1e-2], "seed": [0, 1]}


def comparable(rows):
    """Rows without what differs from run to run and process to process."""
    out = []
    for row in rows:
        row = dict(row)
        row.pop("timings_ms")
        row["provenance"] = {
            k: v
            for k, v in row["provenance"].items()
            if k not in ("started_at", "command_line")
        }
        out.append(row)
    return out


@pytest.fixture(scope="module")
def local():
    return slc.sweep(None, GRID, metrics=True, **FRAME)


def test_rows_follow_the_grid_with_settings_timings_metrics_and_provenance(local):
    assert len(local) == 8
    assert [r["point"] for r in local][:3] == [
        {"culling": "sphere", "delta": 1e-3, "seed": 0},
        {"culling": "sphere", "delta": 1e-3, "seed": 1},
        {"culling": "sphere", "delta": 1e-2, "seed": 0},
    ]
    for row in local:
        assert row["settings"]["culling"] == row["point"]["culling"]
        assert row["settings"]["width"] == 24 and row["settings"]["metrics"] is True
        assert row["timings_ms"]["shading"] > 0
        assert row["metrics"]["missed_pairs"] == 0
        assert row["provenance"]["scene_sha256"] == row["scene_sha256"]
        assert row["scene"] == "cornell-glossy"
    # A larger δ culls more: fewer lights per pixel at the same seed and strategy.
    assert local[0]["metrics"]["lights_per_pixel_mean"] > local[2]["metrics"]["lights_per_pixel_mean"]


def test_a_thread_or_process_pool_gives_the_same_rows(local):
    spawn = multiprocessing.get_context("spawn")
    for pool in (
        concurrent.futures.ThreadPoolExecutor(2),
        concurrent.futures.ProcessPoolExecutor(2, mp_context=spawn),
    ):
        with pool:
            rows = slc.sweep(None, GRID, executor=pool, metrics=True, **FRAME)
        assert comparable(rows) == comparable(local), type(pool).__name__


def test_on_a_local_ray_cluster_of_two_workers_the_rows_are_the_same(local):
    try:
        import ray
    except ImportError:
        if os.environ.get("CI"):
            raise
        pytest.skip("Ray is not installed")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        rows = slc.sweep(None, GRID, executor="ray", metrics=True, **FRAME)
        workers = {
            n["NodeID"]: n["Resources"].get("CPU") for n in ray.nodes() if n["Alive"]
        }
    finally:
        ray.shutdown()
    assert list(workers.values()) == [2.0], "one node with two worker slots"
    assert comparable(rows) == comparable(local)


def test_scenes_materials_and_images_as_axes():
    materials = REPO / "scenes/materials/materials.gltf"
    rows = slc.sweep(
        None,
        {
            "scene": [slc.Scene.builtin(), str(materials)],
            "materials": [None, {"pattern": "*", "alpha": 0.5}],
        },
        images=True,
        culling="ellipsoid",
        **FRAME,
    )
    assert [r["scene"] for r in rows] == ["cornell-glossy"] * 2 + ["materials"] * 2
    assert rows[2]["point"]["scene"] == str(materials)
    assert rows[0]["scene_sha256"] != rows[1]["scene_sha256"], "the override is in the hash"
    assert rows[0]["images"]["total"].shape == (16, 24, 3)
    assert not np.array_equal(rows[0]["images"]["total"], rows[1]["images"]["total"])


def test_a_process_forked_after_work_refuses_to_render(local):
    fork = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=fork) as pool:
        with pytest.raises(slc.SlcError, match="spawn"):
            slc.sweep(None, {"seed": [0]}, executor=pool, **FRAME)


def test_progress_counts_points():
    calls = []
    slc.sweep(None, {"seed": [0, 1, 2]}, progress=lambda d, t: calls.append((d, t)), **FRAME)
    assert calls == [(1, 3), (2, 3), (3, 3)]


@pytest.mark.parametrize(
    "grid, options, error, message",
    [
        ({"culling": "sphere"}, {}, TypeError, "expected a list of values"),
        ({"widht": [1]}, {}, TypeError, "unknown name 'widht'"),
        ({"delta": []}, {}, ValueError, "empty"),
        ({"delta": [1e-3]}, {"delta": 1e-2}, TypeError, "both in the grid and an option"),
        ({"delta": [1e-3]}, {"spp2": 1}, TypeError, "unknown option 'spp2'"),
        ([("delta", [1e-3])], {}, TypeError, "grid: expected a dict"),
    ],
)
def test_bad_grids_are_refused_before_any_work(grid, options, error, message):
    with pytest.raises(error, match=message):
        slc.sweep(None, grid, **options)


def test_an_unknown_executor_is_refused():
    with pytest.raises(TypeError, match="concurrent.futures.Executor"):
        slc.sweep(None, {"seed": [0]}, executor="dask", **FRAME)
