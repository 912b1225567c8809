"""Progress of a call as ``progress=...`` asks: ``True`` is a bar (tqdm's ``tqdm.auto`` when
tqdm is installed, which draws a widget in Jupyter and a bar in a terminal; otherwise one line
rewritten on ``sys.stderr``, which Jupyter shows too), a callable is called as
``progress(done, total)``. The native module calls the callback on the calling thread, at
most every few tens of milliseconds."""

import sys
import time
from typing import Any, Callable, Optional


class _Line:
    """A progress line on ``sys.stderr``, rewritten at most twice a second."""

    def __init__(self, description: str):
        self.description = description
        self.shown = 0.0
        self.done = self.total = 0

    def __call__(self, done: int, total: int) -> None:
        self.done, self.total = done, total
        now = time.monotonic()
        if now - self.shown >= 0.5 or (total and done >= total):
            self.shown = now
            percent = 100 * done // total if total else 0
            sys.stderr.write(f"\r{self.description}: {percent:3d}% ({done}/{total})")
            sys.stderr.flush()

    def close(self) -> None:
        if self.shown:
            sys.stderr.write("\n")
            sys.stderr.flush()


class _Tqdm:
    """A tqdm bar driven by (done, total) pairs."""

    def __init__(self, tqdm: Any, description: str, unit: str):
        self.bar = tqdm(total=0, desc=description, unit=unit, unit_scale=True, leave=False)

    def __call__(self, done: int, total: int) -> None:
        if self.bar.total != total:
            self.bar.total = total
        self.bar.update(done - self.bar.n)

    def close(self) -> None:
        self.bar.close()


class Reporter:
    """What ``progress=value`` asks for, as a context manager: ``callback`` is ``None`` or a
    callable ``(done, total)``; a bar it made (counting ``unit``s) is closed on exit."""

    def __init__(self, value: Any, description: str, unit: str = "px"):
        self._bar: Optional[Any] = None
        self.callback: Optional[Callable[[int, int], None]] = None
        if value is True:
            self._bar = _bar(description, unit)
            self.callback = self._bar
        elif callable(value):
            self.callback = value
        elif value not in (False, None):
            raise TypeError(
                f"progress: expected True, False, None or a callable progress(done, total),"
                f" got {type(value).__name__} ({value!r})"
            )

    def __enter__(self) -> "Reporter":
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._bar is not None:
            self._bar.close()


def _bar(description: str, unit: str) -> Any:
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _Line(description)
    return _Tqdm(tqdm, description, unit)
