"""The slc Python package as a script would use it: arrays in the right shapes and types,
reports, scenes kept between calls, compare's metrics, VPLs and light lists that agree with
the renderer, errors as exceptions, the GIL released while working, the example script."""

import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import slc

SMALL = dict(width=32, height=24, rsm=8)
REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def scene():
    return slc.Scene.builtin("default")


def test_render_gives_hxwx3_float32_images_and_the_report():
    f = slc.render(width=64, height=48)
    for image in (f.direct, f.indirect, f.total):
        assert image.shape == (48, 64, 3) and image.dtype == np.float32
        assert np.isfinite(image).all()
    assert f.indirect.max() > 0 and f.direct.max() > 0
    np.testing.assert_allclose(f.total, f.direct + f.indirect, rtol=1e-6)
    r = f.report
    assert (r["width"], r["height"], r["scene"]) == (64, 48, "cornell-glossy")
    assert r["culling"] == "ellipsoid" and r["delta"] == pytest.approx(1e-3)
    assert r["interleave"] == 8 and r["backend"] == "cpu" and r["shader"] == "vpl"
    assert r["provenance"]["schema_version"] == 5
    assert r["timings_ms"]["shading"] > 0
    assert f.lights is None and f.fdr is None, "no metrics unless asked"


def test_a_scene_renders_many_times_deterministically():
    scene = slc.Scene.builtin()
    assert scene.loads == 0
    a = scene.render(**SMALL, seed=3)
    b = scene.render(**SMALL, seed=3)
    np.testing.assert_array_equal(a.indirect, b.indirect)
    c = scene.render(**SMALL, seed=4)
    assert not np.array_equal(a.indirect, c.indirect), "the seed changes ξ"
    assert scene.loads == 1, "the BVH is built once, however many frames are rendered"


def test_compare_gives_every_strategy_with_metrics_and_misses_nothing(scene):
    frames = scene.compare(culling=["none", "sphere", "ellipsoid"], **SMALL, interleave=2)
    assert set(frames) == {"reference_vpl", "none", "sphere", "ellipsoid"}
    for name in ("none", "sphere", "ellipsoid"):
        f = frames[name]
        assert f.lights.shape == (24, 32) and f.lights.dtype == np.uint32
        assert f.fdr.shape == (24, 32) and ((f.fdr >= 0) & (f.fdr <= 1)).all()
        m = f.report["metrics"]
        assert m["missed_pairs"] == 0
        assert m["lights_per_pixel_mean"] == pytest.approx(f.lights.mean())
    assert frames["none"].lights.sum() >= frames["sphere"].lights.sum()
    assert frames["sphere"].lights.sum() >= frames["ellipsoid"].lights.sum()
    # Same VPLs and ξ: every strategy's estimate equals the unculled one.
    for name in ("sphere", "ellipsoid"):
        np.testing.assert_allclose(frames[name].indirect, frames["none"].indirect, atol=1e-5)
    assert frames["reference_vpl"].report["reference"] == "vpl"


def test_vpls_are_columns_of_one_row_per_vpl(scene):
    v = scene.vpls(**SMALL)
    n = len(v["alpha"])
    assert n > 0 and n == scene.render(**SMALL).report["vpl_count"]
    for key in ("position", "normal", "omega_i", "flux", "kd"):
        assert v[key].shape == (n, 3) and v[key].dtype == np.float32
    np.testing.assert_allclose(np.linalg.norm(v["normal"], axis=1), 1, atol=1e-4)
    assert ((v["xi"] > 0) & (v["xi"] < 1)).all()
    assert ((v["alpha"] > 0) & (v["alpha"] <= 1)).all()
    assert v["glossy"].dtype == np.bool_ and v["glossy"].any() and (~v["glossy"]).any()
    assert len(np.unique(v["id"])) == n


def _pixel_lists(lists):
    """Each pixel's VPL indices (row-major), from offsets, indices and the per-pixel lists:
    its own list, or with a shared list the union of both, ascending."""
    offsets, indices = lists["offsets"], lists["indices"]

    def entries(l):
        return () if l == lists["NO_LIST"] else tuple(indices[offsets[l] : offsets[l + 1]])

    return [
        entries(own) if shared == lists["NO_LIST"] else tuple(sorted(set(entries(own) + entries(shared))))
        for own, shared in zip(lists["lists"].ravel(), lists["shared"].ravel())
    ]


