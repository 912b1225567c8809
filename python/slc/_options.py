"""The keyword options of slc's calls, in one place: their names, defaults and meanings. The
signatures and docstrings of ``slc.render``, ``slc.compare``, ``Scene.render`` and the rest
are made from this table (so ``help()`` lists every option), and every call passes the
native module all of its options with these defaults filled in (the native module has no
defaults of its own; the tests check that it takes exactly these names)."""

import inspect
import textwrap
from typing import Any, Callable, Dict, NamedTuple, Sequence, Tuple


class Option(NamedTuple):
    """One keyword option: its name, default and meaning."""

    name: str
    default: Any
    doc: str


_TABLE = (
    Option("width", 512, "image width in pixels, 1 to 16384"),
    Option("height", 512, "image height in pixels, 1 to 16384"),
    Option(
        "backend",
        "cpu",
        '"cpu" or "gpu" (wgpu; on a software adapter such as lavapipe slower than the CPU)',
    ),
    Option(
        "gpu_tiled",
        None,
        'with backend="gpu": the tiled strategies culled and shaded in one pass ("one-pass",'
        ' the default) or through light lists ("lists"); the image is the same',
    ),
    Option("seed", 0, "seed of ξ, the interleaving and the jitter, 0 to 2**32 - 1"),
    Option("rsm", 64, "RSM texels per side and face, 1 to 4096 (up to two VPLs per texel)"),
    Option("lobes", "both", 'the VPLs generated: "both", "diffuse" or "glossy" lobes'),
    Option("culling", "ellipsoid", "the culling strategy, one of slc.STRATEGIES"),
    Option("delta", 1e-3, "δ of eq. (2), finite and > 0: larger culls more, with more noise"),
    Option("interleave", 8, "K of K×K interleaved sampling, 1 to 64"),
    Option("denoise", True, "filter the indirect light (cross bilateral filter)"),
    Option("visibility", False, "shadow rays between lights and pixels (VPLs: CPU only)"),
    Option(
        "spp",
        1,
        "passes averaged, each with jittered pixels and texels and new VPLs and ξ",
    ),
    Option(
        "progress",
        False,
        "True: a progress bar (tqdm's if installed, which shows in Jupyter, else a line on"
        " stderr); a callable: called as progress(done, total) with the pixel-passes"
        " finished; False or None: nothing",
    ),
    Option(
        "shader",
        "vpl",
        '"vpl" (the stochastic VPL estimate) or "vsgl" (virtual spherical Gaussian lights)',
    ),
    Option(
        "metrics",
        False,
        "measure the culling metrics by brute force (Frame.lights, Frame.fdr,"
        ' report["metrics"])',
    ),
    Option(
        "reference",
        None,
        'None, "vpl" (every VPL with p = 1) or "path" (path-traced one bounce); CPU only',
    ),
    Option("vsgls", 1024, 'with shader="vsgl": how many VSGLs, 1 to 2**24'),
    Option(
        "importance",
        "flux",
        'with shader="vsgl": the lights\' importance, "flux" or "bidirectional"',
    ),
    Option(
        "camera_vsgls",
        1024,
        'with importance="bidirectional": VSGLs estimated on the G-buffer, 1 to 2**24',
    ),
    Option(
        "vsgl_diffuse",
        "clamped",
        'with shader="vsgl": the VSGLs\' diffuse intensity, "clamped" (cosine) or "sg"'
        " (the paper's spherical Gaussian)",
    ),
)
OPTIONS: Dict[str, Option] = {o.name: o for o in _TABLE}

_FRAME = ("width", "height", "backend", "seed", "rsm", "lobes")
#: The options of each call, in the order the signatures show them.
METHODS: Dict[str, Tuple[str, ...]] = {
    "vpls": _FRAME,
    "light_lists": _FRAME + ("culling", "delta", "interleave"),
    "compare": _FRAME
    + ("gpu_tiled", "delta", "interleave", "denoise", "visibility", "progress"),
    "render": tuple(o.name for o in _TABLE),
}


def complete(method: str, options: Dict[str, Any]) -> Dict[str, Any]:
    """``options`` of ``method`` with every default filled in; an unknown name is a
    ``TypeError`` naming the options there are."""
    names = METHODS[method]
    unknown = [k for k in options if k not in names]
    if unknown:
        raise TypeError(
            f"unknown option '{unknown[0]}' here; the options are {', '.join(names)}"
        )
    return {name: options.get(name, OPTIONS[name].default) for name in names}


def parameters_doc(method: str) -> str:
    """The "Parameters" lines of ``method``'s keyword options."""
    return "\n".join(
        textwrap.fill(
            f"{name}={OPTIONS[name].default!r}: {OPTIONS[name].doc}",
            width=92,
            initial_indent=" " * 8,
            subsequent_indent=" " * 12,
        )
        for name in METHODS[method]
    )


def document(
    method: str,
    leading: Sequence[inspect.Parameter] = (),
    returns: Any = inspect.Signature.empty,
) -> Callable[[Callable], Callable]:
    """A decorator giving a function taking ``**options`` the signature and docstring of
    ``method``'s options: its own docstring's ``{options}`` is replaced by one line per
    option, and its signature lists ``leading`` then every option as keyword-only with its
    default."""

    def decorate(f: Callable) -> Callable:
        keyword = [
            inspect.Parameter(n, inspect.Parameter.KEYWORD_ONLY, default=OPTIONS[n].default)
            for n in METHODS[method]
        ]
        f.__signature__ = inspect.Signature(
            list(leading) + keyword, return_annotation=returns
        )
        f.__doc__ = (f.__doc__ or "").replace("{options}", parameters_doc(method))
        return f

    return decorate
