"""A Frame shows itself (``_repr_png_``, what Jupyter displays) and saves itself: a PNG of a
layer in sRGB, or every layer with the metrics and the provenance in one EXR; a file is
written completely or not at all."""

import io
import json
import struct

import numpy as np
import pytest

import slc

SMALL = dict(width=40, height=30, rsm=8)


@pytest.fixture(scope="module")
def frame():
    return slc.render(**SMALL, metrics=True)


def _png(data: bytes):
    """Width, height and pixels of a PNG (Pillow comes with matplotlib)."""
    from PIL import Image

    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    image = Image.open(io.BytesIO(data))
    assert image.mode == "RGB"
    return image.width, image.height, np.asarray(image)


def _srgb(linear):
    c = np.clip(linear, 0, 1)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def test_the_preview_is_the_total_in_srgb(frame):
    w, h, pixels = _png(frame._repr_png_())
    assert (w, h) == (40, 30)
    want = np.round(_srgb(frame.total) * 255)
    assert np.abs(pixels.astype(float) - want).max() <= 1


def test_png_saves_a_layer_at_an_exposure(frame, tmp_path):
    path = tmp_path / "indirect.PNG"
    frame.save(path, layer="indirect", exposure=1.0)
    w, h, pixels = _png(path.read_bytes())
    want = np.round(_srgb(frame.indirect * 2.0) * 255)
    assert (w, h) == (40, 30) and np.abs(pixels.astype(float) - want).max() <= 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["indirect.PNG"], "no file left over"


def test_exr_holds_every_layer_the_metrics_and_the_provenance(frame, tmp_path):
    path = tmp_path / "frame.exr"
    frame.save(str(path))
    data = path.read_bytes()
    assert data[:4] == b"\x76\x2f\x31\x01", "OpenEXR magic number"
    for name in (b"direct", b"indirect", b"total", b"metrics", b"lights", b"fdr"):
        assert name in data, name
    # A header attribute: name, type, byte count, value.
    key = b"slc.provenance\x00string\x00"
    at = data.index(key) + len(key)
    (size,) = struct.unpack("<i", data[at : at + 4])
    provenance = json.loads(data[at + 4 : at + 4 + size])
    assert provenance == frame.report["provenance"]


def test_bad_saves_are_errors_and_leave_nothing(frame, tmp_path):
    with pytest.raises(ValueError, match=r"\.png or \.exr"):
        frame.save(tmp_path / "a.jpg")
    with pytest.raises(ValueError, match="every layer"):
        frame.save(tmp_path / "a.exr", layer="total")
    with pytest.raises(ValueError, match="direct, indirect, total"):
        frame.save(tmp_path / "a.png", layer="lights")
    with pytest.raises(FileNotFoundError, match="missing"):
        frame.save(tmp_path / "missing" / "a.png")
    assert list(tmp_path.iterdir()) == []
    # An existing file is replaced whole.
    target = tmp_path / "a.png"
    target.write_bytes(b"old")
    frame.save(target)
    assert target.read_bytes()[:4] == b"\x89PNG" and len(list(tmp_path.iterdir())) == 1