def test_light_lists_are_the_lists_the_renderer_shades_with(scene):
    options = dict(SMALL, delta=1e-3, interleave=2, seed=1)
    lists = scene.light_lists(**options, culling="ellipsoid")
    n = len(scene.vpls(**SMALL, seed=1)["alpha"])
    offsets, indices, per_pixel = lists["offsets"], lists["indices"], lists["lists"]
    assert per_pixel.shape == (24, 32)
    assert (np.diff(offsets.astype(np.int64)) >= 0).all() and offsets[-1] == len(indices)
    assert (indices < n).all()
    culled = _pixel_lists(lists)
    measured = scene.render(**options, culling="ellipsoid", metrics=True).lights
    np.testing.assert_array_equal([len(l) for l in culled], measured.ravel())
    # Without culling each pixel lists every VPL of its interleaving subregion: the K² = 4
    # subregions partition the VPLs, and a culled list keeps a subset of its pixel's.
    unculled = _pixel_lists(scene.light_lists(**options, culling="none"))
    subregions = {}
    for (y, x), full in zip(np.ndindex(24, 32), unculled):
        if full:
            subregions.setdefault((y % 2, x % 2), set(full))
            assert set(full) == subregions[(y % 2, x % 2)]
    members = [i for s in subregions.values() for i in s]
    assert len(subregions) == 4 and sorted(members) == list(range(n))
    assert all(set(c) <= set(f) for c, f in zip(culled, unculled))
    assert sum(map(len, culled)) < sum(map(len, unculled))
    assert (lists["shared"] == lists["NO_LIST"]).all()
    # binned shares the VPLs whose rectangles exceed a tile (16² pixels of a subregion
    # image) per cell: a frame without interleaving where such ranges occur.
    wide = dict(width=96, height=72, rsm=8, delta=1e-3, interleave=1, seed=1)
    binned = scene.light_lists(**wide, culling="binned")
    assert (binned["shared"] != binned["NO_LIST"]).any()
    lights = scene.render(**wide, culling="binned", metrics=True).lights
    binned_lists = _pixel_lists(binned)
    np.testing.assert_array_equal([len(l) for l in binned_lists], lights.ravel())
    everything = _pixel_lists(scene.light_lists(**wide, culling="none"))
    assert all(set(c) <= set(f) for c, f in zip(binned_lists, everything))
    assert all(list(c) == sorted(set(c)) for c in binned_lists)


def test_vsgls_and_references():
    f = slc.render(**SMALL, shader="vsgl", vsgls=32)
    assert f.report["shader"] == "vsgl" and f.report["light_samples"] == 32
    r = slc.render(**SMALL, reference="vpl")
    assert r.report["reference"] == "vpl" and r.report["culling"] is None


def test_bad_input_raises_clear_exceptions(scene):
    with pytest.raises(TypeError, match="unknown option 'widht'"):
        scene.render(widht=3)
    with pytest.raises(TypeError, match="width"):
        scene.render(width="wide")
    with pytest.raises(ValueError, match="not one of"):
        scene.render(backend="tpu")
    with pytest.raises(ValueError, match="octree"):
        scene.render(culling="octree")
    with pytest.raises(ValueError, match="width"):
        scene.render(width=-1)
    with pytest.raises(ValueError, match="importance"):
        scene.render(importance="bogus")
    with pytest.raises(TypeError, match="unknown option 'spp'"):
        scene.compare(spp=2)
    with pytest.raises(TypeError, match="unknown option 'culling'"):
        scene.vpls(culling="sphere")
    with pytest.raises(slc.SlcError, match=r"the width must be in 1\.\.=16384 \(got 0\)"):
        scene.render(width=0)
    # The same ranges as the command line, for every count, whatever the method uses.
    with pytest.raises(slc.SlcError, match=r"spp must be in 1\.\.=65536"):
        scene.render(spp=4294967295)
    with pytest.raises(slc.SlcError, match="camera VSGLs"):
        scene.render(shader="vsgl", camera_vsgls=0)
    with pytest.raises(slc.SlcError, match="sampled lights"):
        scene.render(shader="vsgl", vsgls=0)
    with pytest.raises(slc.SlcError, match="lobes must be both"):
        scene.render(shader="vsgl", lobes="diffuse")
    with pytest.raises(slc.SlcError, match="delta"):
        scene.render(delta=float("nan"))
    with pytest.raises(slc.SlcError, match="no-such-file.gltf"):
        slc.Scene.load("no-such-file.gltf")
    with pytest.raises(slc.SlcError, match="unknown built-in scene"):
        slc.Scene.builtin("nope")
    with pytest.raises(slc.SlcError, match="memory available"):
        scene.render(width=16384, height=16384, rsm=4096)
    unlit = slc.Scene.load(REPO / "crates/core/tests/corpus/valid-sparse-positions.gltf")
    for call in (unlit.render, unlit.vpls, unlit.light_lists):
        with pytest.raises(slc.SlcError, match="no light"):
            call(**SMALL)


