"""Progress as a Python library shows it: a callback gets (done, total) pixel-passes on the
calling thread, rising to the total; progress=True draws tqdm's bar where tqdm is installed
(tqdm.auto: a widget in Jupyter) and a line on sys.stderr (which Jupyter shows) where not."""

import sys
import types

import pytest

import slc

SMALL = dict(width=40, height=30, rsm=8)


def test_a_callback_sees_the_pixel_passes_rise_to_the_total():
    calls = []
    slc.render(**SMALL, spp=3, progress=lambda done, total: calls.append((done, total)))
    assert calls, "called at least once"
    totals = {total for _, total in calls}
    assert totals == {40 * 30 * 3}
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[-1] == 40 * 30 * 3


def test_compare_counts_every_frame_it_shades():
    calls = []
    slc.compare(
        culling=["sphere", "ellipsoid"],
        **SMALL,
        progress=lambda done, total: calls.append((done, total)),
    )
    assert calls[-1] == (40 * 30 * 3, 40 * 30 * 3), "two strategies and the reference"


class _FakeTqdm:
    bars = []

    def __init__(self, total, **kwargs):
        self.total, self.n, self.closed, self.kwargs = total, 0, False, kwargs
        _FakeTqdm.bars.append(self)

    def update(self, n):
        self.n += n

    def close(self):
        self.closed = True


def test_progress_true_draws_tqdms_bar_where_it_is_installed(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm.auto", types.SimpleNamespace(tqdm=_FakeTqdm))
    _FakeTqdm.bars.clear()
    slc.render(**SMALL, progress=True)
    (bar,) = _FakeTqdm.bars
    assert (bar.n, bar.total, bar.closed) == (1200, 1200, True)
    assert "cornell-glossy" in bar.kwargs["desc"]


def test_progress_true_writes_a_line_on_stderr_without_tqdm(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # import fails
    slc.render(**SMALL, progress=True)
    err = capsys.readouterr().err
    assert "rendering cornell-glossy: 100% (1200/1200)" in err and err.endswith("\n")


def test_no_progress_prints_nothing(capsys):
    slc.render(**SMALL)
    slc.render(**SMALL, progress=None)
    assert capsys.readouterr() == ("", "")


def test_progress_must_be_a_flag_or_a_callable():
    with pytest.raises(TypeError, match="progress"):
        slc.render(**SMALL, progress=1)
