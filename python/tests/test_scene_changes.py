"""Camera and lights from Python: read as settings-file tables, set from dicts (numpy values
too) with the settings file's checks, changing the image and the scene's hash; scenes pickle
as their recipe."""

import pickle
from pathlib import Path

import numpy as np
import pytest

import slc

SMALL = dict(width=48, height=32, rsm=8)
REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def scene():
    return slc.Scene.builtin()


def test_camera_and_lights_read_as_settings_tables(scene):
    camera = scene.camera
    assert set(camera) == {"position", "target", "up", "yfov_deg", "znear", "zfar"}
    assert camera["yfov_deg"] == 40.0 and camera["position"] == [0.0, 1.0, 3.4]
    lights = scene.lights
    assert [light["type"] for light in lights] == ["spot", "point"]
    assert list(lights[0])[:2] == ["type", "position"]
    # What is read can be set again and gives the same scene, hash included.
    same = scene.with_camera(camera).with_lights(lights)
    assert same.camera == camera and same.lights == lights
    a = scene.render(**SMALL)
    b = same.render(**SMALL)
    np.testing.assert_allclose(a.total, b.total, rtol=1e-5, atol=1e-6)


def test_a_new_camera_and_lights_change_the_image_and_the_scene_hash(scene):
    base = scene.render(**SMALL)
    narrow = scene.with_camera(scene.camera, yfov_deg=25)
    assert narrow.camera["yfov_deg"] == 25.0 and scene.camera["yfov_deg"] == 40.0
    spot = {
        "type": "spot",
        "position": np.array([0.0, 1.9, 0.0]),
        "target": (0.0, 0.0, 0.0),
        "intensity": np.float32(30),
        "outer_cone_deg": 35,
    }
    lit = narrow.with_lights([spot])
    assert lit.lights[0]["direction"] == [0.0, -1.0, 0.0] and len(lit.lights) == 1
    assert len(narrow.with_lights([spot], replace=False).lights) == 3
    assert any("camera set from Python" in w for w in lit.warnings)
    frame = lit.render(**SMALL)
    assert not np.array_equal(frame.total, base.total)
    sha = frame.report["provenance"]["scene_sha256"]
    assert sha != base.report["provenance"]["scene_sha256"]
    assert narrow.render(**SMALL).report["provenance"]["scene_sha256"] not in (
        sha,
        base.report["provenance"]["scene_sha256"],
    )


@pytest.mark.parametrize(
    "camera, message",
    [
        (dict(position=[0, 0, 1], target=[0, 0, 1], yfov_deg=40), "target equals position"),
        (dict(position=[0, 0, 1], target=[0, 0, 0]), "missing field `yfov_deg`"),
        (dict(position=[0, 0, 1], target=[0, 0, 0], yfov_deg=190), "yfov_deg 190"),
        (dict(position=[0, 0, 1], target=[0, 0, 0], yfov_deg=40, fov=3), "unknown field `fov`"),
        (dict(position=[0, np.nan, 1], target=[0, 0, 0], yfov_deg=40), "not finite"),
        (dict(position=[0, 0, 1], target=[0, 0, 0], yfov_deg=40, znear=2, zfar=1), "znear"),
    ],
)
def test_cameras_are_checked_as_in_a_settings_file(scene, camera, message):
    with pytest.raises(ValueError, match=message):
        scene.with_camera(camera)


@pytest.mark.parametrize(
    "light, error, message",
    [
        ({"type": "point", "position": [0, 1, 0], "intensty": 1}, ValueError, "unknown field `intensty`"),
        ({"type": "area", "position": [0, 1, 0]}, ValueError, "unknown variant `area`"),
        ({"type": "spot", "position": [0, 1, 0], "intensity": 1}, ValueError, "exactly one of"),
        ({"type": "point", "position": [0, 1, 0], "intensity": -1}, ValueError, "intensity"),
        ({"type": "point", "position": [0, 1, 0], "intensity": "bright"}, ValueError, "three numbers"),
        ({"type": "point", "position": [0, 1, 0], "intensity": object()}, TypeError, "object"),
        ("a point light", TypeError, "expected a dict"),
    ],
)
def test_lights_are_checked_as_in_a_settings_file(scene, light, error, message):
    with pytest.raises(error, match=message):
        scene.with_lights([light])


def test_no_light_is_refused(scene):
    with pytest.raises(ValueError, match="without light"):
        scene.with_lights([])


def test_scenes_pickle_as_their_recipe(scene):
    changed = (
        scene.with_materials("copper", alpha=0.05)
        .with_camera(scene.camera, yfov_deg=30)
        .with_lights([{"type": "point", "position": [0, 1.5, 0], "intensity": 3}])
    )
    back = pickle.loads(pickle.dumps(changed))
    assert (back.camera, back.lights, back.name) == (changed.camera, changed.lights, changed.name)
    np.testing.assert_array_equal(back.render(**SMALL).total, changed.render(**SMALL).total)
    loaded = slc.Scene.load(REPO / "scenes/materials/materials.gltf")
    back = pickle.loads(pickle.dumps(loaded))
    assert back.source == loaded.source and back.files == loaded.files
    assert [f.name for f in loaded.files] == [
        "materials.gltf",
        "materials.bin",
        "ridges_normal.png",
        "holes_color.png",
    ]