def test_work_releases_the_gil(scene):
    done = threading.Event()
    worker = threading.Thread(
        # Large enough to last well over the 20 ms asserted below on a fast CPU path.
        target=lambda: (scene.render(width=480, height=360, rsm=64), done.set())
    )
    ticks = 0
    start = time.perf_counter()
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    elapsed = time.perf_counter() - start
    # Holding the GIL, the render would let this loop run only before and after it.
    assert ticks > 10 and elapsed > 0.02, (ticks, elapsed)


def test_one_scene_serves_several_threads(scene):
    frames, errors = [], []

    def work(seed):
        try:
            frames.append(scene.render(width=96, height=64, rsm=16, seed=seed))
        except Exception as e:  # noqa: BLE001 - the test reports whatever went wrong
            errors.append(e)

    threads = [threading.Thread(target=work, args=(s,)) for s in range(3)]
    for t in threads:
        t.start()
    names = [scene.name for _ in range(100)]  # reading the scene while it renders
    for t in threads:
        t.join()
    assert not errors and len(frames) == 3 and set(names) == {"cornell-glossy"}


def test_the_gpu_backend_renders_the_same_frame_shape():
    try:
        f = slc.render(**SMALL, backend="gpu")
    except slc.SlcError as e:
        if "no GPU adapter" in str(e) and not os.environ.get("CI"):
            pytest.skip(str(e))
        raise
    assert f.indirect.shape == (24, 32, 3) and np.isfinite(f.total).all()
    assert f.report["backend"] == "gpu"


def test_gpu_tiled_lists_render_what_one_pass_renders():
    with pytest.raises(ValueError, match="backend='gpu'"):
        slc.render(**SMALL, gpu_tiled="lists")
    try:
        one_pass = slc.render(**SMALL, backend="gpu", culling="sphere")
    except slc.SlcError as e:
        if "no GPU adapter" in str(e) and not os.environ.get("CI"):
            pytest.skip(str(e))
        raise
    lists = slc.render(**SMALL, backend="gpu", culling="sphere", gpu_tiled="lists")
    assert np.array_equal(one_pass.indirect, lists.indirect)
    with pytest.raises(ValueError, match="gpu_tiled"):
        slc.render(**SMALL, backend="gpu", gpu_tiled="two-pass")


def test_raster_baselines_run_on_the_gpu_only():
    with pytest.raises(slc.SlcError, match="rasterization baselines"):
        slc.render(**SMALL, culling="splatting")
    assert {"splatting", "clustered-raster"} <= set(slc.STRATEGIES)
    try:
        frames = slc.compare(
            **SMALL,
            backend="gpu",
            culling=["ellipsoid", "splatting", "clustered-raster"],
            reference=False,
        )
    except slc.SlcError as e:
        if "no GPU adapter" in str(e) and not os.environ.get("CI"):
            pytest.skip(str(e))
        raise
    ours = frames["ellipsoid"]
    for name in ["splatting", "clustered-raster"]:
        m = frames[name].report["metrics"]
        assert m["missed_pairs"] == 0, name
        assert m["true_positive_pairs"] == ours.report["metrics"]["true_positive_pairs"]
        np.testing.assert_allclose(frames[name].indirect, ours.indirect, rtol=1e-3, atol=1e-7)


