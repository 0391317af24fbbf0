"""Synthesis runs with the GIL released: Python threads run alongside, and sessions used from
four threads at once give exactly what they give one at a time.

The evidence is an ordering, not a duration (the machine is shared; no wall-clock time or
ratio is asserted): a counter thread stamps time.perf_counter() while the main thread records
t0 and t1 around one long native call. A stamp needs the GIL, so with the GIL held for the
whole call no stamp can fall inside the call; the only stamps inside [t0, t1] are then those
of the moments before the call starts and after it returns (at most a switch interval each).
The tests count stamps in the interior of the window (its middle 80 %) and ask for a few:
with the GIL held that count is 0 whatever the load, and the call is made long (>= 100 ms on
an idle core, longer under load) so that the 10 % margins dwarf those moments."""
from __future__ import annotations

import contextlib
import hashlib
import threading
import time

import numpy as np

import filmgrain
from conftest import Case

# one picture of 9600x5400 4:2:0 (6.25 times 4K) through the scalar reference stages with one
# thread: about 0.13 s on an idle core (docs/PERFORMANCE.md: rdd5 ref, 4K 8-bit, 34 ms)
WIDTH, HEIGHT = 9600, 5400
MIN_INTERIOR_STAMPS = 3


FGC = Case("rdd5_352x288_420p8").frame_info(0)["params"]["fgc"]


def _session():
    return filmgrain.Session(flavour="rdd5", threads=1, reference_kernels=True)


def _apply(s, planes):
    # an SEI for every picture, so that every call synthesizes grain
    s.push_fgc_params(FGC)
    return s.apply(planes)


def _planes(w=WIDTH, h=HEIGHT):
    rng = np.random.default_rng(1)
    return [rng.integers(16, 235, (h, w), np.uint8), rng.integers(16, 240, (h // 2, w // 2), np.uint8),
            rng.integers(16, 240, (h // 2, w // 2), np.uint8)]


@contextlib.contextmanager
def _counter():
    """A thread stamping time.perf_counter() about every 0.5 ms while it holds the GIL (a
    stamp is taken by Python code, so never while another thread holds the GIL)."""
    stamps: list[float] = []
    stop = threading.Event()
    started = threading.Event()

    def run():
        started.set()
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.0005)
    t = threading.Thread(target=run, daemon=True)
    t.start()
    started.wait()
    try:
        yield stamps
    finally:
        stop.set()
        t.join()


def _interior(stamps, t0, t1):
    margin = 0.1 * (t1 - t0)
    return sum(1 for s in list(stamps) if t0 + margin < s < t1 - margin)


def _timed(call):
    t0 = time.perf_counter()
    result = call()
    t1 = time.perf_counter()
    return result, t0, t1


def test_python_runs_while_session_applies():
    s, planes = _session(), _planes()
    _apply(s, planes)  # first call: tables and pools made outside the measured window
    with _counter() as stamps:
        out, t0, t1 = _timed(lambda: _apply(s, planes))
    assert s.last_result["grain_applied"]
    assert not np.array_equal(out[0], planes[0])
    inside = _interior(stamps, t0, t1)
    assert inside >= MIN_INTERIOR_STAMPS, (
        f"{inside} counter stamps inside the middle of a {1000 * (t1 - t0):.0f} ms Session.apply "
        f"({len(stamps)} in all): the GIL was held while synthesizing")


def test_python_runs_while_rendering():
    # filmgrain.render on an array: the Boolean renderer (render_array) with the GIL released,
    # 256x256 at N = 800 with one thread (about 0.2 s on an idle core)
    rng = np.random.default_rng(2)
    plane = rng.integers(40, 220, (256, 256), np.uint8)
    opts = dict(samples=800, radius=0.1, threads=1)
    with _counter() as stamps:
        out, t0, t1 = _timed(lambda: filmgrain.render(plane, **opts))
    assert out.shape == (256, 256)
    inside = _interior(stamps, t0, t1)
    assert inside >= MIN_INTERIOR_STAMPS, (
        f"{inside} counter stamps inside the middle of a {1000 * (t1 - t0):.0f} ms render "
        f"({len(stamps)} in all): the GIL was held while rendering")


def _digest(planes):
    # hashed through the array's own buffer: tobytes() would copy 78 MB holding the GIL (about
    # 0.25 s here), and four threads doing that one after another starve the counter for longer
    # than a whole native call; OpenSSL's update releases the GIL on large buffers
    m = hashlib.md5()
    for p in planes:
        m.update(memoryview(np.ascontiguousarray(p)).cast("B"))
    return m.hexdigest()


def test_four_threads_at_once_match_one_at_a_time():
    # 4 sessions, each applying 2 pictures: the outputs (their MD5s, in call
    # order) equal those of one session used alone, and every one of the 8 native calls
    # leaves room for the counter thread in the middle of its window (the MD5s are taken in the
    # worker threads too, so they must not hold the GIL for long: see _digest)
    calls = 2
    planes = _planes()

    def outputs(windows=None):
        s = _session()
        digests = []
        for _ in range(calls):
            out, t0, t1 = _timed(lambda: _apply(s, planes))
            digests.append(_digest(out))
            if windows is not None:
                windows.append((t0, t1))
        return digests

    serial = outputs()
    assert len(set(serial)) == calls  # the picture ids differ, so do the outputs
    results = [None] * 4
    windows = [[] for _ in range(4)]

    def run(i):
        results[i] = outputs(windows[i])
    with _counter() as stamps:
        threads = [threading.Thread(target=run, args=(i,)) for i in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    for r in results:
        assert r == serial
    counts = [_interior(stamps, t0, t1) for w in windows for t0, t1 in w]
    assert len(counts) == 4 * calls
    assert min(counts) >= MIN_INTERIOR_STAMPS, f"counter stamps inside each call's window: {counts}"
