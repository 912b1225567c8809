"""Ctrl-C during a render: a real SIGINT raises KeyboardInterrupt within about a second on
either backend (the render would have run for minutes), the scene renders again afterwards,
and a progress callback that raises stops the render with its exception."""

import os
import subprocess
import sys
import textwrap
import time

import pytest

import slc

# A render of minutes, interrupted once it has run for a while; prints the latency.
CHILD = textwrap.dedent(
    """
    import os, signal, sys, threading, time
    import slc
    # Python raises KeyboardInterrupt on SIGINT only where SIGINT was not ignored when it
    # started; a job started in the background of a shell without job control (`cmd &` in a
    # script, as some CI runners start their steps) inherits it ignored.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    backend = sys.argv[1]
    scene = slc.Scene.builtin()
    scene.render(width=16, height=16, rsm=4, backend=backend)  # the device is opened
    # On a software GPU a dispatch cannot be interrupted: the frame is small enough that
    # each of its passes takes well under a second there.
    size = dict(width=1280, height=720, rsm=64) if backend == "cpu" else dict(width=256, height=192, rsm=32)
    long = dict(size, spp=5000, backend=backend)
    sent = []
    def interrupt():
        time.sleep(1.5)
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Thread(target=interrupt, daemon=True).start()
    try:
        scene.render(**long)
        print("not interrupted")
    except KeyboardInterrupt:
        print("latency", time.perf_counter() - sent[0])
    frame = scene.render(width=16, height=16, rsm=4, backend=backend)
    print("again", frame.total.shape)
    """
)


def _gpu_or_skip():
    try:
        slc.render(width=8, height=8, rsm=4, backend="gpu")
    except slc.SlcError as e:
        if "no GPU adapter" in str(e) and not os.environ.get("CI"):
            pytest.skip(str(e))
        raise


@pytest.mark.parametrize("backend", ["cpu", "gpu"])
def test_ctrl_c_raises_keyboard_interrupt_within_a_second(backend):
    if backend == "gpu":
        _gpu_or_skip()
    start = time.perf_counter()
    out = subprocess.run(
        [sys.executable, "-c", CHILD, backend],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    lines = dict(line.split(" ", 1) for line in out.stdout.splitlines())
    assert "latency" in lines, out.stdout
    latency = float(lines["latency"])
    assert latency < 1.0, f"{backend}: KeyboardInterrupt {latency:.2f} s after SIGINT"
    assert lines["again"] == "(16, 16, 3)"
    assert time.perf_counter() - start < 60


def test_a_progress_callback_that_raises_stops_the_render():
    class Enough(Exception):
        pass

    seen = []

    def stop(done, total):
        seen.append((done, total))
        raise Enough

    scene = slc.Scene.builtin()
    start = time.perf_counter()
    with pytest.raises(Enough):
        scene.render(width=1280, height=720, rsm=64, spp=400, progress=stop)
    assert time.perf_counter() - start < 10, "the render stopped at the first report"
    assert len(seen) == 1 and seen[0][1] == 1280 * 720 * 400