def test_a_scene_with_overridden_materials_is_a_new_scene(scene):
    assert "copper" in scene.materials
    sharp = scene.with_materials("copper", alpha=0.01)
    rough = scene.with_materials("cop*", roughness=1.0)
    assert sharp.loads == 0 and any("overridden" in w for w in sharp.warnings)
    assert not any("overridden" in w for w in scene.warnings), "the original is unchanged"
    options = dict(SMALL, culling=["sphere", "ellipsoid"], reference=False)
    a, b = sharp.compare(**options), rough.compare(**options)
    # A narrower lobe shrinks the ellipsoid (and the sphere with it) and changes the image.
    assert a["ellipsoid"].lights.sum() < b["ellipsoid"].lights.sum()
    assert not np.array_equal(a["ellipsoid"].indirect, b["ellipsoid"].indirect)
    assert a["ellipsoid"].report["warnings"][-1].startswith("materials 'copper' overridden")
    with pytest.raises(ValueError, match="matches no material"):
        scene.with_materials("marble", alpha=0.5)
    with pytest.raises(ValueError, match="alpha"):
        scene.with_materials("copper", alpha=0.0)
    with pytest.raises(ValueError, match="sets nothing"):
        scene.with_materials("copper")
    # An index of refraction whose square overflows f32 is refused, not rendered as NaN.
    with pytest.raises(ValueError, match="at most 1e4"):
        scene.with_materials("copper", eta=1e20)


def test_an_anisotropic_override_changes_the_image(scene):
    # The built-in meshes have no texture coordinates, so no tangents: said, not applied.
    plain = scene.with_materials("copper", anisotropy_strength=0.9)
    assert any("anisotropy is not applied" in w for w in plain.warnings)
    room = slc.Scene.load(REPO / "scenes/anisotropy/anisotropy.gltf")
    turned = room.with_materials("brushed_*", anisotropy_strength=0.9, anisotropy_rotation=0.4)
    assert any("anisotropy 0.9 at 0.4 rad" in w for w in turned.warnings)
    options = dict(SMALL, culling=["ellipsoid"], reference=False)
    a, b = turned.compare(**options), room.compare(**options)
    assert np.isfinite(a["ellipsoid"].indirect).all()
    assert not np.array_equal(a["ellipsoid"].indirect, b["ellipsoid"].indirect)
    # The culling never drops a contributing pair of the anisotropic VPLs.
    assert a["ellipsoid"].report["metrics"]["missed_pairs"] == 0
    with pytest.raises(ValueError, match="anisotropy_strength 1.5"):
        scene.with_materials("copper", anisotropy_strength=1.5)
    with pytest.raises(ValueError, match="needs anisotropy_strength"):
        scene.with_materials("copper", anisotropy_rotation=0.4)


def run_example(script, out, *args):
    """Runs python/examples/SCRIPT on a small frame with ARGS, writing OUT."""
    subprocess.run(
        [
            sys.executable,
            str(REPO / "python/examples" / script),
            "--width", "48", "--height", "32", "--rsm", "8",
            *args, "--out", str(out),
        ],
        check=True,
        env=dict(os.environ, MPLBACKEND="Agg"),
    )
    assert out.stat().st_size > 10_000


def test_the_example_sweeps_delta_and_writes_a_plot(tmp_path):
    run_example(
        "delta_sweep.py", tmp_path / "sweep.png",
        "--delta", "1e-3", "1e-2", "--culling", "ellipsoid", "sphere", "--repeat", "1",
    )


def test_the_roughness_example_writes_a_plot_and_a_table(tmp_path):
    out = tmp_path / "roughness.png"
    run_example(
        "roughness_sweep.py", out,
        "--alpha", "0.05", "0.5", "--culling", "sphere", "ellipsoid",
    )
    rows = out.with_suffix(".csv").read_text().splitlines()
    assert rows[0].startswith("alpha,strategy,") and len(rows) == 1 + 2 * 2
    assert all(r.endswith(",0") for r in rows[1:]), "no strategy misses a pair"
