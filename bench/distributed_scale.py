#!/usr/bin/python3
"""Throughput of python3 -m filmgrain.distributed with 1 and 2 local workers (docs/SCALE.md).
Runs render / apply / analyze on clips it makes, alternating 1 and 2 workers, and prints the
median and range of each, and the same-run speed-up. Not a test: no time is asserted.

    PYTHONPATH=build/python /usr/bin/python3 bench/distributed_scale.py [repeats]

With --analyze-cost it measures instead the CPU time `filmgrain analyze` spends per analysed
picture (docs/SCALE.md, cost per frame), on clips made as tests/python/test_distributed.py
makes its 3-scene analyze clip:

    PYTHONPATH=build/python /usr/bin/python3 bench/distributed_scale.py --analyze-cost [repeats]
"""
import json
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import os

import numpy as np

from filmgrain import distributed

TOOL = os.environ.get("FILMGRAIN_TOOL", "build/filmgrain")


def y4m(path, w, h, n, seed=0):
    rng = np.random.default_rng(seed)
    with open(path, "wb") as f:
        f.write(f"YUV4MPEG2 W{w} H{h} F25:1 Ip A1:1 C420jpeg\n".encode())
        for k in range(n):
            f.write(b"FRAME\n" + rng.integers(30, 220, (h, w), np.uint8).tobytes()
                    + np.full((h // 2, w // 2), 128, np.uint8).tobytes() * 2)


def scenes_y4m(path, w, h, n, seed=3, scenes=3):
    # tests/python/test_distributed.py's clip(): a gradient per scene, a little noise
    rng = np.random.default_rng(seed)
    xx, yy = np.meshgrid(np.arange(w), np.arange(h))
    with open(path, "wb") as f:
        f.write(f"YUV4MPEG2 W{w} H{h} F25:1 Ip A1:1 C420jpeg\n".encode())
        for k in range(n):
            s = k * scenes // n
            base = (40 + 60 * s + 0.5 * (xx + 2 * k) % 120 + 0.3 * yy).clip(16, 235)
            y = (base + rng.normal(0, 1, (h, w))).clip(0, 255).astype(np.uint8)
            f.write(b"FRAME\n" + y.tobytes() + np.full((h // 2, w // 2), 100 + 20 * s, np.uint8).tobytes()
                    + np.full((h // 2, w // 2), 150 - 10 * s, np.uint8).tobytes())


def child_cpu(cmd):
    """User + system CPU seconds of one child process (all its threads)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def analyze_cost(repeats):
    # the test's grain: one AV1 set of libaom's test vectors, a new seed per picture; analysed
    # with --frame-step 2 (the test's), so n frames give n / 2 analysed pictures. The cost per
    # analysed picture is the slope between a clip of n and one of m frames (the same content
    # generator): process start, reading the parameters and the one fit cancel out.
    import filmgrain
    d = tempfile.mkdtemp(prefix="fg-analyze-")
    first = filmgrain.params.read("conformance/av1_tv01_176x144_420p8/case.json")["frames"][0]
    for w, h, n, m in ((128, 96, 24, 120), (1920, 1080, 8, 16)):
        clips = {}
        for frames in (n, m):
            sets = []
            for k in range(frames):
                f = json.loads(json.dumps(first))
                f["av1"]["grain_seed"] = 1000 + 37 * k
                sets.append(f)
            with open(f"{d}/grain{frames}.json", "w") as fh:
                json.dump({"frames": sets}, fh)
            scenes_y4m(f"{d}/clean{frames}.y4m", w, h, frames)
            subprocess.run([TOOL, "apply", "-i", f"{d}/clean{frames}.y4m", "-o", f"{d}/grainy{frames}.y4m",
                            "--params", f"{d}/grain{frames}.json", "-q"], check=True)
            clips[frames] = f"{d}/grainy{frames}.y4m"
        for model in ("av1", "fgc"):
            per, whole = [], []
            for _ in range(repeats):
                cpu = {frames: child_cpu([TOOL, "analyze", path, "--model", model, "-o", f"{d}/p.json",
                                          "--frame-step", "2", "-q"]) for frames, path in clips.items()}
                per.append((cpu[m] - cpu[n]) / ((m - n) // 2))
                whole.append(cpu[n] / (n // 2))
            print(f"analyze --model {model} {w}x{h}, --frame-step 2: CPU per analysed picture (slope {n} -> {m} "
                  f"frames) median {1000 * statistics.median(per):.1f} ms [{1000 * min(per):.1f}, "
                  f"{1000 * max(per):.1f}]; whole process of {n} frames / {n // 2} pictures "
                  f"{1000 * statistics.median(whole):.1f} ms [{1000 * min(whole):.1f}, {1000 * max(whole):.1f}]")


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--analyze-cost":
        analyze_cost(int(sys.argv[2]) if len(sys.argv) > 2 else 5)
        return
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    d = tempfile.mkdtemp(prefix="fg-scale-")
    y4m(f"{d}/render.y4m", 256, 256, 4)
    y4m(f"{d}/apply.y4m", 1920, 1080, 60, seed=1)
    sei = "conformance/rdd5_352x288_420p8/frame0.fgc.bin"
    jobs = {
        "render 4 x 256x256, N=800, whole frames": (distributed.render_job,
                                                   [f"{d}/render.y4m", "-o", f"{d}/r.y4m", "--samples", "800",
                                                    "--threads", "1", "-q"], {"tile": 256}),
        "render 4 x 256x256, N=800, 128-pixel tiles": (distributed.render_job,
                                                      [f"{d}/render.y4m", "-o", f"{d}/r.y4m", "--samples", "800",
                                                       "--threads", "1", "-q"], {"tile": 128}),
        "apply 60 x 1080p rdd5": (distributed.apply_job,
                                  ["-i", f"{d}/apply.y4m", "-o", f"{d}/a.y4m", "--sei", sei, "--threads", "1", "-q"],
                                  {"frames_per_task": 8}),
    }
    from distributed import Client, LocalCluster
    clients = {n: Client(LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None))
               for n in (1, 2)}
    for name, (fn, args, kw) in jobs.items():
        times = {1: [], 2: []}
        for _ in range(repeats):
            for n in (1, 2):
                t0 = time.perf_counter()
                fn(args, clients[n], **kw)
                times[n].append(time.perf_counter() - t0)
        ratios = [a / b for a, b in zip(times[1], times[2])]
        print(f"{name}: 1 worker median {statistics.median(times[1]):.2f} s "
              f"[{min(times[1]):.2f}, {max(times[1]):.2f}], 2 workers {statistics.median(times[2]):.2f} s "
              f"[{min(times[2]):.2f}, {max(times[2]):.2f}], speed-up median {statistics.median(ratios):.2f} "
              f"[{min(ratios):.2f}, {max(ratios):.2f}]")
    t0 = time.perf_counter()
    subprocess.run([TOOL, "render", f"{d}/render.y4m", "-o", f"{d}/cli.y4m", "--samples", "800", "--threads", "1", "-q"],
                   check=True)
    print(f"filmgrain render (one process, 1 thread): {time.perf_counter() - t0:.2f} s")


if __name__ == "__main__":
    main()
