"""The package's surface against its single sources: the option table (slc/_options.py) is
what the native module takes, what help() shows and what the stubs declare; the stubs' names
of strategies are the library's; the defaults shown are the defaults used; values of the
wrong type or range are TypeError and ValueError."""

import ast
import inspect
from pathlib import Path

import numpy as np
import pytest

import slc
from slc import _options, _slc

STUB = Path(slc.__file__).with_name("__init__.pyi")
DOCUMENTED = {
    "render": [slc.render, slc.Scene.render],
    "compare": [slc.compare, slc.Scene.compare],
    "vpls": [slc.Scene.vpls],
    "light_lists": [slc.Scene.light_lists],
}
STUB_OPTIONS = {
    "render": "RenderOptions",
    "compare": "CompareOptions",
    "vpls": "FrameOptions",
    "light_lists": "ListOptions",
}


def _stub():
    return ast.parse(STUB.read_text())


def _typed_dict_keys(tree, name):
    """The keys of the TypedDict `name`, its bases' included."""
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    node = classes[name]
    keys = set()
    for base in node.bases:
        if isinstance(base, ast.Name) and base.id in classes:
            keys |= _typed_dict_keys(tree, base.id)
    keys |= {s.target.id for s in node.body if isinstance(s, ast.AnnAssign)}
    return keys


def test_the_stub_names_every_strategy_the_library_has():
    tree = _stub()
    (strategy,) = [
        n for n in tree.body if isinstance(n, ast.Assign) and n.targets[0].id == "Strategy"
    ]
    names = tuple(e.value for e in strategy.value.slice.elts)
    assert names == slc.STRATEGIES


def test_the_stub_declares_every_public_name_and_option():
    tree = _stub()
    declared = {
        n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))
    } | {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    assert set(slc.__all__) <= declared, set(slc.__all__) - declared
    for method, typed_dict in STUB_OPTIONS.items():
        assert _typed_dict_keys(tree, typed_dict) == set(_options.METHODS[method]), method


def test_the_native_module_takes_exactly_the_documented_options():
    assert {k: set(v) for k, v in _slc.OPTION_NAMES.items()} == {
        k: set(v) for k, v in _options.METHODS.items()
    }


@pytest.mark.parametrize("method", list(DOCUMENTED))
def test_help_shows_every_option_with_its_default(method):
    for f in DOCUMENTED[method]:
        parameters = inspect.signature(f).parameters
        doc = inspect.getdoc(f)
        for name in _options.METHODS[method]:
            default = _options.OPTIONS[name].default
            assert parameters[name].default == default, (f, name)
            assert parameters[name].kind is inspect.Parameter.KEYWORD_ONLY
            assert f"{name}={default!r}: " in doc, (f, name)
        assert "{options}" not in doc


def test_the_defaults_shown_are_the_defaults_used():
    implicit = slc.render(width=24, height=16)
    defaults = {o.name: o.default for o in _options.OPTIONS.values()}
    explicit = slc.render(**dict(defaults, width=24, height=16))
    np.testing.assert_array_equal(implicit.total, explicit.total)
    # What a run measured (times, peak memory) differs from run to run; the estimate does not.
    drop = {"timings_ms", "provenance", "memory"}
    strip = lambda r: {k: v for k, v in r.items() if k not in drop}  # noqa: E731
    assert strip(implicit.report) == strip(explicit.report)
    estimate = lambda r: r["memory"]["estimate_bytes"]  # noqa: E731
    assert estimate(implicit.report) == estimate(explicit.report)
    vsgl = dict(width=24, height=16, shader="vsgl")
    a, b = slc.render(**vsgl), slc.render(**dict(defaults, **vsgl))
    assert strip(a.report) == strip(b.report)


@pytest.mark.parametrize(
    "options, error, message",
    [
        (dict(width=-1), ValueError, "width: -1 is outside"),
        (dict(width=2**32), ValueError, "width"),
        (dict(width=True), TypeError, "width: expected an int, got bool"),
        (dict(width=64.0), TypeError, "width: expected an int, got float"),
        (dict(seed=np.int64(3), width=8, height=8), None, None),
        (dict(delta="0.1"), TypeError, "delta: expected a number"),
        (dict(delta=True), TypeError, "delta: expected a number"),
        (dict(denoise=1), TypeError, "denoise: expected a bool"),
        (dict(culling=["sphere"]), TypeError, "culling: expected a str"),
        (dict(backend=None), TypeError, "backend: expected a value, got None"),
        (dict(progress="yes"), TypeError, "progress: expected True, False, None or a callable"),
        (dict(lobes="all"), ValueError, "lobes: 'all' is not one of both, diffuse, glossy"),
    ],
)
def test_wrong_types_and_ranges_are_type_and_value_errors(options, error, message):
    if error is None:
        assert slc.render(**options).report["seed"] == 3
        return
    with pytest.raises(error, match=message):
        slc.render(**options)


def test_compare_wants_a_list_of_strategies():
    with pytest.raises(TypeError, match=r"a list of strategy names such as \['sphere'\]"):
        slc.compare(culling="sphere", width=8, height=8)
    with pytest.raises(ValueError, match="octree"):
        slc.compare(culling=["octree"], width=8, height=8)
    frames = slc.compare(culling=("sphere",), reference=False, width=8, height=8, rsm=4)
    assert list(frames) == ["sphere"]
